// Path tracing and SPPM against the analytic caustic of
// support/caustic_patch.h: a diffuse patch lit only through a glass slab,
// whose radiance the quadrature there computes, with the round trips inside
// the slab that max_depth 3 + 2 kRoundTrips lets the renderers count.
//
// Statistics: path tracing's pixels are independent samples of one value
// (the camera's 0.01 degree field of view sees the patch's centre; the
// irradiance varies by ~1e-8 across it), so their spread gives the standard
// error of the image mean. SPPM's pixels share their photons, so its
// standard error comes from the spread of whole renders over fixed seeds.
// Means are accepted within kSigmaTolerance (4.5) standard errors (a normal
// estimate falls outside with probability 6.8e-6 per check). SPPM is biased
// by its radius: its estimate averages the irradiance over discs of radius
// at most the initial r0, so it lies between the radiance at the centre
// (the largest, under the light's centre) and the least on the circle of
// radius r0, which the quadrature gives too.
//
// Cost (reference, float, 2 threads, CPU time on the 2-core machine): 0.3 s
// for path tracing (262,144 samples), 3 s for SPPM (8 renders of 32
// iterations of 32,768 photons), 4 s for the convergence order (12 renders
// of 256 iterations of 4,096 photons).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

#include "reference/reference_renderer.h"
#include "support/caustic_patch.h"
#include "support/image_statistics.h"
#include "support/statistics.h"

