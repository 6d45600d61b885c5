// libFuzzer target: a glTF 2.0 file -> a Scene (load_gltf_scene: the
// contained import, then the mapping of its materials, cameras and lights),
// or the one SceneError naming the file. Anything else (another exception, a
// crash, a sanitizer report, a hang) is a finding. The input is the
// extension (gltf or glb), a newline, then the file's bytes.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>

#include "import/import_process.h"
#include "import_failures.h"
#include "scene/gltf_scene.h"
#include "scratch_directory.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string input(reinterpret_cast<const char*>(data), size);
    const std::size_t newline = input.find('\n');
    if (newline == std::string::npos) return 0;
    const std::string extension = input.substr(0, newline);
    if (extension != "gltf" && extension != "glb") return 0;

    static const wp::fuzz::ScratchDirectory scratch(
        "gltf");  // where each input becomes a file (the importer reads paths)
    const std::filesystem::path file = scratch.path / ("scene." + extension);
    std::ofstream(file, std::ios::binary).write(input.data() + newline + 1, input.size() - newline - 1);
    try {
        wp::load_gltf_scene(file.string(), wp::fuzz::kImportLimits);
    } catch (const wp::SceneError& error) {
        const std::string message = error.what();
        if (message.rfind(file.string() + ":", 0) != 0) std::abort();  // the one error names the file
        const std::string& mark = wp::fuzz::import_helper_mark();
        const std::size_t helper = message.rfind(mark);
        if (helper != std::string::npos &&
            wp::fuzz::is_process_failure(std::string_view(message).substr(helper + mark.size())))
            wp::fuzz::note_import_failure(message, data, size);
    }
    std::filesystem::remove(file);
    return 0;
}
