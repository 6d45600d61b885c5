// libFuzzer target: a mesh file -> a Mesh, or the one MeshFileError, through
// the contained import (assimp in wavepath-import's process). The input is
// the file's extension, a newline, then its bytes; extensions are the
// formats docs/scene-format.md lists (wavepath refuses the others' readers).
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>

#include "import/import_process.h"
#include "import_failures.h"
#include "scene/mesh_file.h"
#include "scratch_directory.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    static const std::set<std::string> kFormats = {"obj", "ply", "off", "stl", "gltf", "glb"};
    const std::string input(reinterpret_cast<const char*>(data), size);
    const std::size_t newline = input.find('\n');
    if (newline == std::string::npos || !kFormats.contains(input.substr(0, newline))) return 0;

    static const wp::fuzz::ScratchDirectory scratch("mesh");  // where each input becomes a file (assimp reads paths)
    const std::filesystem::path file = scratch.path / ("mesh." + input.substr(0, newline));
    std::ofstream(file, std::ios::binary).write(input.data() + newline + 1, input.size() - newline - 1);
    static wp::MeshImporter importer(wp::fuzz::kImportLimits);  // one helper for the run, as for a scene
    try {
        wp::read_mesh_file(file, wp::MeshFileOptions{}, importer);
    } catch (const wp::ImportProcessError& error) {
        wp::fuzz::note_import_failure(error.what(), data, size);
    } catch (const wp::MeshFileError&) {
    }
    std::filesystem::remove(file);
    return 0;
}
