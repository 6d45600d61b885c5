// What wavepath-import (the mesh import helper, import/helper/main.cpp)
// sends back on its answer pipe, and how wavepath reads it: one answer,
// either the imported scene or the one-line reason it could not be read.
// The parent trusts nothing in it: decode_answer checks every length, count,
// flag and index against the bytes that arrived.
//
// Layout, in the machine's byte order (the helper is built with wavepath):
//   "WPIMPORT" then u32 version (kAnswerVersion), u32 kind:
//   kind 1 (failure): u32 length (1 to kMaxFailureLength), that many bytes of text;
//   kind 2 (scene):   u32 mesh count, then each mesh:
//                       u32 vertices, u32 flags (bit 0: normals, bit 1: uvs), u32 triangles,
//                       f32 x, y, z per vertex, the normals likewise if it has them,
//                       f32 u, v per vertex if it has uvs,
//                       u32 i0, i1, i2 per triangle, u32 material;
//                     u32 node count, then each node (depth first, the root first):
//                       u32 parent (0xffffffff for the root only, else below the node's own index),
//                       f32[16] transform (row-major), u32 name length (up to kMaxNodeName), the name,
//                       u32 mesh count, u32 per mesh (each below the scene's mesh count);
//                     u32 material count, then each material: name (u32 length, up to
//                       kMaxImportedName, the bytes), f32 base colour[4], metallic, roughness,
//                       emissive[3], emissive strength, transmission, ior, the base colour
//                       texture's name (u32 length, up to kMaxImportedName, the bytes), the
//                       normal texture's likewise, f32[6] the base colour texture's transform,
//                       f32[6] the normal texture's,
//                       u32 alpha mode (0 to 2, ImportedAlphaMode), f32 alpha cutoff,
//                       u32 unread textures (ImportedUnreadTexture bits);
//                       every mesh's material is below the count (or 0 where there is none);
//                     u32 camera count, then each camera: name, u32 node (below the node count, or kNoNode),
//                       f32 position[3], look_at[3], up[3], yfov, aspect;
//                     u32 light count, then each light: name, u32 node, u32 type (1 to 3,
//                       ImportedLightType), f32 colour[3], position[3], direction[3],
//                       f32 inner and outer cone angle;
//                     u32 image count, then each embedded image: its format (u32 length, up to
//                       kMaxImageFormat, the bytes), its bytes (u32 length, up to
//                       kMaxImportedImageBytes, the bytes);
//   and nothing after it.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>
#include <variant>

#include "import/imported_scene.h"

namespace wp {

inline constexpr std::uint32_t kAnswerVersion = 5;
inline constexpr std::size_t kMaxFailureLength = 4096;

// The helper's file descriptors (import/helper/main.cpp): the requests it
// reads (each a u32 length, then that many bytes of a file's name, at most
// kMaxRequestLength), the answers its importers write, and the statuses
// (ImporterStatus) it writes when an importer has answered or ended. Exit statuses
// besides 0 (answered), of an importer or of the helper: its command line
// was not what wavepath passes, its limits could not be set or it could not
// start an importer (usage); an allocation failed under its memory limit.
inline constexpr int kRequestFd = 0;
inline constexpr int kAnswerFd = 3;
inline constexpr int kStatusFd = 4;
inline constexpr std::uint32_t kMaxRequestLength = 1u << 16;
inline constexpr int kHelperUsageStatus = 2;
inline constexpr int kHelperOutOfMemoryStatus = 10;

// How an importer's file ended: its wait status (wait4) if the importer
// ended on it, else 0 (answered); the CPU time the file took; and how many
// files the importer had answered before it.
struct ImporterStatus {
    int wait_status = 0;
    double cpu_s = 0.0;
    std::uint32_t files_before = 0;
};

// An answer's message when the file could not be imported (one line).
struct ImportFailure {
    std::string message;
};

using ImportAnswer = std::variant<ImportedScene, ImportFailure>;

std::string encode_answer(const ImportedScene& scene);
std::string encode_answer(const ImportFailure& failure);  // the message cut to kMaxFailureLength bytes

// An answer that is not one well-formed answer; what() says what is wrong.
class MalformedAnswer : public std::runtime_error {
 public:
    using std::runtime_error::runtime_error;
};

// The answer `bytes` hold, or MalformedAnswer.
ImportAnswer decode_answer(std::string_view bytes);

}  // namespace wp
