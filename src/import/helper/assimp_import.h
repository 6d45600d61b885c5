// A mesh file read by assimp in this process: what wavepath-import runs for
// wavepath (import/import_process.h), and what tests and benchmarks run to
// compare the contained import with. Nothing else in wavepath calls assimp.
#pragma once

#include <filesystem>

#include "import/imported_scene.h"

namespace wp {

// The file's scene, triangulated with identical vertices joined. Only the
// readers of the documented formats may read it (OBJ, PLY, OFF, STL and
// glTF 2.0): the one assimp chooses for it is refused before it reads,
// naming it, if it is another. Throws MeshFileError.
ImportedScene import_with_assimp(const std::filesystem::path& path);

}  // namespace wp