namespace {

using wp::test::CausticPatch;
using wp::test::RenderBlock;
using wp::test::RunningMean;

constexpr int kRoundTrips = 2;
constexpr int kMaxDepth = 3 + 2 * kRoundTrips;
constexpr double kInitialRadius = 0.02;

wp::Scene sppm_scene(const CausticPatch& c, int iterations, std::uint32_t photons, std::uint32_t seed) {
    wp::Scene scene = caustic_patch_scene(
        RenderBlock{.width = 1, .height = 1, .spp = iterations, .max_depth = kMaxDepth, .seed = seed}, c);
    scene.render.integrator = wp::Integrator::Sppm;
    scene.render.sppm.photons = photons;
    scene.render.sppm.radius = kInitialRadius;
    return scene;
}

// Without glass (index 1) the slab is air and the irradiance that of a
// square light straight above, in closed form: Le pi times the form factors
// of the four rectangles the point's foot cuts the square into.
TEST(CausticPatch, QuadratureGivesTheFormFactorsOfTheLightWithoutGlass) {
    CausticPatch air;
    air.ior = 1.0;
    const double a = CausticPatch::kLightHalf, height = CausticPatch::kLightHeight;
    for (auto [x, z] : {std::pair{0.0, 0.0}, std::pair{0.03, -0.01}, std::pair{-0.02, 0.025}}) {
        double form_factor = 0.0;
        for (double dx : {a - x, a + x})
            for (double dz : {a - z, a + z})
                form_factor += wp::test::point_to_corner_rectangle_form_factor(dx, dz, height);
        const double expected = air.radiance * std::numbers::pi * form_factor;
        EXPECT_NEAR(wp::test::caustic_patch_irradiance(air, x, z, 0), expected, 1e-9 * expected) << x << " " << z;
    }
}

TEST(CausticPatch, PathTracingAgreesWithTheQuadrature) {
    const CausticPatch c;
    const wp::Scene scene =
        caustic_patch_scene(RenderBlock{.width = 32, .height = 32, .spp = 256, .max_depth = kMaxDepth, .seed = 3}, c);
    const wp::RenderResult result = wp::render_reference(scene, {.threads = 2});
    const double expected = wp::test::caustic_patch_radiance(c, 0.0, 0.0, kRoundTrips);
    const RunningMean mean = wp::test::channel_mean(result.image, 0);
    std::printf("[figure] caustic patch, path tracing: %.5f +- %.5f (262,144 samples), quadrature %.5f (%+.2f%%)\n",
                mean.mean(), mean.standard_error(), expected, 100.0 * (mean.mean() / expected - 1.0));
    EXPECT_NEAR(mean.mean(), expected, wp::test::kSigmaTolerance * mean.standard_error());
}

// The least radiance on the circle of radius r about the patch's centre.
double least_on_circle(const CausticPatch& c, double r) {
    double least = INFINITY;
    for (int i = 0; i < 16; ++i) {
        double phi = 2.0 * std::numbers::pi * i / 16.0;
        least = std::min(least, wp::test::caustic_patch_radiance(c, r * std::cos(phi), r * std::sin(phi), kRoundTrips));
    }
    return least;
}

TEST(CausticPatch, SppmAgreesWithTheQuadratureWithinItsRadius) {
    const CausticPatch c;
    constexpr int kSeeds = 8, kIterations = 32;
    constexpr std::uint32_t kPhotons = 32768;
    RunningMean mean;
    for (std::uint32_t seed = 1; seed <= kSeeds; ++seed) {
        const wp::RenderResult result =
            wp::render_reference(sppm_scene(c, kIterations, kPhotons, seed), {.threads = 2});
        mean.add(result.image.rgb[0]);
    }
    const double centre = wp::test::caustic_patch_radiance(c, 0.0, 0.0, kRoundTrips);
    const double least = least_on_circle(c, kInitialRadius);
    const double tolerance = wp::test::kSigmaTolerance * mean.standard_error();
    std::printf(
        "[figure] caustic patch, SPPM: %.5f +- %.5f (%d seeds of %d iterations of %u photons, radius %g), "
        "quadrature %.5f at the centre (%+.2f%%), %.5f least at the radius\n",
        mean.mean(), mean.standard_error(), kSeeds, kIterations, kPhotons, kInitialRadius, centre,
        100.0 * (mean.mean() / centre - 1.0), least);
    EXPECT_GE(mean.mean(), least - tolerance);
    EXPECT_LE(mean.mean(), centre + tolerance);
}

// The error's order: with alpha = 2/3 the variance of SPPM's estimate falls
// as N^-alpha and its squared bias as N^-2(1 - alpha) (Knaus and Zwicker
// 2011), so the root-mean-square error falls as N^-1/3 over N iterations.
// Measured over kSeeds renders, read after 8, 16, ..., 256 iterations of one
// render each; the least-squares slope of log RMSE against log N must lie
// within [-1/3 - 0.12, -1/3 + 0.12]: the RMSE at each N has a relative
// standard error of about 1/sqrt(2 kSeeds) = 0.20, which gives the slope
// over a factor of 32 in N a standard error of about 0.05.
TEST(CausticPatch, SppmErrorFallsAsTheCubeRootOfTheIterations) {
    const CausticPatch c;
    constexpr int kSeeds = 12, kMost = 256;
    constexpr std::uint32_t kPhotons = 4096;
    const double truth = wp::test::caustic_patch_radiance(c, 0.0, 0.0, kRoundTrips);
    const std::vector<int> counts{8, 16, 32, 64, 128, 256};
    std::vector<double> squared_error(counts.size(), 0.0);
    for (std::uint32_t seed = 1; seed <= kSeeds; ++seed) {
        const wp::Scene scene = sppm_scene(c, kMost, kPhotons, seed);
        std::unique_ptr<wp::FilmRenderer> renderer = wp::make_reference_renderer(scene, {.threads = 2});
        std::uint64_t done = 0;
        for (std::size_t i = 0; i < counts.size(); ++i) {
            renderer->render({done, std::uint64_t(counts[i])}, {});
            done = std::uint64_t(counts[i]);
            const double error = renderer->film().image().rgb[0] - truth;
            squared_error[i] += error * error / kSeeds;
        }
    }
    double mean_x = 0.0, mean_y = 0.0;
    for (std::size_t i = 0; i < counts.size(); ++i) {
        mean_x += std::log(double(counts[i])) / double(counts.size());
        mean_y += 0.5 * std::log(squared_error[i]) / double(counts.size());
    }
    double covariance = 0.0, variance = 0.0;
    for (std::size_t i = 0; i < counts.size(); ++i) {
        const double dx = std::log(double(counts[i])) - mean_x;
        covariance += dx * (0.5 * std::log(squared_error[i]) - mean_y);
        variance += dx * dx;
    }
    const double slope = covariance / variance;
    std::printf("[figure] caustic patch, SPPM RMSE over %d seeds:", kSeeds);
    for (std::size_t i = 0; i < counts.size(); ++i)
        std::printf(" %d: %.2f%%", counts[i], 100.0 * std::sqrt(squared_error[i]) / truth);
    std::printf("; log-log slope %.3f (theory -1/3)\n", slope);
    EXPECT_NEAR(slope, -1.0 / 3.0, 0.12);
}

}  // namespace
