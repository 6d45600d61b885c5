// libFuzzer target: JSON text -> a Scene, or the one SceneError. Anything
// else (another exception, a crash, a sanitizer report, a hang) is a finding.
// Mesh files named by the input resolve beside the corpus's scenes, so the
// corpus's mesh files go through the mesh loader (and wavepath-import) too.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "import/import_process.h"
#include "import_failures.h"
#include "scene/scene.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    static const std::string source = WAVEPATH_FUZZ_SCENE_DIR "/fuzz.json";
    try {
        wp::parse_scene(std::string(reinterpret_cast<const char*>(data), size), source, wp::fuzz::kImportLimits);
    } catch (const wp::SceneError& error) {
        // "<source>: <where>: <problem>"
        const std::string message = error.what();
        if (message.rfind(source + ": ", 0) != 0) std::abort();
        // "...: <mesh file>: wavepath-import crashed ..." (import/import_process.h)
        if (message.find(std::string(": ") + wp::kImportHelperName + " ") != std::string::npos)
            wp::fuzz::note_import_failure(message, data, size);
    }
    return 0;
}
