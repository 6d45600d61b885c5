// What assimp trusts in a mesh file's header, checked before it reads the
// file: it allocates the element counts a PLY or OFF header declares before
// reading them (a 300-byte file claiming 2e9 vertices costs tens of GB), and
// its PLY reader loops forever on some malformed headers.
#pragma once

#include <filesystem>

namespace wp {

// Throws MeshFileError (scene/mesh_file.h) if the file is a PLY (starts with
// "ply") whose header is not as the format defines it or does not end, or a
// PLY or OFF file whose header declares more elements than the rest of the
// file can hold at their smallest encoding. Other files pass unchecked.
void check_mesh_header(const std::filesystem::path& path);

}  // namespace wp
