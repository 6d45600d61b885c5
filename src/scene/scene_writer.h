// Writes a scene read from Mitsuba XML as wavepath JSON (docs/scene-format.md;
// `wavepath convert`): the JSON loader then makes the same Scene of it.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "scene/mitsuba_xml.h"

namespace wp {

// A mesh the JSON refers to that must be written beside it.
struct MeshFileToWrite {
    std::filesystem::path path;
    const ImportedMesh* mesh = nullptr;
};

// An embedded image the JSON refers to, its bytes to be written beside it as they are.
struct ImageFileToWrite {
    std::filesystem::path path;
    const std::string* bytes = nullptr;
};

// A texture computed from an image, to be written beside the JSON as an EXR of its texels.
struct TextureFileToWrite {
    std::filesystem::path path;
    const Texture* texture = nullptr;
};

struct SceneJson {
    nlohmann::json json;
    std::vector<MeshFileToWrite> meshes;
    std::vector<ImageFileToWrite> images;
    std::vector<TextureFileToWrite> computed;
};

// The JSON of `scene` (before finish_scene: in the file's coordinates), to be
// written to `json_path`. Meshes that came from an OBJ or PLY file as the
// JSON loader reads them refer to that file (relative to the JSON's folder)
// with their transform; every other mesh (cube, disk, serialized, a file
// whose winding or normals the scene changes) is a binary PLY beside the
// JSON, "<stem>_mesh<N>.ply", in its own coordinates under the same transform.
// A texture of an image embedded in the scene file refers to that image
// written beside the JSON as it was stored, "<stem>_image<N>.<format>", and
// one computed from an image (a glTF alpha's opacity) to an EXR of its
// texels, "<stem>_texture<N>.exr", which reads back to the same floats.
SceneJson scene_json(const MitsubaScene& scene, const std::filesystem::path& json_path);

// A binary little-endian PLY of float positions (and normals), int triangles; std::runtime_error
// when it cannot be written.
void write_ply(const std::filesystem::path& path, const ImportedMesh& mesh);

}  // namespace wp
