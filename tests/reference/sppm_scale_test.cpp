// SPPM's defaults do not depend on the scene's units or extent (issue 39):
// a glass sphere's caustic on a floor under a small quad light renders the
// same image, within noise, scaled by 1e-3 and by 1e3 (camera, shapes and
// light; radiance is unchanged by a uniform scaling), and with a black
// ground of 1000 x 1000 added behind the camera, out of view, where it
// changes no light path the image sees. Under the former default radius
// (two pixel footprints at the distance of the scene's diagonal) the ground
// alone made every first radius about 300 times larger: 40 scene units,
// wider than the whole scene.
//
// Statistics: kSeeds renders per variant at default settings (radius,
// photons), kIterations iterations each, 16 x 16 pixels cut into four blocks
// of 8 x 8; each render's block means are one sample per seed (SPPM's
// pixels share their photons, so the spread over seeds gives the standard
// error). A variant agrees with the unscaled scene where each block's means
// differ by at most kTolerance standard errors of the difference, taken as
// if the renders were independent (renders of one seed are positively
// correlated, so the true error of the difference is smaller: the check is
// conservative). With kSeeds = 12 the ratio is Student's t with about 22
// degrees of freedom: |t| > 5 has probability 5e-5, so the 12 checks fail a
// correct renderer with probability about 6e-4.
//
// Cost (reference, float, 2 threads, the 2-core machine): 4 variants x 12
// seeds x 4 iterations of 65,536 photons, about 6 s.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>

#include "reference/reference_renderer.h"
#include "support/analytic_scenes.h"
#include "support/statistics.h"

namespace wp {
namespace {
// A namespace of its own: the sanitizer build compiles test files together (unity).
namespace sppm_scale_test {

using test::RunningMean;

constexpr int kSize = 16, kBlocks = 4, kSeeds = 12, kIterations = 4;
constexpr double kTolerance = 5.0;

// The world, at `scale`, shifted so that the camera sits at the origin.
Scene caustic(double scale, bool ground, std::uint32_t seed) {
    const glm::dvec3 camera(0.0, 2.2, 2.2);
    auto at = [&](double x, double y, double z) { return scale * (glm::dvec3(x, y, z) - camera); };
    auto size = [&](double x, double y, double z) { return scale * glm::dvec3(x, y, z); };
    Scene scene = test::empty_scene(
        test::RenderBlock{
            .width = kSize, .height = kSize, .spp = kIterations, .max_depth = 6, .rr_depth = 3, .seed = seed},
        at(0.0, 0.3, 0.0), 40.0);
    scene.render.integrator = Integrator::Sppm;
    const int white = test::add_material(scene, test::diffuse(glm::dvec3(0.7)));
    const int crown = test::add_material(scene, test::glass(1.5));
    const int lamp = test::add_material(scene, test::emitter(glm::dvec3(40.0)));
    scene.quads.push_back({at(-2, 0, -2), size(0, 0, 4), size(4, 0, 0), white});  // facing up
    scene.spheres.push_back({at(0, 0.5, 0), 0.5 * scale, crown});
    scene.quads.push_back({at(-0.15, 2.5, -0.15), size(0.3, 0, 0), size(0, 0, 0.3), lamp});  // facing down
    if (ground) {  // behind the camera (z > 2.2), black: no light path changes
        const int black = test::add_material(scene, test::diffuse(glm::dvec3(0.0)));
        scene.quads.push_back({at(-500, -1, 3), size(0, 0, 1000), size(1000, 0, 0), black});
    }
    build_light_table(scene);
    return scene;
}

using BlockMeans = std::array<RunningMean, kBlocks>;

BlockMeans render_blocks(double scale, bool ground) {
    BlockMeans blocks;
    for (std::uint32_t seed = 1; seed <= kSeeds; ++seed) {
        const Image image = render_reference(caustic(scale, ground, seed), {.threads = 2}).image;
        std::array<double, kBlocks> mean{};
        for (int y = 0; y < kSize; ++y)
            for (int x = 0; x < kSize; ++x)
                for (int c = 0; c < 3; ++c)
                    mean[(y / (kSize / 2)) * 2 + x / (kSize / 2)] +=
                        image.rgb[3 * (std::size_t(y) * kSize + x) + c] / (3.0 * kSize * kSize / kBlocks);
        for (int b = 0; b < kBlocks; ++b) blocks[b].add(mean[b]);
    }
    return blocks;
}

TEST(SppmScale, DefaultsRenderTheSameAtAnyScaleAndExtent) {
    const BlockMeans unit = render_blocks(1.0, false);
    struct Variant {
        const char* name;
        double scale;
        bool ground;
    };
    for (const Variant& v : {Variant{"scaled by 1e-3", 1e-3, false}, Variant{"scaled by 1e3", 1e3, false},
                             Variant{"with a 1000-unit ground", 1.0, true}}) {
        const BlockMeans other = render_blocks(v.scale, v.ground);
        for (int b = 0; b < kBlocks; ++b) {
            const double noise = std::hypot(unit[b].standard_error(), other[b].standard_error());
            const double difference = other[b].mean() - unit[b].mean();
            std::printf("[figure] caustic %s, block %d: %.5f +- %.5f against %.5f +- %.5f (%+.2f%%, %.1f sigma)\n",
                        v.name, b, other[b].mean(), other[b].standard_error(), unit[b].mean(), unit[b].standard_error(),
                        100.0 * difference / unit[b].mean(), difference / noise);
            EXPECT_LE(std::fabs(difference), kTolerance * noise) << v.name << ", block " << b;
        }
    }
}

}  // namespace sppm_scale_test
}  // namespace
}  // namespace wp
