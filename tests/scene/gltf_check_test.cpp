// check_gltf: glTF 1.0 and 2.0 meshes, as JSON and as GLB, pass when each
// primitive has the vertices its mode takes, and each way assimp 5.2.5 would
// wrap a face count to 2^32 - 1 is one message (the corpus,
// tests/corpus/bad/scenes, has fuzz_mesh's file, through the binary).
#include "scene/gltf_check.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <string>

#include "scene/mesh_file.h"
#include "support/mesh_files.h"
#include "support/thrown_message.h"

namespace wp::test {
namespace {

// The message check_gltf throws, or "(none)".
std::string gltf_problem(const std::string& file) {
    return thrown_message<MeshFileError>([&] { check_gltf(file); });
}

// A glTF 2.0 file of one primitive (`primitive`'s JSON) and two accessors:
// 0 of `vertices` positions, 1 of `indices` indices.
std::string gltf2(const std::string& primitive, int vertices = 3, int indices = 3) {
    return R"({"asset": {"version": "2.0"}, "meshes": [{"primitives": [)" + primitive + R"(]}],
      "accessors": [{"count": )" +
           std::to_string(vertices) + R"(}, {"count": )" + std::to_string(indices) + "}]}";
}

// The same as binary glTF 2.0: a 12-byte header, then the JSON chunk.
std::string glb2(const std::string& json) {
    std::string file = "glTF";
    append_bytes(file, std::uint32_t{2});
    append_bytes(file, std::uint32_t(20 + json.size()));
    append_bytes(file, std::uint32_t(json.size()));
    append_bytes(file, std::uint32_t{0x4e4f534a});  // "JSON"
    return file + json;
}

TEST(GltfCheck, PrimitivesWithTheVerticesTheirModesTakePass) {
    EXPECT_EQ(gltf_problem(two_squares_gltf()), "(none)");
    EXPECT_EQ(gltf_problem(glb2(two_squares_gltf())), "(none)");
    EXPECT_EQ(gltf_problem(gltf2(R"({"attributes": {"POSITION": 0}})")), "(none)");  // triangles by default
    EXPECT_EQ(gltf_problem(gltf2(R"({"attributes": {"POSITION": 0}, "mode": 0})", 1)), "(none)");
    EXPECT_EQ(gltf_problem(gltf2(R"({"attributes": {"POSITION": 0}, "mode": 3})", 2)), "(none)");
    EXPECT_EQ(gltf_problem(gltf2(R"({"attributes": {"POSITION": 0}, "indices": 1, "mode": 6})", 1, 3)), "(none)");
    // glTF 1.0: meshes and accessors are objects keyed by id.
    EXPECT_EQ(gltf_problem(R"({"meshes": {"m": {"primitives": [{"attributes": {"POSITION": "p"}, "mode": 5}]}},
                               "accessors": {"p": {"count": 3}}})"),
              "(none)");
    EXPECT_EQ(gltf_problem(R"({"asset": {"version": "2.0"}})"), "(none)");  // no meshes
}

// assimp takes a primitive's face count as its count less what its mode
// needs, in 32 bits: fuzz_mesh's line strip without POSITION asked for 64 GB.
TEST(GltfCheck, PrimitivesHaveTheVerticesTheirModesTake) {
    const std::string first = "glTF meshes[0].primitives[0]: ";
    EXPECT_EQ(gltf_problem(gltf2(R"({"attribs": {"POSITION": 0}, "mode": 3})")), first + "no POSITION attribute");
    EXPECT_EQ(gltf_problem(gltf2(R"({"attributes": {"NORMAL": 0}})")), first + "no POSITION attribute");
    EXPECT_EQ(gltf_problem(gltf2(R"({"attributes": {"POSITION": 0}, "mode": 5})", 2)),
              first + "2 vertices, fewer than the 3 one primitive of mode 5 takes");
    EXPECT_EQ(gltf_problem(gltf2(R"({"attributes": {"POSITION": 0}, "mode": 3})", 1)),
              first + "1 vertices, fewer than the 2 one primitive of mode 3 takes");
    EXPECT_EQ(gltf_problem(gltf2(R"({"attributes": {"POSITION": 0}, "mode": 0})", 0)),
              first + "0 vertices, fewer than the 1 one primitive of mode 0 takes");
    EXPECT_EQ(gltf_problem(gltf2(R"({"attributes": {"POSITION": 0}, "indices": 1, "mode": 6})", 3, 2)),
              first + "2 indices, fewer than the 3 one primitive of mode 6 takes");
    // An accessor that is not there, or has no count, counts nothing.
    EXPECT_EQ(gltf_problem(gltf2(R"({"attributes": {"POSITION": 7}})")),
              first + "0 vertices, fewer than the 3 one primitive of mode 4 takes");
    EXPECT_EQ(gltf_problem(glb2(gltf2(R"({"attributes": {"POSITION": 0}, "mode": 2})", 1))),
              first + "1 vertices, fewer than the 2 one primitive of mode 2 takes");
    EXPECT_EQ(gltf_problem(R"({"meshes": {"m": {"primitives": [{"attributes": {"POSITION": "p"}, "mode": 5}]}},
                               "accessors": {"p": {"count": 2}}})"),
              "glTF meshes.m.primitives[0]: 2 vertices, fewer than the 3 one primitive of mode 5 takes");
}

TEST(GltfCheck, FilesAreJsonOrGlb) {
    EXPECT_EQ(gltf_problem("{\"meshes\": [}"), "glTF: malformed JSON at byte 13");
    EXPECT_EQ(gltf_problem("[1, 2]"), "glTF: not a JSON object");
    EXPECT_EQ(gltf_problem(std::string("glTF\2\0\0\0", 8)), "GLB: 8 bytes, too short for a header");
    std::string version3 = glb2("{}");
    version3[4] = 3;
    EXPECT_EQ(gltf_problem(version3), "GLB: version 3, not 1 or 2");
    std::string binary_chunk = glb2("{}");
    binary_chunk[16] = 'B';
    EXPECT_EQ(gltf_problem(binary_chunk), "GLB: the first chunk is not JSON");
    EXPECT_EQ(gltf_problem(glb2("{}").substr(0, 21)), "GLB: a JSON chunk of 2 bytes in a file of 21");
}

}  // namespace
}  // namespace wp::test
