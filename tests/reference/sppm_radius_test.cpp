// Each pixel's first SPPM radius (kernels/shared/sppm.h, sppm_first_radius):
// two footprints, a footprint being the camera ray cone's spread (the
// pixel's angle, 2 tan(fov_y / 2) / height) times the distance the camera
// path travelled to the pixel's first visible point, through every mirror
// and glass bounce, unless render.sppm.radius overrides it. The camera
// looks down -z through a 2 degree field of view at 4 x 4 pixels, so every
// ray is within 1.5 degrees of the axis and its path at most 1 / cos(1.5
// degrees) = 1.0003 times the length along the axis (kOffAxis):
//   a diffuse wall 3 away: 3;
//   a 45 degree mirror 2 away, sending the rays up to a ceiling 1.5 above
//     it: 3.5 (the mirror unfolds the path into a straight line);
//   a glass slab 0.5 thick 1 away, the wall 1.5 behind it: 3, or 3 + k for
//     a path that crossed the slab 2 k more times (Fresnel reflections).
// No light: no photon comes, so the radii keep their first value.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "reference/reference_renderer.h"
#include "support/analytic_scenes.h"

namespace wp {
namespace {
// A namespace of its own: the sanitizer build compiles test files together (unity).
namespace sppm_radius_test {

constexpr double kOffAxis = 1.0005;

Scene looking_down_z(int iterations) {
    Scene scene = test::empty_scene(
        test::RenderBlock{.width = 4, .height = 4, .spp = iterations, .max_depth = 8, .seed = 7}, {0, 0, -1}, 2.0);
    scene.render.integrator = Integrator::Sppm;
    return scene;
}

int add_wall(Scene& scene, double z) {  // facing the camera, 2 x 2 about the axis
    const int white = test::add_material(scene, test::diffuse(glm::dvec3(0.5)));
    scene.quads.push_back({{-1, -1, z}, {2, 0, 0}, {0, 2, 0}, white});
    return white;
}

PhotonEstimate first_radii(Scene scene) {
    build_light_table(scene);
    std::unique_ptr<FilmRenderer> renderer = make_reference_renderer(scene, {.threads = 2});
    renderer->render({0, 16u * std::uint64_t(scene.render.spp)}, {});
    return renderer->film().photons;
}

// The pixel's angle: the footprint per unit of distance.
double spread(const Scene& scene) {
    return 2.0 * std::tan(scene.camera.fov_y_degrees / 2.0 * std::numbers::pi / 180.0) / scene.camera.height;
}

// Every pixel's footprint is spread x (length + k step) for a k >= 0 (within
// kOffAxis and float rounding), and its radius two footprints (or
// `override`); returns how many pixels took k = 0.
int expect_lengths(const Scene& scene, const PhotonEstimate& photons, double length, double step,
                   double override = 0.0) {
    int direct = 0;
    for (std::size_t p = 0; p < 16; ++p) {
        const double travelled = photons.footprint[p] / spread(scene);
        const double k = step > 0.0 ? std::round((travelled - length) / step) : 0.0;
        const double expected = length + k * step;
        EXPECT_GE(k, 0.0) << p;
        EXPECT_GE(travelled, expected * (1.0 - 1e-6)) << p;
        EXPECT_LE(travelled, expected * kOffAxis) << p;
        const double radius = override > 0.0 ? double(float(override)) : double(2.0f * float(photons.footprint[p]));
        EXPECT_EQ(photons.radius[p], radius) << p;
        direct += k == 0.0 ? 1 : 0;
    }
    return direct;
}

TEST(SppmFirstRadius, IsTwoFootprintsAtTheVisiblePoint) {
    Scene scene = looking_down_z(1);
    add_wall(scene, -3.0);
    expect_lengths(scene, first_radii(scene), 3.0, 0.0);
}

TEST(SppmFirstRadius, CountsTheWayThroughAMirror) {
    Scene scene = looking_down_z(1);
    const int silver = test::add_material(scene, test::mirror(glm::dvec3(0.9)));
    // The plane y + z = -2 (normal (0, 1, 1) / sqrt 2): down -z in, up +y out.
    scene.quads.push_back({{-1, -0.5, -1.5}, {2, 0, 0}, {0, 1, -1}, silver});
    const int white = test::add_material(scene, test::diffuse(glm::dvec3(0.5)));
    scene.quads.push_back({{-1, 1.5, -3}, {2, 0, 0}, {0, 0, 2}, white});  // the ceiling, facing down
    expect_lengths(scene, first_radii(scene), 3.5, 0.0);
}

// Four iterations, so that a pixel whose first path left by the slab's
// reflection (about 4%) has had a visible point since.
TEST(SppmFirstRadius, CountsTheWayThroughGlass) {
    Scene scene = looking_down_z(4);
    const int crown = test::add_material(scene, test::glass(1.5));
    scene.quads.push_back({{-2, -2, -1}, {4, 0, 0}, {0, 4, 0}, crown});    // facing the camera
    scene.quads.push_back({{-2, -2, -1.5}, {0, 4, 0}, {4, 0, 0}, crown});  // facing away
    add_wall(scene, -3.0);
    const PhotonEstimate photons = first_radii(scene);
    EXPECT_GE(expect_lengths(scene, photons, 3.0, 1.0), 14);  // most crossed the slab once
}

TEST(SppmFirstRadius, OverrideSetsTheRadiusAndKeepsTheFootprint) {
    Scene scene = looking_down_z(1);
    add_wall(scene, -3.0);
    scene.render.sppm.radius = 0.7;
    expect_lengths(scene, first_radii(scene), 3.0, 0.0, 0.7);
}

}  // namespace sppm_radius_test
}  // namespace
}  // namespace wp
