// The scene file's `textures` section and the material parameters that may
// name one of its textures (docs/scene-format.md, "textures").
#pragma once

#include <glm/vec3.hpp>
#include <vector>

#include "image/image_io.h"
#include "scene/json_field.h"
#include "scene/scene.h"

namespace wp {

// Reads every texture, bitmaps' images included (found relative to the
// directory of `scene_source`); at most kMaxTextureTexels texels in all.
std::vector<Texture> read_textures(const JsonField& field, const std::string& scene_source);

// A bitmap's image at `path` into texture's path, raw, width, height and
// texels (linear RGB, decoded from sRGB unless read Raw; or the alpha, raw:
// TextureChannels, scene/scene.h); throws
// std::runtime_error with the one-line reason (unreadable, too large, a
// texel outside [0, 1]). The JSON and the Mitsuba XML readers share it.
void read_bitmap_file(const std::string& path, TextureChannels channels, Texture& texture);

// The same of an image file's bytes held in memory (a glTF file's embedded
// image), `format` the extension its file would have ("png", "jpg"); the
// texture's path stays empty.
void read_bitmap_bytes(const std::string& bytes, const std::string& format, TextureChannels channels, Texture& texture);

// An environment map's image at `path` into map's width, height and texels
// (linear RGB, decoded from sRGB where the file holds integers, as
// Mitsuba 3's envmap reads it), `scale` already set; throws
// std::runtime_error with the one-line reason (unreadable, smaller than
// Mitsuba's 2 x 3 or larger than the texture limits, a texel negative or not
// finite, no power: black everywhere). The JSON and the Mitsuba XML readers
// share it.
void read_environment_map_file(const std::string& path, EnvironmentMap& map);

// The texture a textured parameter names, {"texture": "<name>"}, as its index into `textures` (one error
// line naming the key where the name is undefined).
int read_texture_reference(const JsonField& field, const std::vector<Texture>& textures);

// A texture's mean as Mitsuba 3's Texture::mean(): a bitmap's mean texel
// luminance, a checkerboard's mean of its two colours' channel means (what
// a textured plastic's specular sampling weight takes, as Mitsuba's).
double texture_mean(const Texture& texture);

// The least value a texture takes as a scalar parameter (a roughness), read
// as the kernels' scalar_parameter reads it (Mitsuba's eval_1): a bitmap's
// least texel luminance (bilinear blends never go below it), a
// checkerboard's lesser colour channel mean.
double texture_scalar_min(const Texture& texture);

// A roughness texture's problem, for one error line: empty where every
// value it takes (texture_scalar_min) is at least kMinRoughness.
std::string roughness_texture_problem(const Texture& texture);

// A bump map's height texture's problem, for one error line: empty for a
// bitmap; a checkerboard has no gradient (Mitsuba's eval_1_grad has none).
std::string bump_texture_problem(const Texture& texture);

}  // namespace wp
