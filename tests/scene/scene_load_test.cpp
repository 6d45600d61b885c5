// Loading valid scenes: counts, defaults, materials, rebase, normalization and
// the light table.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <glm/geometric.hpp>
#include <numbers>
#include <sstream>
#include <string>

#include "scene/named_media.h"
#include "scene/plastic_constants.h"
#include "scene/scene.h"
#include "scene/texture_section.h"

namespace {

const std::string kSceneDir = std::string(WAVEPATH_SOURCE_DIR) + "/scenes/";

void expect_vec3_eq(const glm::dvec3& actual, const glm::dvec3& expected) {
    EXPECT_EQ(actual.x, expected.x);
    EXPECT_EQ(actual.y, expected.y);
    EXPECT_EQ(actual.z, expected.z);
}

int material_named(const wp::Scene& scene, const std::string& name) {
    for (int i = 0; i < static_cast<int>(scene.materials.size()); ++i) {
        if (scene.materials[i].name == name) return i;
    }
    ADD_FAILURE() << "no material " << name;
    return -1;
}

TEST(SceneLoad, RoomHasTheReportsContents) {
    wp::Scene scene = wp::load_scene(kSceneDir + "room.json");
    EXPECT_EQ(scene.source, kSceneDir + "room.json");
    EXPECT_EQ(scene.camera.width, 512);
    EXPECT_EQ(scene.camera.height, 512);
    EXPECT_EQ(scene.render.spp, 64);
    EXPECT_EQ(scene.render.max_depth, 8);
    EXPECT_EQ(scene.render.rr_depth, 3);
    EXPECT_EQ(scene.quads.size(), 7u);  // six walls and the light
    EXPECT_EQ(scene.spheres.size(), 4u);
    EXPECT_TRUE(scene.planes.empty());
    ASSERT_EQ(scene.lights.size(), 1u);
    EXPECT_EQ(scene.lights[0].shape, wp::ShapeType::Quad);
    EXPECT_EQ(scene.materials[scene.quads[scene.lights[0].index].material].type, wp::MaterialType::Emitter);
    EXPECT_EQ(scene.materials[material_named(scene, "glass")].ior, 1.5);
    EXPECT_EQ(scene.materials[material_named(scene, "mirror")].type, wp::MaterialType::Mirror);
    ASSERT_EQ(scene.light_cdf.size(), 1u);
    EXPECT_EQ(scene.light_cdf[0], 1.0);
}

TEST(SceneLoad, RoomLightFacesDown) {
    wp::Scene scene = wp::load_scene(kSceneDir + "room.json");
    const wp::Quad& light = scene.quads[scene.lights[0].index];
    glm::dvec3 normal = glm::cross(light.edge1, light.edge2);
    EXPECT_LT(normal.y, 0.0);
    EXPECT_EQ(normal.x, 0.0);
    EXPECT_EQ(normal.z, 0.0);
}

TEST(SceneLoad, SmallRoomIsTheRoomAtLowResolution) {
    wp::Scene room = wp::load_scene(kSceneDir + "room.json");
    wp::Scene small = wp::load_scene(kSceneDir + "test/room_small.json");
    EXPECT_EQ(small.camera.width, 32);
    EXPECT_EQ(small.camera.height, 32);
    EXPECT_EQ(small.quads.size(), room.quads.size());
    EXPECT_EQ(small.spheres.size(), room.spheres.size());
    expect_vec3_eq(small.world_offset, room.world_offset);
}

TEST(SceneLoad, CornellBoxFromPublishedData) {
    wp::Scene scene = wp::load_scene(kSceneDir + "cornell.json");
    EXPECT_EQ(scene.camera.width, 256);
    EXPECT_EQ(scene.camera.height, 256);
    EXPECT_NEAR(scene.camera.fov_y_degrees, 2.0 * std::atan(0.0125 / 0.035) * 180.0 / std::numbers::pi, 1e-4);
    // floor, ceiling, back, left and right walls, 5 + 5 block faces, light
    EXPECT_EQ(scene.quads.size(), 16u);
    EXPECT_TRUE(scene.spheres.empty());
    EXPECT_EQ(scene.materials.size(), 4u);
    expect_vec3_eq(scene.world_offset, {278.0, 273.0, -800.0});
    ASSERT_EQ(scene.lights.size(), 1u);
    const wp::Quad& light = scene.quads[scene.lights[0].index];
    EXPECT_DOUBLE_EQ(glm::length(glm::cross(light.edge1, light.edge2)), 130.0 * 105.0);
    EXPECT_LT(glm::cross(light.edge1, light.edge2).y, 0.0);
    EXPECT_DOUBLE_EQ(light.corner.y, 548.7 - 273.0);
}

constexpr const char* kMinimalScene = R"({"camera": {"position": [0, 0, 0], "look_at": [0, 0, -1],
                                                  "fov_y": 45, "width": 8, "height": 4}})";

