// Mesh files checked before assimp reads them, for what its readers trust:
// PLY (scene/ply_check.h) and OFF (scene/off_check.h) files.
#pragma once

#include <filesystem>

namespace wp {

// Throws MeshFileError if the file is a PLY (its first word starts with
// "ply" in any case) that check_ply rejects, or a file assimp reads as OFF
// that check_off rejects. Other files pass unchecked.
void check_before_assimp(const std::filesystem::path& path);

}  // namespace wp
