// libFuzzer target: JSON text -> a Scene, or the one SceneError. Anything
// else (another exception, a crash, a sanitizer report, a hang) is a finding.
// Mesh files named by the input resolve beside the corpus's scenes, so the
// corpus's mesh files go through the mesh loader (and wavepath-import) too.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <string_view>

#include "import/import_process.h"
#include "import_failures.h"
#include "scene/scene.h"

namespace {

const std::string source = WAVEPATH_FUZZ_SCENE_DIR "/fuzz.json";

// "<source>: shapes[i].file: <mesh file>: wavepath-import crashed ..." (import/import_process.h); the
// input may hold such text elsewhere too, in a key or a string that an error quotes.
bool is_import_failure(const std::string& message) {
    const std::string& mark = wp::fuzz::import_helper_mark();
    const std::size_t file = message.find("].file: "), helper = message.find(mark);
    if (message.rfind(source + ": shapes[", 0) != 0 || file == std::string::npos || helper == std::string::npos ||
        helper < file)
        return false;
    return wp::fuzz::is_process_failure(std::string_view(message).substr(helper + mark.size()));
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    try {
        wp::parse_scene(std::string(reinterpret_cast<const char*>(data), size), source, wp::fuzz::kImportLimits);
    } catch (const wp::SceneError& error) {
        // "<source>: <where>: <problem>"
        const std::string message = error.what();
        if (message.rfind(source + ": ", 0) != 0) std::abort();
        if (is_import_failure(message)) wp::fuzz::note_import_failure(message, data, size);
    }
    return 0;
}