TEST(SceneLoad, DefaultsApply) {
    wp::Scene scene = wp::parse_scene(kMinimalScene, "minimal.json");
    EXPECT_EQ(scene.render.spp, 16);
    EXPECT_EQ(scene.render.max_depth, 8);
    EXPECT_EQ(scene.render.rr_depth, 3);
    EXPECT_EQ(scene.render.seed, 0u);
    EXPECT_TRUE(scene.render.nee);
    EXPECT_EQ(scene.render.hemisphere, wp::Hemisphere::Cosine);
    EXPECT_EQ(scene.render.sampler, wp::Sampler::Sobol);
    expect_vec3_eq(scene.background, glm::dvec3(0.0));
    expect_vec3_eq(scene.camera.up, {0.0, 1.0, 0.0});
    EXPECT_TRUE(scene.materials.empty());
    EXPECT_TRUE(scene.spheres.empty() && scene.planes.empty() && scene.quads.empty());
    EXPECT_TRUE(scene.lights.empty());
    EXPECT_TRUE(scene.light_cdf.empty());
}

TEST(SceneLoad, ExplicitSettingsAtTheirLimits) {
    wp::Scene scene = wp::parse_scene(R"({
        "camera": {"position": [0, 0, 0], "look_at": [0, 0, -1], "up": [1, 0, 0], "fov_y": 179.5,
                   "width": 16384, "height": 8192},
        "render": {"spp": 1048576, "max_depth": 100000, "rr_depth": 2147483647, "seed": 4294967295,
                   "nee": false, "hemisphere": "uniform", "sampler": "independent"},
        "background": [0.25, 0.5, 1e12]})",
                                      "limits.json");
    EXPECT_EQ(scene.camera.width, 16384);
    EXPECT_EQ(scene.camera.height, 8192);
    EXPECT_EQ(scene.camera.fov_y_degrees, 179.5);
    expect_vec3_eq(scene.camera.up, {1.0, 0.0, 0.0});
    EXPECT_EQ(scene.render.spp, 1 << 20);
    EXPECT_EQ(scene.render.max_depth, 100000);
    EXPECT_EQ(scene.render.rr_depth, 2147483647);
    EXPECT_EQ(scene.render.seed, 4294967295u);
    EXPECT_FALSE(scene.render.nee);
    EXPECT_EQ(scene.render.hemisphere, wp::Hemisphere::Uniform);
    EXPECT_EQ(scene.render.sampler, wp::Sampler::Independent);
    expect_vec3_eq(scene.background, {0.25, 0.5, 1e12});
}

