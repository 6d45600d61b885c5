// A mesh file as assimp imported it (triangulated, identical vertices
// joined), in the file's own coordinates and in float as assimp holds it:
// what wavepath-import sends back (import/answer.h) and wavepath merges into
// one world-space Mesh (scene/mesh_file.h), or, for a glTF 2.0 file given as
// the scene, reads as a scene with its materials, cameras and lights
// (scene/gltf_scene.h).
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
    std::uint32_t material = 0;  // index into ImportedScene::materials (0 where the file has none)
};

// The glTF textures a material has that wavepath does not read (ImportedMaterial::unread_textures).
enum ImportedUnreadTexture : std::uint32_t {
    kMetallicRoughnessTexture = 1u,
    kEmissiveTexture = 2u,
    kAllUnreadTextures = 3u,
};

// glTF's alphaMode: the base colour's alpha ignored, a cut-out at alphaCutoff, or a blend.
enum class ImportedAlphaMode : std::uint32_t { Opaque = 0, Mask = 1, Blend = 2 };

// A material in glTF 2.0's metallic-roughness model as assimp reads it
// (glTF's defaults where the file gives no value).
struct ImportedMaterial {
    std::string name;                             // at most kMaxImportedName bytes
    std::array<float, 4> base_color{1, 1, 1, 1};  // linear RGBA
    float metallic = 1, roughness = 1;
    std::array<float, 3> emissive{0, 0, 0};
    float emissive_strength = 1;     // KHR_materials_emissive_strength
    float transmission = 0;          // KHR_materials_transmission
    float ior = 1.5;                 // KHR_materials_ior
    std::string base_color_texture;  // the file's name for it (a uri, "*N" when embedded); empty: none
    std::string normal_texture;      // likewise
    // Each texture's KHR_texture_transform as wavepath's Texture::to_uv (u' = t[0] u + t[1] v + t[2],
    // v' = t[3] u + t[4] v + t[5]); the identity where the file gives none.
    std::array<float, 6> base_color_transform{1, 0, 0, 0, 1, 0};
    std::array<float, 6> normal_transform{1, 0, 0, 0, 1, 0};
    ImportedAlphaMode alpha_mode = ImportedAlphaMode::Opaque;
    float alpha_cutoff = 0.5f;
    std::uint32_t unread_textures = 0;  // ImportedUnreadTexture bits
};

// What a camera or light that is on no node (assimp links them to nodes by
// name) gives as its node.
inline constexpr std::uint32_t kNoNode = 0xffffffffu;

// A perspective camera, in the coordinates of the node that holds it.
struct ImportedCamera {
    std::string name;
    std::uint32_t node = 0;  // index into ImportedScene::nodes, or kNoNode
    // look_at: a point
    std::array<float, 3> position{0, 0, 0}, look_at{0, 0, -1}, up{0, 1, 0};
    float yfov = 0;    // radians, the whole vertical angle (a glTF file's); 0: unknown
    float aspect = 0;  // width / height (a glTF file's); 0: the file gives none
};

// A KHR_lights_punctual light, in the coordinates of the node that holds it.
enum class ImportedLightType : std::uint32_t { Directional = 1, Point = 2, Spot = 3 };
struct ImportedLight {
    std::string name;
    std::uint32_t node = 0;  // index into ImportedScene::nodes, or kNoNode
    ImportedLightType type = ImportedLightType::Directional;
    std::array<float, 3> color{1, 1, 1};  // colour times intensity
    std::array<float, 3> position{0, 0, 0}, direction{0, 0, -1};
    float inner_cone = 0, outer_cone = 0;  // a spot's innerConeAngle and outerConeAngle, radians
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

// An image the file holds inside it (a .glb's buffer view, a data: uri), as
// stored (compressed): a material names it "*N", N its index in
// ImportedScene::images.
struct ImportedImage {
    std::string format;  // the file's hint, e.g. "png" or "jpg" (at most kMaxImageFormat bytes); empty: none
    std::string bytes;   // at most kMaxImportedImageBytes; empty where the file's image is not compressed
};

struct ImportedScene {
    std::vector<ImportedMesh> meshes;
    std::vector<ImportedNode> nodes;  // empty, or the root first
    std::vector<ImportedMaterial> materials;
    std::vector<ImportedCamera> cameras;
    std::vector<ImportedLight> lights;
    std::vector<ImportedImage> images;
};

// assimp's names (aiString) hold at most 1023 bytes.
inline constexpr std::size_t kMaxNodeName = 1023;
inline constexpr std::size_t kMaxImportedName = 1023;
// assimp's format hints hold at most 8 bytes; an embedded image at most 1 GiB.
inline constexpr std::size_t kMaxImageFormat = 8;
inline constexpr std::size_t kMaxImportedImageBytes = std::size_t{1} << 30;

}  // namespace wp
