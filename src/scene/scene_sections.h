// Readers for the top-level sections of a scene file. Each validates its
// section completely and reports the first problem through JsonField::fail.
#pragma once

#include <vector>

#include "scene/json_field.h"
#include "scene/scene.h"

namespace wp {

// Sane limits; docs/scene-format.md lists them.
inline constexpr int kMaxResolution = 16384;
inline constexpr std::int64_t kMaxPixels = std::int64_t{1} << 27;
inline constexpr int kMaxSpp = 1 << 20;
inline constexpr int kMaxDepthLimit = 100000;
// Two directions whose angle has a smaller sine count as parallel.
inline constexpr double kMinSine = 1e-6;

Camera read_camera(const JsonField& field);
RenderSettings read_render(const JsonField& field);
std::vector<Material> read_materials(const JsonField& field);
// Appends to scene.spheres/planes/quads; materials must already be read.
void read_shapes(const JsonField& field, Scene& scene);

}  // namespace wp
