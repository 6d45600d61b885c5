// Mesh lights and mesh enclosures against closed-form pixel values, on the
// reference in float and double and on the wavefront: a floor under a square
// light made of triangles of unequal area (next-event estimation picks one by
// area) against the square's form factor, and the camera inside a closed,
// emissive, triangulated sphere against the truncated Neumann series.
//
// Acceptance as in analytic_scenes_test.cpp: per channel, |mean - expected|
// <= 4.5 standard errors of the mean over the image's pixels (independent
// estimates of one value; false-failure probability 6.8e-6 per check, fixed
// seeds) plus a rounding allowance of 2e-6 of the value.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "reference/reference_renderer.h"
#include "support/analytic_scenes.h"
#include "support/image_statistics.h"
#include "support/meshes.h"
#include "support/statistics.h"
#include "wavefront/wavefront_renderer.h"

namespace wp {
namespace {

using test::RenderBlock;

// The square light of plane_under_square_light as a fan of four triangles
// from an off-centre point, fronts facing down at the floor.
Scene floor_under_triangulated_square(const RenderBlock& block, const glm::dvec3& albedo, const glm::dvec3& radiance,
                                      double half_side, double height) {
    Scene scene = test::plane_under_square_light(block, albedo, radiance, half_side, height);
    const Quad square = scene.quads.back();
    scene.quads.pop_back();
    Mesh mesh;
    mesh.file = "triangulated square (test)";
    mesh.material = square.material;
    double y = height - 1.0, s = half_side;
    mesh.positions = {{0.3 * s, y, -0.2 * s}, {-s, y, -s}, {s, y, -s}, {s, y, s}, {-s, y, s}};
    for (unsigned i = 1; i <= 4; ++i) mesh.triangles.push_back({0u, i, i % 4 + 1});
    scene.meshes.push_back(mesh);
    build_light_table(scene);
    return scene;
}

Scene inside_emissive_icosphere(const RenderBlock& block, const glm::dvec3& albedo, const glm::dvec3& emission) {
    Scene scene = test::empty_scene(block, {0.3, -0.1, -1}, 90.0);
    int material = test::add_material(scene, test::diffuse(albedo, emission, /*two_sided=*/true));
    scene.meshes.push_back(test::transformed(test::icosphere(2, material), 1.0, {0.1, -0.2, 0.05}));
    build_light_table(scene);
    return scene;
}

// A square of two triangles, 100 units wide, under a uniform background L and
// seen straight down, whose vertex normals all lean by theta from its
// geometric normal. Cosine-sampling about the shading normal ns, a fraction
// (1 + cos theta) / 2 of directions leaves on the front of the geometric
// normal (the cosine lobe projects to the unit disk uniformly; the plane
// through the surface cuts it along a half-ellipse of semi-axes 1 and
// cos theta); the rest would cross the surface and end. Nothing else is in
// the scene, so every sample carries albedo * L * (1 + cos theta) / 2 in
// expectation: theta 0 is the face-normal floor, and ignoring the shading
// normals, or continuing the paths that cross the surface, changes the value.
Scene floor_with_leaning_normals(const RenderBlock& block, const glm::dvec3& albedo, const glm::dvec3& background,
                                 double theta) {
    Scene scene = test::empty_scene(block, {0, -1, 0}, 60.0);
    scene.background = background;
    Mesh mesh;
    mesh.file = "leaning square (test)";
    mesh.material = test::add_material(scene, test::diffuse(albedo));
    mesh.positions = {{-50, -1, 50}, {50, -1, 50}, {50, -1, -50}, {-50, -1, -50}};
    mesh.normals.assign(4, glm::dvec3(std::sin(theta), std::cos(theta), 0.0));
    mesh.triangles = {{0, 1, 2}, {0, 2, 3}};
    scene.meshes.push_back(mesh);
    build_light_table(scene);
    return scene;
}

void expect_channel(const test::RunningMean& mean, double expected, const std::string& what) {
    double tolerance = test::kSigmaTolerance * mean.standard_error() + 2e-6 * expected;
    EXPECT_NEAR(mean.mean(), expected, tolerance) << what << ", standard error " << mean.standard_error();
}

enum class Renderer { ReferenceFloat, ReferenceDouble, Wavefront };

RenderResult render(const Scene& scene, Renderer renderer) {
    if (renderer == Renderer::Wavefront) return render_wavefront(scene, {}, {});
    return render_reference(scene, {.threads = 2, .double_precision = renderer == Renderer::ReferenceDouble});
}

class MeshAnalytic : public ::testing::TestWithParam<Renderer> {};

TEST_P(MeshAnalytic, FloorUnderTriangulatedSquareLightMatchesFormFactor) {
    const glm::dvec3 albedo(0.9, 0.6, 0.3), radiance(5.0, 10.0, 20.0);
    const double half_side = 0.5, height = 1.5;
    for (bool nee : {true, false}) {
        RenderBlock block{.width = 32, .height = 32, .spp = nee ? 32 : 64, .max_depth = nee ? 1 : 2};
        Scene scene = floor_under_triangulated_square(block, albedo, radiance, half_side, height);
        ASSERT_TRUE(scene.features().mesh_lights);
        scene.render.nee = nee;
        RenderResult result = render(scene, GetParam());
        EXPECT_EQ(result.stats.shadow_rays > 0, nee);
        for (int c = 0; c < 3; ++c)
            expect_channel(test::channel_mean(result.image, c),
                           test::plane_under_square_light_radiance(albedo[c], radiance[c], half_side, height),
                           "nee " + std::to_string(nee) + " channel " + std::to_string(c));
    }
}

TEST_P(MeshAnalytic, InsideEmissiveIcosphereTruncatedNeumannSeries) {
    const glm::dvec3 rho(0.3, 0.5, 0.8), le(1.0, 2.0, 0.5);
    for (int max_depth : {0, 2, 5}) {
        RenderBlock block{.width = 16, .height = 16, .spp = 8, .max_depth = max_depth};
        RenderResult result = render(inside_emissive_icosphere(block, rho, le), GetParam());
        EXPECT_EQ(result.stats.nonfinite, 0u);
        for (int c = 0; c < 3; ++c)
            expect_channel(test::channel_mean(result.image, c),
                           test::inside_emissive_sphere_radiance(rho[c], le[c], max_depth),
                           "max_depth " + std::to_string(max_depth) + " channel " + std::to_string(c));
    }
}

TEST_P(MeshAnalytic, FloorWithLeaningShadingNormalsKeepsTheFrontHalfOfTheLobe) {
    const glm::dvec3 albedo(0.9, 0.6, 0.3), background(1.0, 2.0, 4.0);
    for (double theta_degrees : {0.0, 60.0, 85.0}) {
        RenderBlock block{.width = 16, .height = 16, .spp = 16, .max_depth = 3};
        const double theta = theta_degrees * std::numbers::pi / 180.0;
        Scene scene = floor_with_leaning_normals(block, albedo, background, theta);
        ASSERT_TRUE(scene.features().shading_normals);
        RenderResult result = render(scene, GetParam());
        for (int c = 0; c < 3; ++c)
            expect_channel(test::channel_mean(result.image, c), albedo[c] * background[c] * (1 + std::cos(theta)) / 2,
                           "theta " + std::to_string(theta_degrees) + " channel " + std::to_string(c));
    }
}

std::string renderer_name(const ::testing::TestParamInfo<Renderer>& info) {
    switch (info.param) {
        case Renderer::ReferenceFloat:
            return "ReferenceFloat";
        case Renderer::ReferenceDouble:
            return "ReferenceDouble";
        case Renderer::Wavefront:
            return "Wavefront";
    }
    return "";
}

INSTANTIATE_TEST_SUITE_P(Renderers, MeshAnalytic,
                         ::testing::Values(Renderer::ReferenceFloat, Renderer::ReferenceDouble, Renderer::Wavefront),
                         renderer_name);

}  // namespace
}  // namespace wp
