// What assimp 5.2.5's PLY reader trusts, checked before it reads a file.
// Each was found by fuzz_mesh:
// - it loops forever on some header lines it does not expect;
// - it sizes a list by its count before reading the list, taking the count
//   as 32 bits whatever its type: an ASCII face line whose count is
//   8888800000000000012425 made it allocate gigabytes, and a binary count of
//   2^32 - 1 would cost 32 GB;
// - it reads an ASCII body one element a line, a line ending at \r, \n, \f
//   or NUL: a NUL in a face line's number made it allocate 15 GB.
// Element counts the body does not hold are refused too: assimp reserves
// them before reading (a 300-byte file claiming 2e9 vertices costs tens of GB).
#pragma once

#include <string_view>

namespace wp {

// Throws MeshFileError unless `file` is a PLY file as the format defines it:
// - a header of "ply", the format line, element, property, comment and
//   obj_info lines, ending at end_header within its first 64 KiB;
// - then each declared element in turn. ASCII: one a line, a number of its
//   type for each property, each list's count within its count type and the
//   words that follow it; then only blank lines. Binary: each list's count
//   within its count type and the bytes that follow it.
void check_ply(std::string_view file);

}  // namespace wp