TEST(SceneLoad, MaterialsAreReadAndResolved) {
    wp::Scene scene = wp::parse_scene(R"({
        "camera": {"position": [0, 0, 0], "look_at": [0, 0, -1], "fov_y": 45, "width": 8, "height": 8},
        "materials": {
            "glow": {"type": "diffuse", "albedo": [0.1, 0.2, 0.3], "emission": [1, 2, 3], "two_sided": true},
            "chrome": {"type": "mirror", "reflectance": [0.9, 0.8, 1]},
            "water": {"type": "glass", "ior": 1.33},
            "lamp": {"type": "emitter", "radiance": [5, 6, 7]}
        },
        "shapes": [
            {"type": "sphere", "center": [0, 0, -5], "radius": 1, "material": "water"},
            {"type": "sphere", "center": [3, 0, -5], "radius": 1, "material": "chrome"},
            {"type": "quad", "corner": [0, 2, -5], "edge1": [1, 0, 0], "edge2": [0, 0, 1], "material": "lamp"},
            {"type": "quad", "corner": [0, -2, -5], "edge1": [1, 0, 0], "edge2": [0, 0, 1], "material": "glow"}
        ]})",
                                      "materials.json");
    ASSERT_EQ(scene.materials.size(), 4u);
    const wp::Material& glow = scene.materials[material_named(scene, "glow")];
    EXPECT_EQ(glow.type, wp::MaterialType::Diffuse);
    expect_vec3_eq(glow.albedo, {0.1, 0.2, 0.3});
    expect_vec3_eq(glow.emission, {1.0, 2.0, 3.0});
    EXPECT_TRUE(glow.two_sided);
    const wp::Material& chrome = scene.materials[material_named(scene, "chrome")];
    EXPECT_EQ(chrome.type, wp::MaterialType::Mirror);
    expect_vec3_eq(chrome.reflectance, {0.9, 0.8, 1.0});
    const wp::Material& water = scene.materials[material_named(scene, "water")];
    EXPECT_EQ(water.type, wp::MaterialType::Glass);
    EXPECT_EQ(water.ior, 1.33);
    const wp::Material& lamp = scene.materials[material_named(scene, "lamp")];
    EXPECT_EQ(lamp.type, wp::MaterialType::Emitter);
    expect_vec3_eq(lamp.emission, {5.0, 6.0, 7.0});
    EXPECT_FALSE(lamp.two_sided);

    EXPECT_EQ(scene.spheres[0].material, material_named(scene, "water"));
    EXPECT_EQ(scene.spheres[1].material, material_named(scene, "chrome"));
    EXPECT_EQ(scene.quads[0].material, material_named(scene, "lamp"));
    EXPECT_EQ(scene.quads[1].material, material_named(scene, "glow"));
    EXPECT_EQ(scene.lights.size(), 2u);  // the emitter and the glowing diffuse quad
}

TEST(SceneLoad, ConductorsAndNamedMediaAreRead) {
    wp::Scene scene = wp::parse_scene(R"({
        "camera": {"position": [0, 0, 0], "look_at": [0, 0, -1], "fov_y": 45, "width": 8, "height": 8},
        "materials": {
            "copper": {"type": "roughconductor", "material": "Cu", "distribution": "ggx", "alpha": 0.25},
            "brushed": {"type": "roughconductor", "eta": 1.5, "k": [3, 2, 1], "alpha_u": 0.05, "alpha_v": 0.4,
                        "specular_reflectance": [0.9, 0.8, 0.7]},
            "mirror": {"type": "conductor"},
            "crown": {"type": "glass", "ior": "bk7"}
        },
        "shapes": [{"type": "sphere", "center": [0, 0, -5], "radius": 1, "material": "copper"}]})",
                                      "conductors.json");
    const wp::Material& copper = scene.materials[material_named(scene, "copper")];
    EXPECT_EQ(copper.type, wp::MaterialType::RoughConductor);
    expect_vec3_eq(copper.eta, wp::named_conductor("Cu")->eta);
    expect_vec3_eq(copper.k, wp::named_conductor("Cu")->k);
    EXPECT_EQ(copper.distribution, wp::Microfacet::GGX);
    EXPECT_EQ(copper.alpha_u, 0.25);
    EXPECT_EQ(copper.alpha_v, 0.25);
    expect_vec3_eq(copper.specular_reflectance, {1.0, 1.0, 1.0});
    const wp::Material& brushed = scene.materials[material_named(scene, "brushed")];
    expect_vec3_eq(brushed.eta, {1.5, 1.5, 1.5});
    expect_vec3_eq(brushed.k, {3.0, 2.0, 1.0});
    EXPECT_EQ(brushed.distribution, wp::Microfacet::Beckmann);  // Mitsuba's default
    EXPECT_EQ(brushed.alpha_u, 0.05);
    EXPECT_EQ(brushed.alpha_v, 0.4);
    expect_vec3_eq(brushed.specular_reflectance, {0.9, 0.8, 0.7});
    const wp::Material& mirror = scene.materials[material_named(scene, "mirror")];
    EXPECT_EQ(mirror.type, wp::MaterialType::Conductor);
    expect_vec3_eq(mirror.eta, {0.0, 0.0, 0.0});  // "none", the default: Fresnel reflectance 1
    expect_vec3_eq(mirror.k, {1.0, 1.0, 1.0});
    EXPECT_EQ(scene.materials[material_named(scene, "crown")].ior, *wp::named_ior("bk7"));
    EXPECT_TRUE(scene.features().rough_conductor);
    EXPECT_TRUE(scene.features().conductor);
    EXPECT_TRUE(scene.features().non_specular());
}

