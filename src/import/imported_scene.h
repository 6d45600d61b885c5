// A mesh file as assimp imported it (triangulated, identical vertices
// joined), in the file's own coordinates and in float as assimp holds it:
// what wavepath-import sends back (import/answer.h) and wavepath merges into
// one world-space Mesh (scene/mesh_file.h).
#pragma once

#include <array>
#include <cstdint>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <string>
#include <vector>

namespace wp {

struct ImportedMesh {
    std::vector<glm::vec3> positions;
    bool has_normals = false;
    std::vector<glm::vec3> normals;  // one per position if has_normals, else empty
    std::vector<glm::uvec3> triangles;
    bool has_uvs = false;
    std::vector<glm::vec2> uvs;  // the file's first texture coordinates, one per position if has_uvs, else empty
};

// A node of the file's node graph. Nodes are listed depth first, each
// before its children, so a node's parent comes before it.
struct ImportedNode {
    static constexpr std::uint32_t kNoParent = 0xffffffffu;
    std::uint32_t parent = kNoParent;   // the root's is kNoParent, every other node's is below its own index
    std::string name;                   // at most kMaxNodeName bytes
    std::array<float, 16> transform{};  // row-major, to the parent's coordinates
    std::vector<std::uint32_t> meshes;  // indices into ImportedScene::meshes
};

struct ImportedScene {
    std::vector<ImportedMesh> meshes;
    std::vector<ImportedNode> nodes;  // empty, or the root first
};

// assimp's node names (aiString) hold at most 1023 bytes.
inline constexpr std::size_t kMaxNodeName = 1023;

}  // namespace wp
