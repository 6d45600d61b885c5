// SPPM at its default settings against the analytic caustic of
// support/caustic_patch.h: a diffuse patch 0.08 wide lit only through a
// glass slab of 100 x 100 (issue 39). The slab's extent once set the
// default radius (two pixel footprints at the distance of the scene's
// diagonal, 141): 4.4 here, 55 times the patch's width. The radius now
// comes from each pixel's own footprint, and the photons per iteration are
// a fixed 65,536 (kSppmDefaultPhotons), so the test sets nothing of SPPM's.
//
// The camera sits 0.2 above the patch's centre, under the slab, looking
// straight down, its view the square |x|, |z| <= kViewHalf inside the patch
// (kPatchHalf = 0.04; the margin is twice the first radius): the image's
// mean is the patch's mean radiance over that square
// (caustic_patch_square_mean), with the round trips inside the slab that
// max_depth 3 + 2 kRoundTrips counts.
//
// Statistics: kSeeds renders of kIterations iterations each (the budget: 16
// x 16 pixels, 4 x 64 iterations of 65,536 photons, 17 million in all, 3.5 s
// on the 2-core machine); their image means are independent samples, whose
// spread gives the standard error of their mean, measured 0.30% of the
// value. The mean must lie within 2% of the quadrature (the issue's
// target), which a correct renderer misses by chance with probability
// 2e-11 (6.7 standard errors). So that the check stays one of bias, the
// standard error must be below kMostNoise = 1% (3.3 times the measured
// one: an estimate from 4 renders exceeds that by chance with probability
// 3e-7). Measured: -0.22% +- 0.30%; under the former default 0.0013, 250
// times too dark, at the same render time (2,956 iterations of 256 photons).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "reference/reference_renderer.h"
#include "support/caustic_patch.h"
#include "support/image_statistics.h"
#include "support/statistics.h"

namespace {
// A namespace of its own: the sanitizer build compiles test files together (unity).
namespace sppm_slab_test {

using wp::test::CausticPatch;
using wp::test::RenderBlock;
using wp::test::RunningMean;

constexpr int kRoundTrips = 2;
constexpr int kMaxDepth = 3 + 2 * kRoundTrips;
constexpr double kViewHalf = 0.025;
constexpr double kCameraHeight = 0.2;
constexpr double kMostNoise = 0.01;

wp::Scene slab_scene(int iterations, std::uint32_t seed) {
    const CausticPatch c;
    const double fov_y = 2.0 * std::atan(kViewHalf / kCameraHeight) * 180.0 / 3.14159265358979323846;
    wp::Scene scene = caustic_patch_scene(
        RenderBlock{.width = 16, .height = 16, .spp = iterations, .max_depth = kMaxDepth, .seed = seed}, c,
        glm::dvec3(0.0, kCameraHeight, 0.0), fov_y);
    scene.render.integrator = wp::Integrator::Sppm;
    return scene;
}

TEST(SppmSlab, DefaultSettingsAgreeWithTheQuadratureWithinTwoPercent) {
    constexpr int kSeeds = 4, kIterations = 64;
    const double expected = wp::test::caustic_patch_square_mean(CausticPatch{}, kViewHalf, kRoundTrips);
    RunningMean mean;
    for (std::uint32_t seed = 1; seed <= kSeeds; ++seed) {
        const wp::RenderResult result = wp::render_reference(slab_scene(kIterations, seed), {.threads = 2});
        mean.add(wp::test::channel_mean(result.image, 0).mean());
    }
    std::printf("[figure] slab, SPPM defaults: %.5f +- %.5f, quadrature %.5f (%+.2f%%), centre %.5f\n", mean.mean(),
                mean.standard_error(), expected, 100.0 * (mean.mean() / expected - 1.0),
                wp::test::caustic_patch_radiance(CausticPatch{}, 0, 0, kRoundTrips));
    EXPECT_LT(mean.standard_error(), kMostNoise * expected);
    EXPECT_NEAR(mean.mean(), expected, 0.02 * expected);
}

}  // namespace sppm_slab_test
}  // namespace
