// Readers for the top-level sections of a scene file. Each validates its
// section completely and reports the first problem through JsonField::fail.
#pragma once

#include <vector>

#include "import/import_process.h"
#include "scene/json_field.h"
#include "scene/limits.h"
#include "scene/scene.h"

namespace wp {

// Two directions whose angle has a smaller sine count as parallel.
inline constexpr double kMinSine = 1e-6;

Camera read_camera(const JsonField& field);
RenderSettings read_render(const JsonField& field);
// Materials' parameters may name one of `textures` (scene/texture_section.h).
std::vector<Material> read_materials(const JsonField& field, const std::vector<Texture>& textures);
// Appends to scene.spheres/planes/quads/meshes; materials and source must already be set
// (mesh files are found relative to the directory of scene.source, and imported by `importer`).
void read_shapes(const JsonField& field, Scene& scene, MeshImporter& importer, const ShapeProgress& progress);
// Appends to scene.directional_lights and scene.point_lights, or sets scene.environment_map.
void read_lights(const JsonField& field, Scene& scene);

}  // namespace wp
