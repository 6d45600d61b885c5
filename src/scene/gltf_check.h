// What assimp 5.2.5's glTF readers (1.0 and 2.0) trust, checked before they
// read a file: a primitive's face count is its vertex (or index) count less
// what its mode needs, in 32 bits, so a line strip of no vertices is 2^32 - 1
// faces and a 64 GB allocation (found by fuzz_mesh: a primitive whose
// "attributes" key was garbled, so it had no POSITION).
#pragma once

#include <string_view>

namespace wp {

// Throws MeshFileError unless `file` (glTF JSON, or binary glTF: a GLB of
// version 1 or 2 around its JSON) is JSON in which every mesh primitive has
// a POSITION attribute naming an accessor, and its indices' accessor if it
// has one, else its POSITION accessor, counts at least the vertices one of
// its primitives takes in its mode (1 for points, 2 for lines, 3 for
// triangles, strips and fans alike).
void check_gltf(std::string_view file);

}  // namespace wp
