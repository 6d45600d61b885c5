// libFuzzer target: Mitsuba 3 XML text -> a Scene (parse_mitsuba_scene, then
// what every loader does after), or the one SceneError naming the file.
// Anything else (another exception, a crash, a sanitizer report, a hang) is
// a finding. The text reads as a file beside the XML corpus's cases, so what
// it includes and names (their .inc and .serialized files) resolves there,
// and mesh files go through the mesh import (and wavepath-import) too.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <string_view>

#include "import/import_process.h"
#include "import_failures.h"
#include "scene/mitsuba_xml.h"

namespace {

const std::string source = WAVEPATH_FUZZ_XML_DIR "/fuzz.xml";

// "<file>:<line>: shape "obj": <mesh file>: wavepath-import crashed ..." (import/import_process.h).
bool is_import_failure(const std::string& message) {
    const std::string& mark = wp::fuzz::import_helper_mark();
    const std::size_t shape = message.find(": shape \""), helper = message.rfind(mark);
    if (shape == std::string::npos || helper == std::string::npos || helper < shape) return false;
    return wp::fuzz::is_process_failure(std::string_view(message).substr(helper + mark.size()));
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    try {
        wp::MitsubaScene scene = wp::parse_mitsuba_scene(std::string(reinterpret_cast<const char*>(data), size), source,
                                                         {}, wp::fuzz::kImportLimits);
        wp::finish_scene(scene.scene);
    } catch (const wp::SceneError& error) {
        // "<file>:<line>: <problem>", the file the scene's or one it includes (beside it, or by an absolute name).
        const std::string message = error.what();
        if (message.rfind(WAVEPATH_FUZZ_XML_DIR "/", 0) != 0 && message.rfind("/", 0) != 0) std::abort();
        if (is_import_failure(message)) wp::fuzz::note_import_failure(message, data, size);
    }
    return 0;
}
