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
