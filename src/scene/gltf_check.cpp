#include "scene/gltf_check.h"

#include <cstdint>
#include <cstring>
#include <nlohmann/json.hpp>
#include <string>

#include "scene/mesh_file.h"

namespace wp {
namespace {

using nlohmann::json;

std::uint32_t read_u32(std::string_view bytes, std::size_t offset) {
    std::uint32_t value = 0;
    for (int i = 3; i >= 0; --i) value = value << 8 | static_cast<unsigned char>(bytes[offset + std::size_t(i)]);
    return value;
}

// The JSON text of a GLB: version 2's first chunk, version 1's scene.
std::string_view glb_json(std::string_view file) {
    if (file.size() < 20) throw MeshFileError("GLB: " + std::to_string(file.size()) + " bytes, too short for a header");
    const std::uint32_t version = read_u32(file, 4);
    if (version != 1 && version != 2) throw MeshFileError("GLB: version " + std::to_string(version) + ", not 1 or 2");
    const std::uint64_t length = read_u32(file, 12);
    if (version == 2 && read_u32(file, 16) != 0x4e4f534a) throw MeshFileError("GLB: the first chunk is not JSON");
    const std::size_t start = 20;
    if (length > file.size() - start)
        throw MeshFileError("GLB: a JSON chunk of " + std::to_string(length) + " bytes in a file of " +
                            std::to_string(file.size()));
    return file.substr(start, length);
}

// The element `reference` names in `table`: an index into an array (2.0)
// or a key of an object (1.0); null if there is none.
const json* find(const json& document, const char* table, const json& reference) {
    const auto entries = document.find(table);
    if (entries == document.end()) return nullptr;
    if (entries->is_array() && reference.is_number_unsigned() && reference.get<std::uint64_t>() < entries->size())
        return &(*entries)[reference.get<std::size_t>()];
    if (entries->is_object() && reference.is_string()) {
        const auto entry = entries->find(reference.get<std::string>());
        return entry == entries->end() ? nullptr : &*entry;
    }
    return nullptr;
}

// The count of the accessor `reference` names; 0 if there is none.
std::uint64_t accessor_count(const json& document, const json& reference) {
    const json* accessor = find(document, "accessors", reference);
    if (accessor == nullptr || !accessor->is_object()) return 0;
    const auto count = accessor->find("count");
    return count != accessor->end() && count->is_number_unsigned() ? count->get<std::uint64_t>() : 0;
}

// The vertices one primitive takes in a mode (glTF's modes 0 to 6).
std::uint64_t vertices_per_primitive(std::int64_t mode) {
    if (mode == 0) return 1;               // points
    if (mode >= 1 && mode <= 3) return 2;  // lines, line loop, line strip
    return 3;                              // triangles, strip, fan (and modes assimp ignores)
}

void check_primitive(const json& document, const json& primitive, const std::string& where) {
    if (!primitive.is_object()) throw MeshFileError("glTF " + where + ": not an object");
    const auto attributes = primitive.find("attributes");
    if (attributes == primitive.end() || !attributes->is_object() || !attributes->contains("POSITION"))
        throw MeshFileError("glTF " + where + ": no POSITION attribute");
    const auto indices = primitive.find("indices");
    const bool indexed = indices != primitive.end();
    const std::uint64_t count = accessor_count(document, indexed ? *indices : attributes->at("POSITION"));
    const auto mode_field = primitive.find("mode");
    const std::int64_t mode =
        mode_field != primitive.end() && mode_field->is_number_integer() ? mode_field->get<std::int64_t>() : 4;
    const std::uint64_t needed = vertices_per_primitive(mode);
    if (count < needed) {
        throw MeshFileError("glTF " + where + ": " + std::to_string(count) + (indexed ? " indices" : " vertices") +
                            ", fewer than the " + std::to_string(needed) + " one primitive of mode " +
                            std::to_string(mode) + " takes");
    }
}

void check_mesh(const json& document, const json& mesh, const std::string& where) {
    const auto primitives = mesh.find("primitives");
    if (primitives == mesh.end() || !primitives->is_array()) return;  // no faces to count
    for (std::size_t p = 0; p < primitives->size(); ++p)
        check_primitive(document, (*primitives)[p], where + ".primitives[" + std::to_string(p) + "]");
}

}  // namespace

void check_gltf(std::string_view file) {
    const std::string_view text = file.starts_with("glTF") ? glb_json(file) : file;
    json document;
    try {
        document = json::parse(text.begin(), text.end());
    } catch (const json::parse_error& error) {
        throw MeshFileError("glTF: malformed JSON at byte " + std::to_string(error.byte));
    }
    if (!document.is_object()) throw MeshFileError("glTF: not a JSON object");
    const auto meshes = document.find("meshes");
    if (meshes == document.end()) return;
    if (meshes->is_array()) {
        for (std::size_t m = 0; m < meshes->size(); ++m)
            check_mesh(document, (*meshes)[m], "meshes[" + std::to_string(m) + "]");
    } else if (meshes->is_object()) {
        for (const auto& [id, mesh] : meshes->items()) check_mesh(document, mesh, "meshes." + id);
    }
}

}  // namespace wp
