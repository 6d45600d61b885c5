#include "scene/scene_sections.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <glm/geometric.hpp>
#include <glm/gtc/matrix_access.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/matrix.hpp>
#include <limits>
#include <string>

#include "core/shared_math.h"
#include "scene/limits.h"
#include "scene/mesh_file.h"
#include "scene/named_media.h"
#include "scene/texture_section.h"

namespace wp {
namespace {

// The direction of v without overflow or underflow; the zero vector stays zero.
glm::dvec3 safe_normalize(const glm::dvec3& v) {
    double scale = std::max({std::fabs(v.x), std::fabs(v.y), std::fabs(v.z)});
    return scale == 0.0 ? glm::dvec3(0.0) : glm::normalize(v / scale);
}

bool nearly_parallel(const glm::dvec3& a, const glm::dvec3& b) {
    return glm::length(glm::cross(safe_normalize(a), safe_normalize(b))) < kMinSine;
}

glm::dvec3 read_direction(const JsonField& field) {
    glm::dvec3 v = field.vec3();
    if (v == glm::dvec3(0.0)) field.fail("must not be zero-length");
    return v;
}

double read_positive(const JsonField& field) {
    double value = field.number();
    if (!(value > 0.0)) field.fail("must be > 0, got " + format_number(value));
    return value;
}

template <class Int>
void read_optional_integer(const JsonField& parent, std::string_view key, std::int64_t min, std::int64_t max,
                           Int& out) {
    if (auto field = parent.optional_member(key)) out = static_cast<Int>(field->integer(min, max));
}

// ---- camera ----

double read_fov(const JsonField& field) {
    double fov = field.number();
    if (!(fov > 0.0 && fov < 180.0)) field.fail("must be in (0, 180), got " + format_number(fov));
    return fov;
}

void check_pixel_count(const JsonField& camera_field, const Camera& camera) {
    std::int64_t pixels = std::int64_t{camera.width} * camera.height;
    if (pixels > kMaxPixels) {
        camera_field.fail("width * height must be <= " + std::to_string(kMaxPixels) + ", got " +
                          std::to_string(camera.width) + " * " + std::to_string(camera.height) + " = " +
                          std::to_string(pixels));
    }
}

void read_up(const JsonField& camera_field, Camera& camera) {
    std::optional<JsonField> up = camera_field.optional_member("up");
    if (up) camera.up = read_direction(*up);
    if (!nearly_parallel(camera.up, camera.look_at - camera.position)) return;
    if (up) up->fail("must not be parallel to the view direction (look_at - position)");
    camera_field.fail("the default up [0, 1, 0] is parallel to the view direction (look_at - position); set up");
}

// ---- materials ----

glm::dvec3 read_reflectivity(const JsonField& field) { return field.vec3_in(0.0, 1.0, " (energy gain)"); }

glm::dvec3 read_radiance(const JsonField& field) { return field.vec3_in(0.0, kMaxSceneMagnitude); }

bool read_two_sided(const JsonField& field) {
    std::optional<JsonField> two_sided = field.optional_member("two_sided");
    return two_sided && two_sided->boolean();
}

// A colour parameter that may be textured (docs/scene-format.md): {"texture": "<name>"} names
// material's texture for `parameter` (`value`, its constant, is then 0: unused), anything else is
// the constant, which `read_constant` reads into `value`.
template <class ReadConstant>
void read_colour_parameter(const JsonField& field, const std::vector<Texture>& textures, Material& material,
                           TexturedParameter parameter, glm::dvec3& value, ReadConstant read_constant) {
    if (field.is_object()) {
        material.texture(parameter) = read_texture_reference(field, textures);
        value = glm::dvec3(0.0);
    } else {
        value = read_constant(field);
    }
}

void read_diffuse(const JsonField& field, Material& material, const std::vector<Texture>& textures) {
    field.allow_only_keys({"type", "albedo", "emission", "two_sided", "one_sided"});
    read_colour_parameter(field.member("albedo"), textures, material, TexturedParameter::Albedo, material.albedo,
                          read_reflectivity);
    if (auto emission = field.optional_member("emission")) material.emission = read_radiance(*emission);
    material.two_sided = read_two_sided(field);
}

void read_mirror(const JsonField& field, Material& material) {
    field.allow_only_keys({"type", "reflectance", "one_sided"});
    material.reflectance = read_reflectivity(field.member("reflectance"));
}

// An index of refraction: a number > 0 or a name of Mitsuba's ("bk7", "water", ...).
double read_ior(const JsonField& field) {
    if (field.is_number()) return read_positive(field);
    if (!field.is_string()) field.fail_type("a number or a name");
    std::string name = field.string();
    std::optional<double> ior = named_ior(name);
    if (!ior)
        field.fail("unknown index of refraction " + nlohmann::json(name).dump() + " (known: " + named_ior_list() + ")");
    return *ior;
}

void read_glass(const JsonField& field, Material& material) {
    field.allow_only_keys({"type", "ior"});
    material.ior = read_ior(field.member("ior"));
}

// A colour or index given per channel: a number (every channel) or an array of 3, each in [min, max].
glm::dvec3 read_rgb(const JsonField& field, double min, double max) {
    if (!field.is_number()) return field.vec3_in(min, max);
    double value = field.number();
    if (!(value >= min && value <= max)) {
        field.fail("must be in [" + format_number(min) + ", " + format_number(max) + "], got " + format_number(value));
    }
    return glm::dvec3(value);
}

// A conductor's complex index eta + i k: `eta` and `k` (both), or a named
// `material` (Mitsuba's names; "none", the default, reflects everything).
void read_conductor_index(const JsonField& field, Material& material) {
    std::optional<JsonField> name = field.optional_member("material");
    std::optional<JsonField> eta = field.optional_member("eta"), k = field.optional_member("k");
    if (eta || k) {
        if (name) name->fail("give either material or eta and k, not both");
        if (!eta) k->fail("needs eta beside it");
        if (!k) eta->fail("needs k beside it");
        material.eta = read_rgb(*eta, 0.0, kMaxSceneMagnitude);
        material.k = read_rgb(*k, 0.0, kMaxSceneMagnitude);
        return;
    }
    std::string metal = name ? name->string() : "none";
    std::optional<ComplexIor> index = named_conductor(metal);
    if (!index)
        name->fail("unknown conductor " + nlohmann::json(metal).dump() + " (known: " + named_conductor_list() + ")");
    material.eta = index->eta;
    material.k = index->k;
}

// A reflectance factor: a number or an RGB in [0, 1].
glm::dvec3 read_reflectance_factor(const JsonField& field) { return read_rgb(field, 0.0, 1.0); }

// The conductors' and plastics' `specular_reflectance`, which may be textured (the default: 1).
void read_specular_reflectance(const JsonField& field, Material& material, const std::vector<Texture>& textures) {
    if (auto specular = field.optional_member("specular_reflectance")) {
        read_colour_parameter(*specular, textures, material, TexturedParameter::SpecularReflectance,
                              material.specular_reflectance, read_reflectance_factor);
    }
}

// A conductor's index and `specular_reflectance` (the caller checks the keys).
void read_conductor(const JsonField& field, Material& material, const std::vector<Texture>& textures) {
    read_conductor_index(field, material);
    read_specular_reflectance(field, material, textures);
}

void read_smooth_conductor(const JsonField& field, Material& material, const std::vector<Texture>& textures) {
    field.allow_only_keys({"type", "material", "eta", "k", "specular_reflectance", "one_sided"});
    read_conductor(field, material, textures);
}

// A microfacet roughness: finite and at least kMinRoughness, below which
// float's D overflows (docs/scene-format.md; a smooth surface is a
// conductor, or a plastic under a plastic's coat).
double read_roughness(const JsonField& field, const char* smooth_kind = "conductor") {
    double alpha = field.number();
    if (!(alpha >= kMinRoughness)) {
        field.fail("must be >= " + format_number(kMinRoughness) + ", got " + format_number(alpha) +
                   " (a smooth surface is a " + smooth_kind + ")");
    }
    return alpha;
}

// A microfacet distribution's `distribution` (Mitsuba's default Beckmann).
void read_distribution(const JsonField& field, Material& material) {
    std::optional<JsonField> distribution = field.optional_member("distribution");
    if (!distribution) return;
    std::string name = distribution->string();
    if (name == "beckmann") {
        material.distribution = Microfacet::Beckmann;
    } else if (name == "ggx") {
        material.distribution = Microfacet::GGX;
    } else {
        distribution->fail("unknown distribution " + nlohmann::json(name).dump() + " (expected beckmann or ggx)");
    }
}

// A roughconductor's or roughdielectric's roughness along one tangent, which
// may be textured: {"texture": "<name>"} names material's texture for
// `parameter` (`value` is then 0: unused), each of whose values
// (texture_scalar_min) must be a roughness; else the number.
void read_textured_roughness(const JsonField& field, const std::vector<Texture>& textures, Material& material,
                             TexturedParameter parameter, double& value) {
    if (!field.is_object()) {
        value = read_roughness(field);
        return;
    }
    const int texture = read_texture_reference(field, textures);
    if (const std::string problem = roughness_texture_problem(textures[std::size_t(texture)]); !problem.empty())
        field.member("texture").fail(problem);
    material.texture(parameter) = texture;
    value = 0.0;
}

// A microfacet distribution: `distribution` (Mitsuba's default Beckmann)
// and `alpha` or `alpha_u` and `alpha_v` (default 0.1), each a number or a texture.
void read_microfacet(const JsonField& field, Material& material, const std::vector<Texture>& textures) {
    read_distribution(field, material);
    std::optional<JsonField> alpha = field.optional_member("alpha");
    std::optional<JsonField> alpha_u = field.optional_member("alpha_u"), alpha_v = field.optional_member("alpha_v");
    if (alpha_u || alpha_v) {
        if (alpha) alpha->fail("give either alpha or alpha_u and alpha_v, not both");
        if (!alpha_u) alpha_v->fail("needs alpha_u beside it");
        if (!alpha_v) alpha_u->fail("needs alpha_v beside it");
        read_textured_roughness(*alpha_u, textures, material, TexturedParameter::AlphaU, material.alpha_u);
        read_textured_roughness(*alpha_v, textures, material, TexturedParameter::AlphaV, material.alpha_v);
    } else if (alpha) {
        read_textured_roughness(*alpha, textures, material, TexturedParameter::AlphaU, material.alpha_u);
        material.alpha_v = material.alpha_u;
        material.texture(TexturedParameter::AlphaV) = material.texture(TexturedParameter::AlphaU);
    }
}

void read_rough_conductor(const JsonField& field, Material& material, const std::vector<Texture>& textures) {
    field.allow_only_keys({"type", "material", "eta", "k", "specular_reflectance", "distribution", "alpha", "alpha_u",
                           "alpha_v", "one_sided"});
    read_conductor(field, material, textures);
    read_microfacet(field, material, textures);
}

// A dielectric interface's `int_ior` over `ext_ior`, each a number or a name
// of Mitsuba's, with Mitsuba's defaults: `default_inside` (its dielectrics'
// bk7, its plastics' polypropylene) inside, air outside.
double read_relative_ior(const JsonField& field, const char* default_inside = "bk7") {
    std::optional<JsonField> inside = field.optional_member("int_ior"), outside = field.optional_member("ext_ior");
    double int_ior = inside ? read_ior(*inside) : *named_ior(default_inside);
    double ext_ior = outside ? read_ior(*outside) : *named_ior("air");
    return int_ior / ext_ior;
}

void read_dielectric(const JsonField& field, Material& material) {
    field.allow_only_keys({"type", "int_ior", "ext_ior"});
    material.ior = read_relative_ior(field);
}

void read_rough_dielectric(const JsonField& field, Material& material, const std::vector<Texture>& textures) {
    field.allow_only_keys({"type", "int_ior", "ext_ior", "distribution", "alpha", "alpha_u", "alpha_v"});
    material.ior = read_relative_ior(field);
    read_microfacet(field, material, textures);
}

// A plastic's base and coat (the caller checks the keys), with Mitsuba's
// defaults: diffuse_reflectance 0.5, specular_reflectance 1, polypropylene
// in air, nonlinear off.
void read_plastic_coat(const JsonField& field, Material& material, const std::vector<Texture>& textures) {
    material.albedo = glm::dvec3(0.5);
    if (auto diffuse = field.optional_member("diffuse_reflectance")) {
        read_colour_parameter(*diffuse, textures, material, TexturedParameter::Albedo, material.albedo,
                              read_reflectance_factor);
    }
    read_specular_reflectance(field, material, textures);
    material.ior = read_relative_ior(field, "polypropylene");
    if (auto nonlinear = field.optional_member("nonlinear")) material.nonlinear = nonlinear->boolean();
}

void read_plastic(const JsonField& field, Material& material, const std::vector<Texture>& textures) {
    field.allow_only_keys(
        {"type", "diffuse_reflectance", "specular_reflectance", "int_ior", "ext_ior", "nonlinear", "one_sided"});
    read_plastic_coat(field, material, textures);
}

// roughplastic: isotropic, as Mitsuba's (`alpha`, no alpha_u and alpha_v).
void read_rough_plastic(const JsonField& field, Material& material, const std::vector<Texture>& textures) {
    field.allow_only_keys({"type", "diffuse_reflectance", "specular_reflectance", "int_ior", "ext_ior", "nonlinear",
                           "distribution", "alpha", "one_sided"});
    read_plastic_coat(field, material, textures);
    read_distribution(field, material);
    if (auto alpha = field.optional_member("alpha")) {
        // Mitsuba's roughplastic precomputes its tables for one roughness.
        if (alpha->is_object())  // {"texture": ...} elsewhere
            alpha->fail("must be a number: a roughplastic's roughness takes no texture (Mitsuba's neither)");
        material.alpha_u = material.alpha_v = read_roughness(*alpha, "plastic");
    }
}

void read_emitter(const JsonField& field, Material& material) {
    field.allow_only_keys({"type", "radiance", "two_sided"});
    material.emission = read_radiance(field.member("radiance"));
    material.two_sided = read_two_sided(field);
}

Material read_material(const std::string& name, const JsonField& field, const std::vector<Texture>& textures);

// The material an adapter (`adapter`: normalmap, bumpmap or mask) wraps
// (`bsdf`), which may not be an adapter itself.
Material read_wrapped_material(const std::string& name, const JsonField& field, const std::vector<Texture>& textures,
                               const std::string& adapter) {
    const JsonField nested_field = field.member("bsdf");
    Material material = read_material(name, nested_field, textures);
    if (material.adapted()) nested_field.fail("a " + adapter + " cannot nest a normalmap, bumpmap or mask");
    return material;
}

// The material a `normalmap` or `bumpmap` adapter (`adapter`) nests
// (`bsdf`). Only materials that reflect alone may be nested: a transmitting
// one would need Mitsuba's inside-out treatment of an arrival below the
// perturbed normal, which the kernels do not model; nor may another adapter.
Material read_adapted_material(const std::string& name, const JsonField& field, const std::vector<Texture>& textures,
                               const std::string& adapter) {
    Material material = read_wrapped_material(name, field, textures, adapter);
    const MaterialType t = material.type;
    if (t == MaterialType::Emitter || t == MaterialType::Glass || t == MaterialType::RoughDielectric ||
        t == MaterialType::ThinDielectric) {
        field.member("bsdf").member("type").fail(
            adapter + " nests only diffuse, mirror, conductor, roughconductor, plastic or roughplastic");
    }
    return material;
}

// Mitsuba's `normalmap` adapter (kernels/shared/normal_map.h): its nested
// material with the texture `normalmap` perturbing the shading normal.
Material read_normal_map(const std::string& name, const JsonField& field, const std::vector<Texture>& textures) {
    field.allow_only_keys({"type", "normalmap", "bsdf"});
    Material material = read_adapted_material(name, field, textures, "normalmap");
    material.texture(TexturedParameter::NormalMap) = read_texture_reference(field.member("normalmap"), textures);
    return material;
}

// Mitsuba's `bumpmap` adapter (kernels/shared/normal_map.h' bump_mapped):
// its nested material with the shading normal bent by the gradient of the
// bitmap `bumpmap` (a height) times `scale` (default 1).
Material read_bump_map(const std::string& name, const JsonField& field, const std::vector<Texture>& textures) {
    field.allow_only_keys({"type", "bumpmap", "scale", "bsdf"});
    Material material = read_adapted_material(name, field, textures, "bumpmap");
    const JsonField map = field.member("bumpmap");
    const int texture = read_texture_reference(map, textures);
    if (const std::string problem = bump_texture_problem(textures[std::size_t(texture)]); !problem.empty())
        map.member("texture").fail(problem);
    material.texture(TexturedParameter::BumpMap) = texture;
    if (auto scale = field.optional_member("scale")) material.bump_scale = scale->number();
    return material;
}

// Mitsuba's `mask` adapter (kernels/shared/materials/mask.h): its nested
// material (`bsdf`) scatters a ray with probability `opacity` (a number in
// [0, 1] or a texture, clamped to [0, 1] where it is read; Mitsuba's default
// 0.5), and otherwise the ray passes straight through. An adapter inside it
// is refused (a normal map's arrival rule would end rays the mask lets
// pass), as is an emitter (its emission does not pass).
Material read_mask(const std::string& name, const JsonField& field, const std::vector<Texture>& textures) {
    field.allow_only_keys({"type", "opacity", "bsdf"});
    Material material = read_wrapped_material(name, field, textures, "mask");
    if (material.type == MaterialType::Emitter)
        field.member("bsdf").member("type").fail("a mask cannot nest an emitter");
    const std::optional<JsonField> opacity = field.optional_member("opacity");
    if (!opacity) {
        material.opacity = 0.5;
    } else if (opacity->is_object()) {
        material.texture(TexturedParameter::Opacity) = read_texture_reference(*opacity, textures);
        material.opacity = 0.0;
    } else {
        material.opacity = opacity->number();
        if (!(material.opacity >= 0.0 && material.opacity <= 1.0))
            opacity->fail("must be in [0, 1], got " + format_number(material.opacity));
    }
    return material;
}

Material read_material(const std::string& name, const JsonField& field, const std::vector<Texture>& textures) {
    Material material;
    material.name = name;
    JsonField type_field = field.member("type");
    std::string type = type_field.string();
    if (type == "diffuse") {
        material.type = MaterialType::Diffuse;
        read_diffuse(field, material, textures);
    } else if (type == "mirror") {
        material.type = MaterialType::Mirror;
        read_mirror(field, material);
    } else if (type == "glass") {
        material.type = MaterialType::Glass;
        read_glass(field, material);
    } else if (type == "emitter") {
        material.type = MaterialType::Emitter;
        read_emitter(field, material);
    } else if (type == "conductor") {
        material.type = MaterialType::Conductor;
        read_smooth_conductor(field, material, textures);
    } else if (type == "roughconductor") {
        material.type = MaterialType::RoughConductor;
        read_rough_conductor(field, material, textures);
    } else if (type == "dielectric") {
        material.type = MaterialType::Glass;
        read_dielectric(field, material);
    } else if (type == "roughdielectric") {
        material.type = MaterialType::RoughDielectric;
        read_rough_dielectric(field, material, textures);
    } else if (type == "thindielectric") {
        material.type = MaterialType::ThinDielectric;
        read_dielectric(field, material);
    } else if (type == "plastic") {
        material.type = MaterialType::Plastic;
        read_plastic(field, material, textures);
    } else if (type == "roughplastic") {
        material.type = MaterialType::RoughPlastic;
        read_rough_plastic(field, material, textures);
    } else if (type == "normalmap") {
        material = read_normal_map(name, field, textures);
    } else if (type == "bumpmap") {
        material = read_bump_map(name, field, textures);
    } else if (type == "mask") {
        material = read_mask(name, field, textures);
    } else {
        type_field.fail("unknown material type " + nlohmann::json(type).dump() +
                        " (expected one of: diffuse, mirror, glass, emitter, conductor, roughconductor, dielectric, "
                        "roughdielectric, thindielectric, plastic, roughplastic, normalmap, bumpmap, mask)");
    }
    // the reflecting materials' key (their readers allow it): black from the back, as Mitsuba's BSDFs outside twosided
    if (auto one_sided = field.optional_member("one_sided")) material.one_sided = one_sided->boolean();
    return material;
}

// ---- shapes ----

std::string material_names(const std::vector<Material>& materials) {
    if (materials.empty()) return "none";
    std::string names;
    for (const Material& m : materials) names += (names.empty() ? "" : ", ") + m.name;
    return names;
}

int resolve_material(const JsonField& shape_field, const std::vector<Material>& materials) {
    JsonField field = shape_field.member("material");
    std::string name = field.string();
    auto found = std::find_if(materials.begin(), materials.end(), [&](const Material& m) { return m.name == name; });
    if (found == materials.end()) {
        field.fail("undefined material " + nlohmann::json(name).dump() + " (defined: " + material_names(materials) +
                   ")");
    }
    return static_cast<int>(found - materials.begin());
}

Sphere read_sphere(const JsonField& field, const std::vector<Material>& materials) {
    field.allow_only_keys({"type", "center", "radius", "material"});
    return {field.member("center").vec3(), read_positive(field.member("radius")), resolve_material(field, materials)};
}

Plane read_plane(const JsonField& field, const std::vector<Material>& materials) {
    field.allow_only_keys({"type", "point", "normal", "material"});
    Plane plane{field.member("point").vec3(), safe_normalize(read_direction(field.member("normal"))),
                resolve_material(field, materials)};
    const Material& material = materials[plane.material];
    if (material.emits()) {
        field.member("material")
            .fail(nlohmann::json(material.name).dump() + " emits light, but a plane cannot be a light (infinite area)");
    }
    return plane;
}

Quad read_quad(const JsonField& field, const std::vector<Material>& materials) {
    field.allow_only_keys({"type", "corner", "edge1", "edge2", "material"});
    Quad quad;
    quad.corner = field.member("corner").vec3();
    quad.edge1 = read_direction(field.member("edge1"));
    JsonField edge2 = field.member("edge2");
    quad.edge2 = read_direction(edge2);
    if (nearly_parallel(quad.edge1, quad.edge2)) edge2.fail("must not be parallel to edge1");
    quad.material = resolve_material(field, materials);
    return quad;
}

// ---- meshes ----

// A JSON array of exactly `count` numbers.
std::vector<double> read_numbers(const JsonField& field, std::size_t count) {
    const std::string expected = "an array of " + std::to_string(count) + " numbers";
    if (!field.is_array()) field.fail_type(expected);
    std::size_t size = field.array_size();
    if (size != count) field.fail("must be " + expected + ", got " + std::to_string(size) + " elements");
    std::vector<double> numbers;
    for (std::size_t i = 0; i < count; ++i) numbers.push_back(field.element(i).number());
    return numbers;
}

glm::dvec3 read_scale(const JsonField& field) {
    glm::dvec3 scale;
    if (field.is_number()) {
        scale = glm::dvec3(field.number());
        if (scale.x == 0.0) field.fail("must not be 0");
        return scale;
    }
    if (!field.is_array()) field.fail_type("a number or an array of 3 numbers");
    scale = field.vec3();
    for (int i = 0; i < 3; ++i) {
        if (scale[i] == 0.0) field.element(i).fail("must not be 0");
    }
    return scale;
}

glm::dmat4 read_rotation(const JsonField& field) {
    std::vector<double> numbers = read_numbers(field, 4);  // axis x, y, z, degrees
    glm::dvec3 axis(numbers[0], numbers[1], numbers[2]);
    if (axis == glm::dvec3(0.0)) field.fail("the axis (the first 3 numbers) must not be zero-length");
    return glm::rotate(glm::dmat4(1.0), glm::radians(numbers[3]), safe_normalize(axis));
}

// Row-major in the file, as written on paper; affine and invertible.
glm::dmat4 read_matrix(const JsonField& field) {
    const std::size_t rows = field.array_size();
    if (rows != 4) field.fail("must be an array of 4 rows, got " + std::to_string(rows) + " elements");
    glm::dmat4 matrix;
    for (int row = 0; row < 4; ++row) {
        std::vector<double> numbers = read_numbers(field.element(row), 4);
        for (int column = 0; column < 4; ++column) matrix[column][row] = numbers[column];
    }
    if (glm::row(matrix, 3) != glm::dvec4(0.0, 0.0, 0.0, 1.0))
        field.element(3).fail("must be [0, 0, 0, 1] (affine transforms only)");
    if (glm::determinant(glm::dmat3(matrix)) == 0.0) field.fail("must be invertible (its 3x3 part is singular)");
    return matrix;
}

// Scale, then rotate, then translate; or a whole matrix.
glm::dmat4 read_transform(const JsonField& field) {
    field.allow_only_keys({"translate", "rotate", "scale", "matrix"});
    if (std::optional<JsonField> matrix = field.optional_member("matrix")) {
        if (field.object().size() > 1) matrix->fail("cannot be combined with translate, rotate or scale");
        return read_matrix(*matrix);
    }
    glm::dmat4 transform(1.0);
    if (auto translate = field.optional_member("translate")) transform = glm::translate(transform, translate->vec3());
    if (auto rotate = field.optional_member("rotate")) transform = transform * read_rotation(*rotate);
    if (auto scale = field.optional_member("scale")) transform = glm::scale(transform, read_scale(*scale));
    return transform;
}

std::vector<std::string> read_object_names(const JsonField& field) {
    std::vector<std::string> names;
    std::size_t count = field.array_size();
    if (count == 0) field.fail("must name at least one object (leave it out to load all)");
    for (std::size_t i = 0; i < count; ++i) names.push_back(field.element(i).string());
    return names;
}

MeshFileOptions read_mesh_options(const JsonField& field) {
    MeshFileOptions options;
    if (auto transform = field.optional_member("transform")) options.to_world = read_transform(*transform);
    if (auto face_normals = field.optional_member("face_normals")) options.face_normals = face_normals->boolean();
    if (auto objects = field.optional_member("objects")) options.objects = read_object_names(*objects);
    return options;
}

// The mesh file's path is relative to the scene file's directory.
Mesh read_mesh(const JsonField& field, const Scene& scene, MeshImporter& importer) {
    field.allow_only_keys({"type", "file", "material", "transform", "face_normals", "objects"});
    JsonField file_field = field.member("file");
    const std::string file = file_field.string();
    if (file.empty()) file_field.fail("must not be empty");
    const MeshFileOptions options = read_mesh_options(field);
    const int material = resolve_material(field, scene.materials);
    Mesh mesh;
    try {
        mesh = read_mesh_file(std::filesystem::path(scene.source).parent_path() / file, options, importer);
    } catch (const MeshFileError& error) {
        file_field.fail(file + ": " + error.what());
    }
    mesh.file = file;
    mesh.material = material;
    return mesh;
}

void read_shape(const JsonField& field, Scene& scene, MeshImporter& importer) {
    JsonField type_field = field.member("type");
    std::string type = type_field.string();
    if (type == "sphere") {
        scene.spheres.push_back(read_sphere(field, scene.materials));
    } else if (type == "plane") {
        scene.planes.push_back(read_plane(field, scene.materials));
    } else if (type == "quad") {
        scene.quads.push_back(read_quad(field, scene.materials));
    } else if (type == "mesh") {
        scene.meshes.push_back(read_mesh(field, scene, importer));
        std::size_t triangles = 0;
        for (const Mesh& mesh : scene.meshes) triangles += mesh.triangles.size();
        if (triangles > kMaxTriangles)
            field.fail("the meshes so far have " + std::to_string(triangles) + " triangles, more than the " +
                       std::to_string(kMaxTriangles) + " a scene may have");
    } else {
        type_field.fail("unknown shape type " + nlohmann::json(type).dump() +
                        " (expected one of: sphere, plane, quad, mesh)");
    }
}

// A filter's width in pixels: > 0 and within kMaxFilterRadius (`per_radius`:
// the window's radius over the parameter, 4 for a gaussian's stddev).
double read_filter_width(const JsonField& field, double per_radius) {
    double width = field.number();
    double most = kMaxFilterRadius / per_radius;
    if (!(width > 0.0 && width <= most)) {
        field.fail("must be > 0 and <= " + format_number(most) + " pixels, got " + format_number(width));
    }
    return width;
}

// `filter`: {"type": "box"}, {"type": "tent", "radius": r} or {"type":
// "gaussian", "stddev": s}, as Mitsuba 3's rfilters (defaults 1 and 0.5).
PixelFilter read_filter(const JsonField& field) {
    PixelFilter filter;
    JsonField type_field = field.member("type");
    std::string type = type_field.string();
    if (type == "box") {
        field.allow_only_keys({"type"});
    } else if (type == "tent") {
        field.allow_only_keys({"type", "radius"});
        filter.type = FilterType::Tent;
        if (auto radius = field.optional_member("radius")) filter.radius = read_filter_width(*radius, 1.0);
    } else if (type == "gaussian") {
        field.allow_only_keys({"type", "stddev"});
        filter.type = FilterType::Gaussian;
        if (auto stddev = field.optional_member("stddev")) filter.stddev = read_filter_width(*stddev, 4.0);
    } else {
        type_field.fail("unknown filter " + nlohmann::json(type).dump() + " (expected box, tent or gaussian)");
    }
    return filter;
}

}  // namespace

Camera read_camera(const JsonField& field) {
    field.allow_only_keys({"position", "look_at", "up", "fov_y", "width", "height", "filter"});
    Camera camera;
    camera.position = field.member("position").vec3();
    JsonField look_at = field.member("look_at");
    camera.look_at = look_at.vec3();
    if (camera.look_at == camera.position) look_at.fail("must differ from camera.position");
    read_up(field, camera);
    camera.fov_y_degrees = read_fov(field.member("fov_y"));
    camera.width = static_cast<int>(field.member("width").integer(1, kMaxResolution));
    camera.height = static_cast<int>(field.member("height").integer(1, kMaxResolution));
    check_pixel_count(field, camera);
    if (auto filter = field.optional_member("filter")) camera.filter = read_filter(*filter);
    return camera;
}

Hemisphere read_hemisphere(const JsonField& field) {
    std::string name = field.string();
    if (name == "cosine") return Hemisphere::Cosine;
    if (name == "uniform") return Hemisphere::Uniform;
    field.fail("unknown hemisphere sampling " + nlohmann::json(name).dump() + " (expected \"cosine\" or \"uniform\")");
}

Sampler read_sampler(const JsonField& field) {
    std::string name = field.string();
    if (name == "sobol") return Sampler::Sobol;
    if (name == "independent") return Sampler::Independent;
    field.fail("unknown sampler " + nlohmann::json(name).dump() + " (expected \"sobol\" or \"independent\")");
}

Integrator read_integrator(const JsonField& field) {
    std::string name = field.string();
    if (name == "path") return Integrator::Path;
    if (name == "sppm") return Integrator::Sppm;
    field.fail("unknown integrator " + nlohmann::json(name).dump() + " (expected \"path\" or \"sppm\")");
}

// The sppm integrator's keys; with the path integrator each is an error.
SppmSettings read_sppm(const JsonField& field, Integrator integrator) {
    SppmSettings sppm;
    for (const char* key : {"photons", "initial_radius", "alpha"})
        if (auto found = field.optional_member(key); found && integrator != Integrator::Sppm)
            found->fail("applies to the sppm integrator only (render.integrator is \"path\")");
    read_optional_integer(field, "photons", 1, kMaxPhotons, sppm.photons);
    if (auto radius = field.optional_member("initial_radius")) sppm.radius = read_positive(*radius);
    if (auto alpha = field.optional_member("alpha")) {
        sppm.alpha = alpha->number();
        if (!(sppm.alpha > 0.0 && sppm.alpha <= 1.0))
            alpha->fail("must be in (0, 1], got " + format_number(sppm.alpha));
    }
    return sppm;
}

RenderSettings read_render(const JsonField& field) {
    field.allow_only_keys({"spp", "max_depth", "rr_depth", "seed", "nee", "mis", "hemisphere", "sampler", "integrator",
                           "photons", "initial_radius", "alpha"});
    RenderSettings render;
    read_optional_integer(field, "spp", 1, kMaxSpp, render.spp);
    read_optional_integer(field, "max_depth", 0, kMaxDepthLimit, render.max_depth);
    read_optional_integer(field, "rr_depth", 0, std::numeric_limits<int>::max(), render.rr_depth);
    read_optional_integer(field, "seed", 0, std::numeric_limits<std::uint32_t>::max(), render.seed);
    if (std::optional<JsonField> nee = field.optional_member("nee")) render.nee = nee->boolean();
    if (std::optional<JsonField> mis = field.optional_member("mis")) render.mis = mis->boolean();
    if (std::optional<JsonField> hemisphere = field.optional_member("hemisphere"))
        render.hemisphere = read_hemisphere(*hemisphere);
    if (std::optional<JsonField> sampler = field.optional_member("sampler")) render.sampler = read_sampler(*sampler);
    if (std::optional<JsonField> integrator = field.optional_member("integrator"))
        render.integrator = read_integrator(*integrator);
    render.sppm = read_sppm(field, render.integrator);
    return render;
}

std::vector<Material> read_materials(const JsonField& field, const std::vector<Texture>& textures) {
    std::vector<Material> materials;
    for (const auto& entry : field.object())
        materials.push_back(read_material(entry.first, field.member(entry.first), textures));
    return materials;
}

void read_shapes(const JsonField& field, Scene& scene, MeshImporter& importer, const ShapeProgress& progress) {
    const std::size_t count = field.array_size();
    for (std::size_t i = 0; i < count; ++i) {
        read_shape(field.element(i), scene, importer);
        if (progress) progress(i + 1, count);
    }
}

namespace {

// An envmap light: its image (relative to the scene's folder), scale and
// to_world (a rotation or a mirror; its translation is ignored, as for any
// direction). One environment per scene: a non-black background is one.
void read_environment_map(const JsonField& light, Scene& scene) {
    light.allow_only_keys({"type", "filename", "scale", "to_world"});
    if (scene.environment_map || SharedMath<double>::emits(scene.background)) {
        light.member("type").fail(
            "a second environment: a scene has one (an envmap, or the constant one of a non-black background)");
    }
    EnvironmentMap map;
    if (auto scale = light.optional_member("scale")) map.scale = read_positive(*scale);
    if (auto to_world = light.optional_member("to_world")) {
        map.to_world = glm::dmat3(read_transform(*to_world));
        const glm::dmat3 product = glm::transpose(map.to_world) * map.to_world;
        for (int column = 0; column < 3; ++column)
            if (glm::length(product[column] - glm::dmat3(1.0)[column]) > 1e-6)
                to_world->fail("must rotate or mirror only (its 3x3 part orthogonal): an environment has no size");
    }
    const JsonField file_field = light.member("filename");
    map.file = file_field.string();
    if (map.file.empty()) file_field.fail("must not be empty");
    const std::filesystem::path path = std::filesystem::path(scene.source).parent_path() / map.file;
    try {
        read_environment_map_file(path.string(), map);
    } catch (const std::runtime_error& error) {
        file_field.fail(map.file + ": " + error.what());
    }
    map.path = path.string();
    scene.environment_map = std::move(map);
}

// A point light (Mitsuba's point): `position`, `intensity`; a spot (its
// spot) also `direction`, `cutoff_angle` and `beam_width` in degrees.
void read_point_light(const JsonField& light, bool spot, Scene& scene) {
    if (spot)
        light.allow_only_keys({"type", "position", "direction", "intensity", "cutoff_angle", "beam_width"});
    else
        light.allow_only_keys({"type", "position", "intensity"});
    PointLight point;
    point.position = light.member("position").vec3();
    if (auto intensity = light.optional_member("intensity"))
        point.intensity = intensity->vec3_in(0.0, kMaxSceneMagnitude);
    if (spot) {
        SpotCone cone;
        cone.axis = safe_normalize(read_direction(light.member("direction")));
        if (auto cutoff = light.optional_member("cutoff_angle")) {
            cone.cutoff_angle = cutoff->number();
            if (!(cone.cutoff_angle > 0.0 && cone.cutoff_angle <= 90.0))
                cutoff->fail("must be in (0, 90] degrees, got " + format_number(cone.cutoff_angle));
        }
        cone.beam_width = 0.75 * cone.cutoff_angle;
        if (auto beam = light.optional_member("beam_width")) {
            cone.beam_width = beam->number();
            if (!(cone.beam_width >= 0.0 && cone.beam_width <= cone.cutoff_angle))
                beam->fail("must be in [0, cutoff_angle " + format_number(cone.cutoff_angle) + "] degrees, got " +
                           format_number(cone.beam_width));
        }
        point.cone = cone;
    }
    scene.point_lights.push_back(point);
}

}  // namespace

void read_lights(const JsonField& field, Scene& scene) {
    std::size_t count = field.array_size();
    for (std::size_t i = 0; i < count; ++i) {
        const JsonField light = field.element(i);
        const JsonField type_field = light.member("type");
        const std::string type = type_field.string();
        if (type == "envmap") {
            read_environment_map(light, scene);
            continue;
        }
        if (type == "point" || type == "spot") {
            read_point_light(light, type == "spot", scene);
            continue;
        }
        if (type != "directional") {
            type_field.fail("unknown light type " + nlohmann::json(type).dump() +
                            " (expected one of: directional, envmap, point, spot)");
        }
        light.allow_only_keys({"type", "direction", "irradiance"});
        DirectionalLight directional;
        directional.direction = safe_normalize(read_direction(light.member("direction")));
        if (auto irradiance = light.optional_member("irradiance"))
            directional.irradiance = irradiance->vec3_in(0.0, kMaxSceneMagnitude);
        scene.directional_lights.push_back(directional);
    }
}

}  // namespace wp
