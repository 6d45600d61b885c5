// Scenes built in code whose pixel values are known in closed form, with
// those values; for the reference tests, and for any backend that must
// reproduce them. The camera sits at the origin (as after loading).
#pragma once

#include <cmath>
#include <cstdint>
#include <glm/geometric.hpp>
#include <glm/vec3.hpp>
#include <numbers>
#include <optional>

#include "scene/scene.h"

namespace wp::test {

struct RenderBlock {
    int width = 16, height = 16, spp = 16;
    int max_depth = 8;
    int rr_depth = 1 << 30;  // roulette off unless asked for
    std::uint32_t seed = 1;
};

inline Scene empty_scene(const RenderBlock& block, const glm::dvec3& look_at, double fov_y_degrees) {
    Scene scene;
    scene.source = "analytic";
    scene.camera.look_at = look_at;
    scene.camera.up = std::fabs(look_at.y) > 0.9 * glm::length(look_at) ? glm::dvec3(0, 0, -1) : glm::dvec3(0, 1, 0);
    scene.camera.fov_y_degrees = fov_y_degrees;
    scene.camera.width = block.width;
    scene.camera.height = block.height;
    scene.render = RenderSettings{};
    scene.render.spp = block.spp;
    scene.render.max_depth = block.max_depth;
    scene.render.rr_depth = block.rr_depth;
    scene.render.seed = block.seed;
    return scene;
}

inline int add_material(Scene& scene, const Material& material) {
    scene.materials.push_back(material);
    return static_cast<int>(scene.materials.size()) - 1;
}

inline Material diffuse(const glm::dvec3& albedo, const glm::dvec3& emission = glm::dvec3(0), bool two_sided = false) {
    Material m;
    m.type = MaterialType::Diffuse;
    m.albedo = albedo;
    m.emission = emission;
    m.two_sided = two_sided;
    return m;
}

inline Material emitter(const glm::dvec3& radiance) {
    Material m;
    m.type = MaterialType::Emitter;
    m.emission = radiance;
    return m;
}

inline Material mirror(const glm::dvec3& reflectance) {
    Material m;
    m.type = MaterialType::Mirror;
    m.reflectance = reflectance;
    return m;
}

inline Material glass(double ior) {
    Material m;
    m.type = MaterialType::Glass;
    m.ior = ior;
    return m;
}

// (a) The camera inside a closed, two-sided emissive diffuse sphere. Every
// surface point emits Le and reflects rho, so the radiance after at most d
// scattering events is the truncated Neumann series
//   L_d = Le (1 + rho + ... + rho^d) = Le (1 - rho^(d+1)) / (1 - rho).
// (With next-event estimation the per-vertex estimate is even exact: from a
// point on a sphere, cos at both ends is dist / 2r, so albedo/pi * Le *
// cos / pdf_area->solid_angle = albedo * Le for every light sample.)
inline Scene inside_emissive_sphere(const RenderBlock& block, const glm::dvec3& albedo, const glm::dvec3& emission) {
    Scene scene = empty_scene(block, {0.3, -0.1, -1}, 90.0);
    int material = add_material(scene, diffuse(albedo, emission, /*two_sided=*/true));
    scene.spheres.push_back({{0.1, -0.2, 0.05}, 1.0, material});  // off-centre: the camera is inside, not at the centre
    build_light_table(scene);
    return scene;
}

inline double inside_emissive_sphere_radiance(double albedo, double emission, int max_depth) {
    return emission * (1.0 - std::pow(albedo, max_depth + 1)) / (1.0 - albedo);
}

// (b) A convex sphere under a uniform background and no lights. A path that
// meets it leaves after one scattering event (diffuse or mirror: a convex
// surface cannot see itself), so every sample that hits the sphere carries
// exactly albedo (or reflectance) * background, every other sample
// background; a pixel is a mix of the two with one hit fraction for all
// channels. A glass sphere scales radiance by 1/eta^2 on entering and by
// eta^2 on leaving and absorbs nothing, so every sample carries background
// and the sphere is invisible.
// The background is the environment light; these scenes render without
// next-event estimation, whose light samples would make the pixels noisy
// (floor_under_environment has it).
inline Scene sphere_under_background(const RenderBlock& block, const Material& material, const glm::dvec3& background) {
    Scene scene = empty_scene(block, {0, 0, -1}, 40.0);
    scene.render.nee = false;
    scene.background = background;
    scene.spheres.push_back({{0.2, -0.1, -4.0}, 1.0, add_material(scene, material)});
    build_light_table(scene);
    return scene;
}

// A diffuse floor under a uniform background, seen straight down: every
// sample carries albedo * background, whichever way the plane's normal
// points (surfaces are two-sided; scattering must use the side the ray came
// from).
inline Scene floor_under_background(const RenderBlock& block, const glm::dvec3& albedo, const glm::dvec3& background,
                                    double normal_sign) {
    Scene scene = empty_scene(block, {0, -1, 0}, 60.0);
    scene.render.nee = false;
    scene.background = background;
    scene.planes.push_back({{0, -1, 0}, {0, normal_sign, 0}, add_material(scene, diffuse(albedo))});
    build_light_table(scene);
    return scene;
}

// The same floor under the environment of radiance L with next-event
// estimation (and, where `mis`, multiple importance sampling): each pixel's
// expected value is still albedo * L (the white furnace), now estimated by
// the environment's light samples too.
inline Scene floor_under_environment(const RenderBlock& block, const glm::dvec3& albedo, const glm::dvec3& radiance,
                                     bool mis) {
    Scene scene = floor_under_background(block, albedo, radiance, 1.0);
    scene.render.nee = true;
    scene.render.mis = mis;
    return scene;
}

// The same floor under an environment map of constant radiance L (8 x 5
// texels, turned about x so that its poles are not the floor's normal):
// each pixel's expected value is albedo * L, as under the constant
// environment, now estimated by the map's importance-sampled light samples.
inline Scene floor_under_constant_environment_map(const RenderBlock& block, const glm::dvec3& albedo,
                                                  const glm::dvec3& radiance, bool mis) {
    Scene scene = floor_under_environment(block, albedo, glm::dvec3(0.0), mis);
    std::vector<float> texels;
    for (int i = 0; i < 8 * 5; ++i)
        texels.insert(texels.end(), {float(radiance.x), float(radiance.y), float(radiance.z)});
    const double c = std::cos(0.4), s = std::sin(0.4);
    EnvironmentMap map;
    map.file = "constant.exr";
    map.width = 8, map.height = 5;
    map.texels = texels;
    map.to_world = glm::dmat3(1, 0, 0, 0, c, s, 0, -s, c);
    scene.environment_map = map;
    build_light_table(scene);
    return scene;
}

// A diffuse floor y = -1 seen straight down under a directional light of
// irradiance E whose light arrives at angle theta from the floor's normal,
// black background: the light sample of every floor point is the same, so
// every pixel is exactly albedo / pi * E * cos(theta).
inline Scene floor_under_directional_light(const RenderBlock& block, const glm::dvec3& albedo,
                                           const glm::dvec3& irradiance, double theta) {
    Scene scene = empty_scene(block, {0, -1, 0}, 60.0);
    scene.planes.push_back({{0, -1, 0}, {0, 1, 0}, add_material(scene, diffuse(albedo))});
    scene.directional_lights.push_back({{std::sin(theta), -std::cos(theta), 0.0}, irradiance});
    build_light_table(scene);
    return scene;
}

// The camera at the centre of a diffuse sphere of radius R seen from inside,
// looking along -z, with a point light of intensity I at the centre too
// (where `cone`, a spot pointing along -z), direct light only (max_depth 1):
// every surface point lies at distance R and faces the light, so a pixel
// shows albedo / pi * I / R^2 times the mean falloff over the directions its
// samples take, which are also the directions from the light.
inline Scene inside_sphere_around_point_light(const RenderBlock& block, const glm::dvec3& albedo, double radius,
                                              const glm::dvec3& intensity, std::optional<SpotCone> cone) {
    RenderBlock direct_only = block;
    direct_only.max_depth = 1;
    Scene scene = empty_scene(direct_only, {0, 0, -1}, 90.0);
    scene.spheres.push_back({{0, 0, 0}, radius, add_material(scene, diffuse(albedo, glm::dvec3(0), true))});
    if (cone) cone->axis = {0, 0, -1};
    scene.point_lights.push_back({{0, 0, 0}, intensity, cone});
    build_light_table(scene);
    return scene;
}

// The camera inside a glass sphere of index n, off centre by less than r/n
// so that no ray is ever totally reflected: every path leaves the glass once
// (after any number of Fresnel reflections), and radiance grows by n^2 on
// the way out of the denser medium, so every sample carries n^2 * background.
inline Scene inside_glass_sphere(const RenderBlock& block, double ior, const glm::dvec3& background) {
    Scene scene = empty_scene(block, {0.2, 0.1, -1}, 90.0);
    scene.background = background;
    scene.spheres.push_back({{-0.15, 0.1, 0.0}, 1.0, add_material(scene, glass(ior))});
    build_light_table(scene);
    return scene;
}

// Form factor from a point to a parallel a x b rectangle whose corner lies
// at height h straight above it (Siegel and Howell, configuration B-2):
//   F = 1/(2 pi) [A/sqrt(1+A^2) atan(B/sqrt(1+A^2)) + B/sqrt(1+B^2) atan(A/sqrt(1+B^2))],
// A = a/h, B = b/h.
inline double point_to_corner_rectangle_form_factor(double a, double b, double h) {
    double A = a / h, B = b / h;
    double sa = std::sqrt(1.0 + A * A), sb = std::sqrt(1.0 + B * B);
    return (A / sa * std::atan(B / sa) + B / sb * std::atan(A / sb)) / (2.0 * std::numbers::pi);
}

// (c) A diffuse floor plane y = -1 under a downward-facing square emitter of
// side 2s centred at height h above the point (0, -1, 0), which the camera at
// the origin views straight down through a 0.01 degree field of view (the
// irradiance varies by ~(footprint / h)^2 < 1e-8 across it). Irradiance
// E = Le * pi * F with F four corner rectangles s x s, so the floor's
// radiance is albedo / pi * E = albedo * Le * F.
inline Scene plane_under_square_light(const RenderBlock& block, const glm::dvec3& albedo, const glm::dvec3& radiance,
                                      double half_side, double height) {
    Scene scene = empty_scene(block, {0, -1, 0}, 0.01);
    scene.planes.push_back({{0, -1, 0}, {0, 1, 0}, add_material(scene, diffuse(albedo))});
    // edge1 x edge2 = (2s,0,0) x (0,0,2s) points down, at the floor.
    scene.quads.push_back({{-half_side, height - 1.0, -half_side},
                           {2 * half_side, 0, 0},
                           {0, 0, 2 * half_side},
                           add_material(scene, emitter(radiance))});
    build_light_table(scene);
    return scene;
}

// Adds a light below the floor, brighter in total than the one above, that
// no floor point can see: next-event estimation picks it most of the time and
// its shadow rays are blocked, yet dividing by the selection probability
// keeps the floor's radiance unchanged.
inline void add_hidden_light_below_floor(Scene& scene, const glm::dvec3& radiance) {
    scene.spheres.push_back({{0.3, -3.0, 0.2}, 0.5, add_material(scene, emitter(radiance))});
    build_light_table(scene);
}

inline double plane_under_square_light_radiance(double albedo, double radiance, double half_side, double height) {
    return albedo * radiance * 4.0 * point_to_corner_rectangle_form_factor(half_side, half_side, height);
}

// The same floor under a spherical emitter of radius r centred at height h:
// a sphere fully above the horizon gives E = pi Le (r / h)^2, so the floor's
// radiance is albedo * Le * (r / h)^2.
inline Scene plane_under_sphere_light(const RenderBlock& block, const glm::dvec3& albedo, const glm::dvec3& radiance,
                                      double radius, double height) {
    Scene scene = empty_scene(block, {0, -1, 0}, 0.01);
    scene.planes.push_back({{0, -1, 0}, {0, 1, 0}, add_material(scene, diffuse(albedo))});
    scene.spheres.push_back({{0, height - 1.0, 0}, radius, add_material(scene, emitter(radiance))});
    build_light_table(scene);
    return scene;
}

inline double plane_under_sphere_light_radiance(double albedo, double radiance, double radius, double height) {
    return albedo * radiance * (radius / height) * (radius / height);
}

// A small closed room with every feature (diffuse quads and plane, mirror and
// glass spheres, a quad light, a sphere light, an emissive diffuse sphere),
// no closed form: for comparisons between precisions, thread counts, seeds
// and backends.
inline Scene feature_room(const RenderBlock& block) {
    Scene scene = empty_scene(block, {0, -0.2, -1}, 60.0);
    int white = add_material(scene, diffuse({0.7, 0.7, 0.7}));
    int red = add_material(scene, diffuse({0.7, 0.1, 0.1}));
    int chrome = add_material(scene, mirror({0.9, 0.9, 0.9}));
    int crown_glass = add_material(scene, glass(1.5));
    int lamp = add_material(scene, emitter({8, 7, 6}));
    int glow = add_material(scene, diffuse({0.5, 0.5, 0.8}, {0.5, 0.5, 2.0}, /*two_sided=*/true));
    scene.planes.push_back({{0, -1, 0}, {0, 1, 0}, white});                       // floor
    scene.quads.push_back({{-1.5, -1, -4}, {0, 0, 4}, {0, 2.5, 0}, red});         // left wall
    scene.quads.push_back({{1.5, -1, -4}, {0, 2.5, 0}, {0, 0, 4}, white});        // right wall
    scene.quads.push_back({{-1.5, -1, -4}, {0, 2.5, 0}, {3, 0, 0}, white});       // back wall
    scene.quads.push_back({{-1.5, 1.5, -4}, {0, 0, 4}, {3, 0, 0}, white});        // ceiling
    scene.quads.push_back({{-0.4, 1.49, -2.4}, {0.8, 0, 0}, {0, 0, 0.8}, lamp});  // faces down
    scene.spheres.push_back({{-0.7, -0.5, -2.8}, 0.5, chrome});
    scene.spheres.push_back({{0.6, -0.55, -2.2}, 0.45, crown_glass});
    scene.spheres.push_back({{0.9, 0.9, -3.4}, 0.15, lamp});
    scene.spheres.push_back({{-0.9, 1.0, -3.0}, 0.2, glow});
    build_light_table(scene);
    return scene;
}

}  // namespace wp::test
