// Small mesh files for the tests, written into temporary directories: the
// unit square [0, 1]^2 in z = 0, facing +z, in every format wavepath reads
// (bad mesh files are the corpus's: tests/corpus/bad/scenes).
#pragma once

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace wp::test {

// ---- the unit square, counter-clockwise seen from +z ----

inline constexpr const char* kSquareObj = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n";

inline constexpr const char* kSquarePlyAscii =
    "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
    "property float nx\nproperty float ny\nproperty float nz\nelement face 1\n"
    "property list uchar int vertex_indices\nend_header\n"
    "0 0 0 0 0 1\n1 0 0 0 0 1\n1 1 0 0 0 1\n0 1 0 0 0 1\n4 0 1 2 3\n";

inline constexpr const char* kSquareOff = "OFF\n4 1 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n";

inline constexpr const char* kSquareStlAscii =
    "solid square\n"
    "facet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 1 1 0\nendloop\nendfacet\n"
    "facet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 1 0\nvertex 0 1 0\nendloop\nendfacet\n"
    "endsolid square\n";

template <class T>
void append_bytes(std::string& bytes, T value) {
    char raw[sizeof(T)];
    std::memcpy(raw, &value, sizeof(T));
    bytes.append(raw, sizeof(T));
}

inline const float kSquareCorners[4][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};

inline std::string square_ply_binary() {
    std::string bytes =
        "ply\nformat binary_little_endian 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
        "property float z\nelement face 2\nproperty list uchar int vertex_indices\nend_header\n";
    for (const auto& corner : kSquareCorners) {
        for (float c : corner) append_bytes(bytes, c);
    }
    for (std::int32_t first : {0, 2}) {  // (0, 1, 2) and (2, 3, 0)
        append_bytes(bytes, std::uint8_t{3});
        for (std::int32_t i = 0; i < 3; ++i) append_bytes(bytes, (first + i) % 4);
    }
    return bytes;
}

inline std::string square_stl_binary() {
    std::string bytes(80, ' ');  // a header that does not start with "solid"
    bytes.replace(0, 6, "binary");
    append_bytes(bytes, std::uint32_t{2});
    for (int first : {0, 2}) {
        for (float n : {0.0f, 0.0f, 1.0f}) append_bytes(bytes, n);
        for (int i = 0; i < 3; ++i) {
            for (float c : kSquareCorners[(first + i) % 4]) append_bytes(bytes, c);
        }
        append_bytes(bytes, std::uint16_t{0});
    }
    return bytes;
}

inline std::string base64(const std::string& bytes) {
    static constexpr char kDigits[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string text;
    for (std::size_t i = 0; i < bytes.size(); i += 3) {
        const std::size_t chunk = std::min<std::size_t>(3, bytes.size() - i);
        std::uint32_t group = 0;
        for (std::size_t k = 0; k < 3; ++k)
            group = group << 8 | (k < chunk ? static_cast<unsigned char>(bytes[i + k]) : 0u);
        for (std::size_t k = 0; k < 4; ++k) text += k <= chunk ? kDigits[(group >> (18 - 6 * k)) & 63] : '=';
    }
    return text;
}

// glTF 2.0 with an embedded buffer: one square mesh used by two nodes, "left"
// at the origin and "right" translated by (2, 0, 0).
inline std::string two_squares_gltf() {
    std::string buffer;
    for (const auto& corner : kSquareCorners) {
        for (float c : corner) append_bytes(buffer, c);
    }
    for (std::uint16_t index : {0, 1, 2, 2, 3, 0}) append_bytes(buffer, index);
    return R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0, 1]}],
  "nodes": [{"name": "left", "mesh": 0}, {"name": "right", "mesh": 0, "translation": [2, 0, 0]}],
  "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1, "mode": 4}]}],
  "accessors": [
    {"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]},
    {"bufferView": 1, "componentType": 5123, "count": 6, "type": "SCALAR"}],
  "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 48, "target": 34962},
                  {"buffer": 0, "byteOffset": 48, "byteLength": 12, "target": 34963}],
  "buffers": [{"byteLength": 60, "uri": "data:application/octet-stream;base64,)" +
           base64(buffer) + R"("}]})";
}

inline void write_file(const std::filesystem::path& path, const std::string& bytes) {
    std::ofstream(path, std::ios::binary) << bytes;
}

}  // namespace wp::test
