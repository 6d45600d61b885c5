// glTF 2.0 files given as the scene (docs/scene-format.md, "glTF scenes"):
// the contained importer (import/import_process.h) reads the file's meshes,
// node transforms, metallic-roughness materials, cameras and
// KHR_lights_punctual lights, and this maps them onto the Scene the JSON
// loader makes. Every malformed file (a spot's cone out of range among
// them) is one SceneError line naming the file and the element.
#pragma once

#include <string>

#include "import/import_limits.h"
#include "scene/mitsuba_xml.h"
#include "scene/scene.h"

namespace wp {

// The image's width where the file's camera (or the default camera) gives
// its aspect ratio: glTF has no image size.
inline constexpr int kGltfImageWidth = 640;

// The scene, with where each mesh came from for `wavepath convert`, and the
// notes on the defaults it took (no camera, no light), one line each.
MitsubaScene read_gltf_scene(const std::string& path, const MeshImportLimits& mesh_import = {});

// read_gltf_scene, then what every loader does after reading (finish_scene).
Scene load_gltf_scene(const std::string& path, const MeshImportLimits& mesh_import = {},
                      std::vector<std::string>* notes = nullptr);

// Whether a scene file is read as glTF 2.0: its name ends in .gltf or .glb (any case).
bool is_gltf_scene_path(const std::string& path);

}  // namespace wp