// {"texture": name} as a plastic's diffuse_reflectance and specular_reflectance
// and a conductor's specular_reflectance: the material's slot names the
// texture, its constant is 0 (unused), the untextured parameters keep theirs.
// The textured plastic's specular sampling weight takes the textures' means as
// Mitsuba 3.9.1's Texture::mean() prints them: a checkerboard of rgb
// (1, 0, 0) and (0, 0, 0.5) 0.25 (its colours' channel means averaged), a raw
// bitmap of texels (1, 0, 0) and (0, 0, 1) 0.14242 (the mean luminance).
TEST(SceneLoad, TexturedPlasticsAndConductors) {
    wp::Scene scene = wp::parse_scene(R"({
        "camera": {"position": [0, 0, 0], "look_at": [0, 0, -1], "fov_y": 45, "width": 8, "height": 8},
        "textures": {"checks": {"type": "checkerboard", "color0": [1, 0, 0], "color1": [0, 0, 0.5]}},
        "materials": {
            "tiled": {"type": "roughplastic", "diffuse_reflectance": {"texture": "checks"}, "specular_reflectance": 0.5},
            "metal": {"type": "conductor", "specular_reflectance": {"texture": "checks"}},
            "brushed": {"type": "roughconductor", "alpha": {"texture": "checks"}},
            "frosted": {"type": "roughdielectric", "alpha_u": 0.2, "alpha_v": {"texture": "checks"}}
        },
        "shapes": [{"type": "sphere", "center": [0, 0, -5], "radius": 1, "material": "tiled"}]})",
                                      "textured.json");
    using P = wp::TexturedParameter;
    const wp::Material& tiled = scene.materials[material_named(scene, "tiled")];
    EXPECT_EQ(tiled.texture(P::Albedo), 0);
    EXPECT_EQ(tiled.texture(P::SpecularReflectance), wp::kNoTexture);
    expect_vec3_eq(tiled.albedo, {0.0, 0.0, 0.0});
    expect_vec3_eq(tiled.specular_reflectance, {0.5, 0.5, 0.5});
    const wp::Material& metal = scene.materials[material_named(scene, "metal")];
    EXPECT_EQ(metal.texture(P::SpecularReflectance), 0);
    EXPECT_EQ(metal.texture(P::Albedo), wp::kNoTexture);
    // `alpha` textures both tangents' roughness, alpha_u and alpha_v one each
    const wp::Material& brushed = scene.materials[material_named(scene, "brushed")];
    EXPECT_EQ(brushed.texture(P::AlphaU), 0);
    EXPECT_EQ(brushed.texture(P::AlphaV), 0);
    const wp::Material& frosted = scene.materials[material_named(scene, "frosted")];
    EXPECT_EQ(frosted.texture(P::AlphaU), wp::kNoTexture);
    EXPECT_EQ(frosted.alpha_u, 0.2);
    EXPECT_EQ(frosted.texture(P::AlphaV), 0);
    EXPECT_TRUE(scene.features().textures);
    EXPECT_NEAR(wp::texture_mean(scene.textures[0]), 0.25, 1e-12);
    EXPECT_NEAR(wp::texture_scalar_min(scene.textures[0]), 1.0 / 6.0, 1e-12);  // color1's mean
    // Mitsuba's weight s / (d + s) with the texture's mean as d
    const std::size_t tiled_index = std::size_t(material_named(scene, "tiled"));
    EXPECT_NEAR(wp::plastic_tables(scene.materials, scene.textures).materials[tiled_index].specular_sampling_weight,
                0.5 / (0.25 + 0.5), 1e-12);
    wp::Texture bitmap;
    bitmap.width = 2, bitmap.height = 1, bitmap.texels = {1, 0, 0, 0, 0, 1};
    EXPECT_NEAR(wp::texture_mean(bitmap), 0.14242, 1e-5);
}

