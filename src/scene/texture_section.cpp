#include "scene/texture_section.h"

#include <algorithm>
#include <filesystem>
#include <limits>
#include <stdexcept>
#include <string>

#include "core/number_text.h"
#include "image/image_io.h"
#include "scene/environment_layout.h"
#include "scene/limits.h"

namespace wp {
namespace {
namespace texture_section {

// One of `names`' values by its key, or a one-line error listing them.
template <class Value, std::size_t N>
Value read_choice(const JsonField& field, const char* what, const std::pair<const char*, Value> (&names)[N]) {
    const std::string name = field.string();
    std::string known;
    for (const auto& [key, value] : names) {
        if (name == key) return value;
        known += (known.empty() ? "" : ", ") + std::string(key);
    }
    field.fail("unknown " + std::string(what) + " " + nlohmann::json(name).dump() + " (expected one of: " + known +
               ")");
}

// [[m0, m1, m2], [m3, m4, m5]]: u' = m0 u + m1 v + m2, v' = m3 u + m4 v + m5.
std::array<double, 6> read_to_uv(const JsonField& field) {
    if (field.array_size() != 2) field.fail("must be 2 rows of 3 numbers: [[m0, m1, m2], [m3, m4, m5]]");
    std::array<double, 6> to_uv{};
    for (std::size_t row = 0; row < 2; ++row) {
        JsonField row_field = field.element(row);
        if (row_field.array_size() != 3) row_field.fail("must be 3 numbers");
        for (std::size_t column = 0; column < 3; ++column) to_uv[3 * row + column] = row_field.element(column).number();
    }
    return to_uv;
}

glm::dvec3 read_color(const JsonField& field) {
    if (!field.is_number()) return field.vec3_in(0.0, 1.0, " (energy gain)");
    const double value = field.number();
    if (!(value >= 0.0 && value <= 1.0)) field.fail("must be in [0, 1] (energy gain), got " + format_number(value));
    return glm::dvec3(value);
}

// The image, checked: every texel finite and in [0, 1], as a reflectance must be.
void read_bitmap(const JsonField& field, const std::string& scene_source, Texture& texture) {
    field.allow_only_keys({"type", "file", "filter_type", "wrap_mode", "raw", "to_uv"});
    JsonField file_field = field.member("file");
    texture.file = file_field.string();
    if (texture.file.empty()) file_field.fail("must not be empty");
    if (auto filter = field.optional_member("filter_type")) {
        texture.filter =
            read_choice(*filter, "filter_type",
                        {std::pair{"bilinear", TextureFilter::Bilinear}, {"nearest", TextureFilter::Nearest}});
    }
    if (auto wrap = field.optional_member("wrap_mode")) {
        texture.wrap = read_choice(
            *wrap, "wrap_mode",
            {std::pair{"repeat", TextureWrap::Repeat}, {"mirror", TextureWrap::Mirror}, {"clamp", TextureWrap::Clamp}});
    }
    const std::optional<JsonField> raw = field.optional_member("raw");
    const std::filesystem::path path = std::filesystem::path(scene_source).parent_path() / texture.file;
    try {
        read_bitmap_file(path.string(), raw && raw->boolean() ? TextureChannels::Raw : TextureChannels::Colour,
                         texture);
    } catch (const std::runtime_error& error) {
        file_field.fail(texture.file + ": " + error.what());
    }
}

void read_checkerboard(const JsonField& field, Texture& texture) {
    field.allow_only_keys({"type", "color0", "color1", "to_uv"});
    if (auto color0 = field.optional_member("color0")) texture.color0 = read_color(*color0);
    if (auto color1 = field.optional_member("color1")) texture.color1 = read_color(*color1);
}

Texture read_texture(const std::string& name, const JsonField& field, const std::string& scene_source) {
    Texture texture;
    texture.name = name;
    texture.type = read_choice(field.member("type"), "texture type",
                               {std::pair{"bitmap", TextureType::Bitmap}, {"checkerboard", TextureType::Checkerboard}});
    if (texture.type == TextureType::Bitmap) {
        read_bitmap(field, scene_source, texture);
    } else {
        read_checkerboard(field, texture);
    }
    if (auto to_uv = field.optional_member("to_uv")) texture.to_uv = read_to_uv(*to_uv);
    return texture;
}

}  // namespace texture_section
}  // namespace

namespace {
namespace texture_section {
// A bitmap texture's texels, each a reflectance in [0, 1].
void set_bitmap(Image image, TextureChannels channels, Texture& texture) {
    for (float value : image.rgb) {
        if (!(value >= 0.0f && value <= 1.0f))
            throw std::runtime_error("a texel value " + format_number(value) + " is outside [0, 1] (energy gain)");
    }
    texture.raw = channels != TextureChannels::Colour;
    texture.width = image.width;
    texture.height = image.height;
    texture.texels = std::move(image.rgb);
}
}  // namespace texture_section
}  // namespace

void read_bitmap_file(const std::string& path, TextureChannels channels, Texture& texture) {
    texture_section::set_bitmap(read_texture_image(path, channels, kMaxTextureSide), channels, texture);
    texture.path = path;
}

void read_bitmap_bytes(const std::string& bytes, const std::string& format, TextureChannels channels,
                       Texture& texture) {
    texture_section::set_bitmap(read_texture_image_bytes(bytes, format, channels, kMaxTextureSide), channels, texture);
}

void read_environment_map_file(const std::string& path, EnvironmentMap& map) {
    Image image = read_texture_image(path, TextureChannels::Colour, kMaxTextureSide);
    if (image.width < 2 || image.height < 3) {
        throw std::runtime_error(std::to_string(image.width) + " x " + std::to_string(image.height) +
                                 " texels, fewer than an environment map's 2 x 3");
    }
    const std::size_t texels = std::size_t(image.width) * std::size_t(image.height);
    if (texels > kMaxTextureTexels) {
        throw std::runtime_error(std::to_string(texels) + " texels, more than the " +
                                 std::to_string(kMaxTextureTexels) + " a scene may have");
    }
    for (float value : image.rgb) {
        if (!(value >= 0.0f && value <= float(kMaxSceneMagnitude)))
            throw std::runtime_error("a texel value " + format_number(value) + " is outside [0, 1e12] (radiance)");
    }
    map.width = image.width;
    map.height = image.height;
    map.texels = std::move(image.rgb);
    if (!(environment_luminance_integral(map) > 0.0))
        throw std::runtime_error("the map has no power (its luminance is 0 everywhere)");
}

std::vector<Texture> read_textures(const JsonField& field, const std::string& scene_source) {
    std::vector<Texture> textures;
    std::size_t texels = 0;
    for (const auto& entry : field.object()) {
        JsonField texture_field = field.member(entry.first);
        textures.push_back(texture_section::read_texture(entry.first, texture_field, scene_source));
        texels += textures.back().texels.size() / 3;
        if (texels > kMaxTextureTexels) {
            texture_field.fail("the textures so far have " + std::to_string(texels) + " texels, more than the " +
                               std::to_string(kMaxTextureTexels) + " a scene may have");
        }
    }
    return textures;
}

int read_texture_reference(const JsonField& field, const std::vector<Texture>& textures) {
    field.allow_only_keys({"texture"});
    JsonField name_field = field.member("texture");
    const std::string name = name_field.string();
    auto found = std::find_if(textures.begin(), textures.end(), [&](const Texture& t) { return t.name == name; });
    if (found == textures.end()) {
        std::string names;
        for (const Texture& t : textures) names += (names.empty() ? "" : ", ") + t.name;
        name_field.fail("undefined texture " + nlohmann::json(name).dump() +
                        " (defined: " + (names.empty() ? "none" : names) + ")");
    }
    return static_cast<int>(found - textures.begin());
}

namespace {
namespace texture_section {
// Mitsuba's luminance of linear RGB (what its bitmap's eval_1 and mean() take)
double luminance(float r, float g, float b) { return 0.212671 * r + 0.715160 * g + 0.072169 * b; }
double channel_mean(const glm::dvec3& c) { return (c.x + c.y + c.z) / 3.0; }
}  // namespace texture_section
}  // namespace

double texture_scalar_min(const Texture& texture) {
    if (texture.type == TextureType::Checkerboard)
        return std::min(texture_section::channel_mean(texture.color0), texture_section::channel_mean(texture.color1));
    double least = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i + 2 < texture.texels.size(); i += 3)
        least = std::min(least,
                         texture_section::luminance(texture.texels[i], texture.texels[i + 1], texture.texels[i + 2]));
    return least;
}

std::string roughness_texture_problem(const Texture& texture) {
    const double least = texture_scalar_min(texture);
    if (least >= kMinRoughness) return "";
    return "texture " + nlohmann::json(texture.name).dump() +
           " as a roughness must be >= " + format_number(kMinRoughness) +
           " everywhere (a bitmap's texel luminance, a checkerboard's colour means), got " + format_number(least);
}

std::string bump_texture_problem(const Texture& texture) {
    if (texture.type == TextureType::Bitmap) return "";
    return "texture " + nlohmann::json(texture.name).dump() +
           " is a checkerboard, which has no gradient: a bump map's height must be a bitmap (as Mitsuba's)";
}

double texture_mean(const Texture& texture) {
    if (texture.type == TextureType::Checkerboard)
        return 0.5 * (texture_section::channel_mean(texture.color0) + texture_section::channel_mean(texture.color1));
    double sum = 0.0;
    for (std::size_t i = 0; i + 2 < texture.texels.size(); i += 3)
        sum += texture_section::luminance(texture.texels[i], texture.texels[i + 1], texture.texels[i + 2]);
    return sum / (double(texture.width) * double(texture.height));
}

}  // namespace wp
