// libFuzzer target: the bytes of a Mitsuba serialized mesh file ->
// parse_serialized_mesh of each of its first meshes, or the one
// MeshFileError. Anything else (another exception, a crash, a sanitizer
// report, a hang, an allocation the file's counts claim but its bytes do not
// hold) is a finding.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "import/mesh_file_error.h"
#include "scene/serialized_mesh.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view bytes(reinterpret_cast<const char*>(data), size);
    for (std::int64_t index = 0; index < 3; ++index) {
        try {
            wp::parse_serialized_mesh(bytes, index);
        } catch (const wp::MeshFileError&) {
        }
    }
    return 0;
}