TEST(SceneLoad, PlasticsAreReadWithMitsubasDefaults) {
    wp::Scene scene = wp::parse_scene(R"({
        "camera": {"position": [0, 0, 0], "look_at": [0, 0, -1], "fov_y": 45, "width": 8, "height": 8},
        "materials": {
            "default": {"type": "plastic"},
            "varnish": {"type": "plastic", "diffuse_reflectance": [0.6, 0.2, 0.1], "specular_reflectance": 0.8,
                        "int_ior": "bk7", "ext_ior": 1.2, "nonlinear": true},
            "satin": {"type": "roughplastic", "distribution": "ggx", "alpha": 0.3},
            "rough_default": {"type": "roughplastic"}
        },
        "shapes": [{"type": "sphere", "center": [0, 0, -5], "radius": 1, "material": "default"}]})",
                                      "plastics.json");
    const wp::Material& plain = scene.materials[material_named(scene, "default")];
    EXPECT_EQ(plain.type, wp::MaterialType::Plastic);
    expect_vec3_eq(plain.albedo, {0.5, 0.5, 0.5});
    expect_vec3_eq(plain.specular_reflectance, {1.0, 1.0, 1.0});
    EXPECT_EQ(plain.ior, *wp::named_ior("polypropylene") / *wp::named_ior("air"));
    EXPECT_FALSE(plain.nonlinear);
    const wp::Material& varnish = scene.materials[material_named(scene, "varnish")];
    expect_vec3_eq(varnish.albedo, {0.6, 0.2, 0.1});
    expect_vec3_eq(varnish.specular_reflectance, {0.8, 0.8, 0.8});
    EXPECT_EQ(varnish.ior, *wp::named_ior("bk7") / 1.2);
    EXPECT_TRUE(varnish.nonlinear);
    const wp::Material& satin = scene.materials[material_named(scene, "satin")];
    EXPECT_EQ(satin.type, wp::MaterialType::RoughPlastic);
    EXPECT_EQ(satin.distribution, wp::Microfacet::GGX);
    EXPECT_EQ(satin.alpha_u, 0.3);
    EXPECT_EQ(satin.alpha_v, 0.3);
    const wp::Material& rough_default = scene.materials[material_named(scene, "rough_default")];
    EXPECT_EQ(rough_default.distribution, wp::Microfacet::Beckmann);  // Mitsuba 3.9.1's defaults
    EXPECT_EQ(rough_default.alpha_u, 0.1);
    EXPECT_TRUE(scene.features().plastic);
    EXPECT_TRUE(scene.features().rough_plastic);
    EXPECT_TRUE(scene.features().specular());  // the plastic's delta lobe
    EXPECT_TRUE(scene.features().non_specular());
}

