// Mesh files checked before assimp reads them, for what its readers trust:
// PLY (scene/ply_check.h), OFF (scene/off_check.h) and glTF
// (scene/gltf_check.h) files.
#pragma once

#include <filesystem>

namespace wp {

// Throws MeshFileError if assimp would read the file with its PLY reader and
// check_ply rejects it, with its OFF reader and check_off rejects it, or
// with a glTF reader and check_gltf rejects it.
// Which reader is assimp's own choice, made as Importer::ReadFile makes it
// (by the extension, else by each reader's signature check). Other files
// pass unchecked.
void check_before_assimp(const std::filesystem::path& path);

}  // namespace wp
