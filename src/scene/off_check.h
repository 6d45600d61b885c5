// What assimp 5.2.5's OFF reader trusts, checked before it reads a file. It
// reads the header as words, then one vertex and one face a line, and
// carries on with a guess when a line is not what it expects: a face line
// whose vertex count is not 1 to 9 is dropped and the face count lowered,
// below zero when such lines outnumber the faces (a wrapped count of 2^32 - 1
// faces and a crash: found by fuzz_mesh); a line of 4096 bytes or more
// overflows its line buffer; a word that is not a number reads as 0; a
// header count that does not fit the file is allocated all the same.
#pragma once

#include <string_view>

namespace wp {

// Throws MeshFileError unless `text` is an OFF file laid out as assimp reads
// it: the header's words ([ST][C][N][4][n]OFF, or none and a vertex count
// that does not begin with 4; the dimension after nOFF; the vertex, face and
// edge counts), one vertex a line (its coordinates first), one face a line
// (1 to 9 vertex indices below the vertex count, after their count), then
// only blank or comment lines.
void check_off(std::string_view text);

}  // namespace wp