TEST(SceneLoad, PositionsAreRebasedToTheCamera) {
    // Far from the origin, where float kernels would lose precision without the rebase.
    const glm::dvec3 camera{1e6 + 0.125, -2e5 + 0.5, 3e6 + 0.25};
    wp::Scene scene = wp::parse_scene(R"({
        "camera": {"position": [1000000.125, -199999.5, 3000000.25], "look_at": [1000000.125, -199999.5, 2999990],
                   "fov_y": 45, "width": 8, "height": 8},
        "materials": {"white": {"type": "diffuse", "albedo": [0.5, 0.5, 0.5]}},
        "shapes": [
            {"type": "sphere", "center": [1000001.3, -199998.7, 2999995.1], "radius": 0.5, "material": "white"},
            {"type": "plane", "point": [1000000, -200001, 3000000], "normal": [0, 1, 0], "material": "white"},
            {"type": "quad", "corner": [999999.9, -199997.3, 2999993.7], "edge1": [2, 0, 0], "edge2": [0, 0, 3],
             "material": "white"}
        ]})",
                                      "far.json");
    expect_vec3_eq(scene.world_offset, camera);
    expect_vec3_eq(scene.camera.position, glm::dvec3(0.0));
    expect_vec3_eq(scene.camera.look_at, glm::dvec3{1000000.125, -199999.5, 2999990.0} - camera);
    expect_vec3_eq(scene.spheres[0].center, glm::dvec3{1000001.3, -199998.7, 2999995.1} - camera);
    EXPECT_EQ(scene.spheres[0].radius, 0.5);
    expect_vec3_eq(scene.planes[0].point, glm::dvec3{1000000.0, -200001.0, 3000000.0} - camera);
    expect_vec3_eq(scene.quads[0].corner, glm::dvec3{999999.9, -199997.3, 2999993.7} - camera);
    // Directions do not move.
    expect_vec3_eq(scene.planes[0].normal, {0.0, 1.0, 0.0});
    expect_vec3_eq(scene.quads[0].edge1, {2.0, 0.0, 0.0});
    expect_vec3_eq(scene.quads[0].edge2, {0.0, 0.0, 3.0});
}

TEST(SceneLoad, PlaneNormalsAreNormalized) {
    wp::Scene scene = wp::parse_scene(R"({
        "camera": {"position": [0, 0, 0], "look_at": [0, 0, -1], "fov_y": 45, "width": 8, "height": 8},
        "materials": {"white": {"type": "diffuse", "albedo": [0.5, 0.5, 0.5]}},
        "shapes": [
            {"type": "plane", "point": [0, -1, 0], "normal": [0, 3, 4], "material": "white"},
            {"type": "plane", "point": [0, -1, 0], "normal": [1e-300, 0, 0], "material": "white"},
            {"type": "plane", "point": [0, -1, 0], "normal": [1e12, -1e12, 0], "material": "white"}
        ]})",
                                      "planes.json");
    ASSERT_EQ(scene.planes.size(), 3u);
    EXPECT_NEAR(scene.planes[0].normal.x, 0.0, 1e-15);
    EXPECT_NEAR(scene.planes[0].normal.y, 0.6, 1e-15);
    EXPECT_NEAR(scene.planes[0].normal.z, 0.8, 1e-15);
    expect_vec3_eq(scene.planes[1].normal, {1.0, 0.0, 0.0});  // tiny but not zero: still a direction
    EXPECT_NEAR(scene.planes[2].normal.x, std::sqrt(0.5), 1e-15);
    EXPECT_NEAR(scene.planes[2].normal.y, -std::sqrt(0.5), 1e-15);
    for (const wp::Plane& plane : scene.planes) EXPECT_NEAR(glm::length(plane.normal), 1.0, 1e-15);
}

