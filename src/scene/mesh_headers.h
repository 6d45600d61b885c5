// What assimp trusts in a mesh file, checked before it reads the file: it
// allocates the element counts a PLY header declares before reading them (a
// 300-byte file claiming 2e9 vertices costs tens of GB), its PLY reader loops
// forever on some malformed headers and allocates gigabytes on a NUL byte in
// an ASCII body, and its OFF reader crashes on some malformed files
// (scene/off_check.h).
#pragma once

#include <filesystem>

namespace wp {

// Throws MeshFileError (scene/mesh_file.h) if the file is a PLY (starts with
// "ply") whose header is not as the format defines it, does not end, or
// declares more elements than the rest of the file can hold at their
// smallest encoding, or is ASCII with a NUL byte in its body; or a file
// assimp reads as OFF that check_off rejects.
// Other files pass unchecked.
void check_mesh_header(const std::filesystem::path& path);

}  // namespace wp