TEST(SceneLoad, LightsAreSelectedInProportionToPower) {
    // Sphere light: radius 0.5, one-sided, radiance 2 (luminance 2):
    //   power = pi * 2 * (4 pi 0.5^2) * 1 = 2 pi^2.
    // Quad light: 1 x 2, two-sided, radiance (0, 1, 0) (luminance 0.7152):
    //   power = pi * 0.7152 * 2 * 2 = 2.8608 pi.
    // The cdf is [p_sphere / total, 1]; spheres come first.
    wp::Scene scene = wp::parse_scene(R"({
        "camera": {"position": [0, 0, 0], "look_at": [0, 0, -1], "fov_y": 45, "width": 8, "height": 8},
        "materials": {
            "bulb": {"type": "emitter", "radiance": [2, 2, 2]},
            "panel": {"type": "emitter", "radiance": [0, 1, 0], "two_sided": true},
            "white": {"type": "diffuse", "albedo": [0.5, 0.5, 0.5]},
            "dark": {"type": "emitter", "radiance": [0, 0, 0]}
        },
        "shapes": [
            {"type": "quad", "corner": [0, 3, -5], "edge1": [1, 0, 0], "edge2": [0, 0, 2], "material": "panel"},
            {"type": "sphere", "center": [0, 0, -5], "radius": 1, "material": "white"},
            {"type": "sphere", "center": [2, 0, -5], "radius": 0.5, "material": "bulb"},
            {"type": "sphere", "center": [4, 0, -5], "radius": 0.5, "material": "dark"}
        ]})",
                                      "lights.json");
    const double pi = std::numbers::pi;
    const double sphere_power = 2.0 * pi * pi;
    const double quad_power = pi * 0.7152 * 2.0 * 2.0;
    ASSERT_EQ(scene.lights.size(), 2u);
    EXPECT_EQ(scene.lights[0].shape, wp::ShapeType::Sphere);
    EXPECT_EQ(scene.lights[0].index, 1);
    EXPECT_NEAR(scene.lights[0].power, sphere_power, 1e-12);
    EXPECT_EQ(scene.lights[1].shape, wp::ShapeType::Quad);
    EXPECT_EQ(scene.lights[1].index, 0);
    EXPECT_NEAR(scene.lights[1].power, quad_power, 1e-12);
    ASSERT_EQ(scene.light_cdf.size(), 2u);
    EXPECT_NEAR(scene.light_cdf[0], sphere_power / (sphere_power + quad_power), 1e-15);
    EXPECT_EQ(scene.light_cdf[1], 1.0);
}

TEST(SceneLoad, LightsWhosePowerUnderflowsAreSelectedUniformly) {
    // 0.2126 * 5e-324 rounds to 0: both powers are 0, and power / total would be 0 / 0.
    wp::Scene scene = wp::parse_scene(R"({
        "camera": {"position": [0, 0, 0], "look_at": [0, 0, -1], "fov_y": 45, "width": 8, "height": 8},
        "materials": {"faint": {"type": "emitter", "radiance": [5e-324, 0, 0]}},
        "shapes": [
            {"type": "sphere", "center": [0, 0, -5], "radius": 1, "material": "faint"},
            {"type": "sphere", "center": [3, 0, -5], "radius": 1, "material": "faint"},
            {"type": "sphere", "center": [6, 0, -5], "radius": 1, "material": "faint"}
        ]})",
                                      "faint.json");
    ASSERT_EQ(scene.lights.size(), 3u);
    EXPECT_EQ(scene.lights[0].power, 0.0);
    EXPECT_EQ(scene.light_cdf, (std::vector<double>{1.0 / 3.0, 2.0 / 3.0, 1.0}));
}

TEST(SceneLoad, DocumentationExampleLoads) {
    std::ifstream file(std::string(WAVEPATH_SOURCE_DIR) + "/docs/scene-format.md");
    std::stringstream text;
    text << file.rdbuf();
    const std::string doc = text.str();
    std::size_t start = doc.find("```json\n");
    ASSERT_NE(start, std::string::npos);
    start += 8;
    std::size_t end = doc.find("```", start);
    wp::Scene scene = wp::parse_scene(doc.substr(start, end - start), "scene-format.md");
    EXPECT_EQ(scene.materials.size(), 4u);
    EXPECT_EQ(scene.spheres.size() + scene.planes.size() + scene.quads.size(), 4u);
    EXPECT_EQ(scene.lights.size(), 1u);
}

TEST(SceneLoad, MissingFileNamesThePathAndTheReason) {
    const std::string path = kSceneDir + "no_such_scene.json";
    try {
        wp::load_scene(path);
        FAIL() << "no error";
    } catch (const wp::SceneError& error) {
        EXPECT_EQ(std::string(error.what()), path + ": cannot open scene file: No such file or directory");
    }
}

TEST(SceneLoad, DirectoryIsNotAScene) {
    try {
        wp::load_scene(kSceneDir);
        FAIL() << "no error";
    } catch (const wp::SceneError& error) {
        EXPECT_EQ(std::string(error.what()), kSceneDir + ": cannot read scene file: Is a directory");
    }
}

}  // namespace
