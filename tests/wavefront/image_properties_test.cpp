// Whole-image properties of the wavefront: determinism, independence of the
// wavefront size, statistical agreement with the reference; analytic scenes
// on both OpenCL backends (--backend auto, the default, picks one of them).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <utility>
#include <vector>

#include "megakernel/megakernel_renderer.h"
#include "reference/reference_renderer.h"
#include "support/image_statistics.h"
#include "support/statistics.h"
#include "wavefront/wavefront_renderer.h"
#include "wavefront_test_support.h"

namespace wp {
namespace {

Scene small_room(int spp, std::uint32_t seed = 0) {
    Scene scene = test::scene_from_file("scenes/test/room_small.json");
    scene.render.spp = spp;
    scene.render.seed = seed;
    return scene;
}

TEST(WavefrontImage, BitIdenticalRunToRunAndAcrossWavefrontSizes) {
    Scene scene = small_room(8);
    // 64 paths in flight: many passes and regenerations; 4096: one pass.
    RenderResult a = render_wavefront(scene, {.wavefront = 64}, {});
    RenderResult b = render_wavefront(scene, {.wavefront = 64}, {});
    RenderResult c = render_wavefront(scene, {.wavefront = 4096}, {});
    EXPECT_EQ(a.image.rgb, b.image.rgb);
    EXPECT_EQ(a.image.rgb, c.image.rgb);
    EXPECT_EQ(a.stats.extension_rays, c.stats.extension_rays);
    EXPECT_EQ(a.stats.shadow_rays, c.stats.shadow_rays);
}

// Independent estimates of the same image, 256 spp on each backend as
// kSeeds renders of 32 spp with seeds of their own (wavefront 1..8,
// reference 9..16). The standard error of each 8x8-pixel region mean comes
// from the estimator's own variance: for every pixel, the sample variance
// of its kSeeds values (each render independent of the others), summed
// over the region's pixels (independent too) for both backends:
//   SE^2 = sum_p (s_w,p^2 + s_r,p^2) / kSeeds / n^2.
// Image structure does not enter it (each pixel is compared with itself
// across seeds). The same for the whole image per channel. With 64 x 7 x 2
// degrees of freedom per region's estimate the normal law holds:
// |z| <= kSigmaTolerance (4.5) rejects a correct pair with probability
// 6.8e-6 per comparison, < 4e-4 for the 51 (fixed seeds: a passing run
// passes every time). Measured: worst region |z| 2.3; the whole image's
// standard error is 0.7% of its level, so a bias of 3% fails.
TEST(WavefrontImage, RegionMeansAgreeWithReference) {
    constexpr int kSeeds = 8, kSppPerSeed = 32, kRegion = 8;
    std::vector<Image> wavefront, reference;
    for (int k = 0; k < kSeeds; ++k) {
        wavefront.push_back(render_wavefront(small_room(kSppPerSeed, 1 + k), {}, {}).image);
        reference.push_back(
            render_reference(small_room(kSppPerSeed, 1 + kSeeds + k), ReferenceOptions{2, false}).image);
    }
    const int width = wavefront[0].width, height = wavefront[0].height;
    // Per pixel and channel: the mean over seeds and the variance of that mean.
    auto mean_and_variance = [&](const std::vector<Image>& renders, std::size_t i) {
        test::RunningMean m;
        for (const Image& image : renders) m.add(image.rgb[i]);
        return std::pair{m.mean(), m.standard_error() * m.standard_error()};
    };
    // |region mean difference| / its standard error over the pixels [x0, x1) x [y0, y1), channel c.
    auto z_of = [&](int x0, int x1, int y0, int y1, int c, double& relative_se) {
        double difference = 0.0, variance = 0.0, level = 0.0, n = double(x1 - x0) * (y1 - y0);
        for (int y = y0; y < y1; ++y)
            for (int x = x0; x < x1; ++x) {
                std::size_t i = 3 * (std::size_t(y) * width + x) + c;
                auto [w, w_variance] = mean_and_variance(wavefront, i);
                auto [r, r_variance] = mean_and_variance(reference, i);
                difference += (w - r) / n;
                variance += (w_variance + r_variance) / (n * n);
                level += r / n;
            }
        double standard_error = std::sqrt(variance);
        relative_se = standard_error / level;
        EXPECT_GT(standard_error, 0.0);
        return std::fabs(difference) / standard_error;
    };
    double worst_z = 0.0, largest_relative_se = 0.0, relative_se = 0.0;
    for (int ry = 0; ry < height / kRegion; ++ry)
        for (int rx = 0; rx < width / kRegion; ++rx)
            for (int c = 0; c < 3; ++c) {
                double z = z_of(rx * kRegion, (rx + 1) * kRegion, ry * kRegion, (ry + 1) * kRegion, c, relative_se);
                worst_z = std::max(worst_z, z);
                largest_relative_se = std::max(largest_relative_se, relative_se);
                EXPECT_LE(z, test::kSigmaTolerance) << "region (" << rx << ", " << ry << ") channel " << c;
            }
    double whole_worst_z = 0.0, whole_relative_se = 0.0;
    for (int c = 0; c < 3; ++c) {
        double z = z_of(0, width, 0, height, c, relative_se);
        whole_worst_z = std::max(whole_worst_z, z);
        whole_relative_se = std::max(whole_relative_se, relative_se);
        EXPECT_LE(z, test::kSigmaTolerance) << "whole image, channel " << c;
    }
    std::printf(
        "wavefront vs reference at %d spp: 8x8 regions worst |z| %.2f, largest SE %.3f of the level; "
        "whole image worst |z| %.2f, SE %.4f of the level\n",
        kSeeds * kSppPerSeed, worst_z, largest_relative_se, whole_worst_z, whole_relative_se);
}

// An OpenCL backend with its default options.
struct OpenClBackend {
    const char* name;
    RenderResult (*render)(const Scene& scene);
};

class OpenClAnalytic : public ::testing::TestWithParam<OpenClBackend> {
 protected:
    RenderResult render(const Scene& scene) const { return GetParam().render(scene); }
};

INSTANTIATE_TEST_SUITE_P(
    Backends, OpenClAnalytic,
    ::testing::Values(OpenClBackend{"wavefront", [](const Scene& s) { return render_wavefront(s, {}, {}); }},
                      OpenClBackend{"megakernel", [](const Scene& s) { return render_megakernel(s, {}, {}); }}),
    [](const ::testing::TestParamInfo<OpenClBackend>& info) { return std::string(info.param.name); });

constexpr const char* kEmissiveSphereInterior = R"({
  "camera": {"position": [0, 0, 0], "look_at": [0, 0, -1], "up": [0, 1, 0], "fov_y": 60, "width": 16, "height": 16},
  "render": {"spp": 4, "max_depth": 5, "rr_depth": 100, "seed": 3},
  "materials": {"glow": {"type": "diffuse", "albedo": [0.5, 0.25, 0.75], "emission": [1, 2, 0.5], "two_sided": true}},
  "shapes": [{"type": "sphere", "center": [0.2, -0.1, 0.3], "radius": 2, "material": "glow"}]
})";

// Inside a closed sphere of emission Le and albedo rho, the path sees Le at
// depth 0, and next-event estimation at each of the d diffuse vertices adds
// rho^(k+1) Le with zero variance: area sampling from inside a sphere gives
// cos * cos_light / distance^2 = 1 / (4 R^2) (both angles of a chord are
// equal, distance = 2 R cos), so albedo / pi * Le * cos / pdf = rho Le.
// Every pixel is Le (1 - rho^(d+1)) / (1 - rho), up to float rounding.
TEST_P(OpenClAnalytic, EmissiveSphereInterior) {
    Scene scene = test::scene_from_json(kEmissiveSphereInterior);
    RenderResult result = render(scene);
    const double rho[3] = {0.5, 0.25, 0.75}, le[3] = {1, 2, 0.5};
    int d = scene.render.max_depth;
    for (std::size_t p = 0; p < result.image.rgb.size() / 3; ++p)
        for (int c = 0; c < 3; ++c) {
            double expected = le[c] * (1 - std::pow(rho[c], d + 1)) / (1 - rho[c]);
            ASSERT_NEAR(result.image.rgb[3 * p + c], expected, 2e-5 * expected) << "pixel " << p << " channel " << c;
        }
}

constexpr const char* kSphereUnderBackground = R"({
  "camera": {"position": [0, 0, 0], "look_at": [0, 0, -1], "up": [0, 1, 0], "fov_y": 30, "width": 16, "height": 16},
  "render": {"spp": 2, "max_depth": 4, "rr_depth": 100, "seed": 5, "nee": false},
  "background": [0.8, 0.6, 0.4],
  "materials": {"grey": {"type": "diffuse", "albedo": [0.3, 0.5, 0.7]}},
  "shapes": [{"type": "sphere", "center": [0, 0, -4], "radius": 0.6, "material": "grey"}]
})";

// A convex diffuse sphere under a uniform background B, without other lights
// and without next-event estimation (whose samples of the background would
// vary): every bounce off the sphere escapes it, so a path that hits shows
// exactly rho * B and one that misses shows B. The centre pixels are all sphere; the corner
// pixels all background.
TEST_P(OpenClAnalytic, ConvexSphereUnderBackground) {
    Scene scene = test::scene_from_json(kSphereUnderBackground);
    RenderResult result = render(scene);
    const double rho[3] = {0.3, 0.5, 0.7}, background[3] = {0.8, 0.6, 0.4};
    auto pixel = [&](int x, int y, int c) { return result.image.rgb[3 * (y * 16 + x) + c]; };
    for (int c = 0; c < 3; ++c) {
        for (auto [x, y] : {std::pair{7, 7}, {8, 8}, {7, 8}, {8, 7}})
            EXPECT_NEAR(pixel(x, y, c), rho[c] * background[c], 1e-6);
        for (auto [x, y] : {std::pair{0, 0}, {15, 0}, {0, 15}, {15, 15}})
            EXPECT_NEAR(pixel(x, y, c), background[c], 1e-6);
    }
}

constexpr const char* kPlaneUnderQuadLight = R"({
  "camera": {"position": [0, 0.5, 0], "look_at": [0, 0, 0], "up": [0, 0, -1], "fov_y": 1, "width": 16, "height": 16},
  "render": {"spp": 64, "max_depth": 1, "rr_depth": 100, "seed": 7},
  "materials": {"floor": {"type": "diffuse", "albedo": [0.6, 0.6, 0.6]},
                "light": {"type": "emitter", "radiance": [5, 5, 5]}},
  "shapes": [{"type": "plane", "point": [0, 0, 0], "normal": [0, 1, 0], "material": "floor"},
             {"type": "quad", "corner": [-0.5, 1, -0.5], "edge1": [1, 0, 0], "edge2": [0, 0, 1], "material": "light"}]
})";

// Form factor from a point to a parallel a x b rectangle at height c, the
// point below one corner: F = 1/(2 pi) [X/sqrt(1+X^2) atan(Y/sqrt(1+X^2)) +
// Y/sqrt(1+Y^2) atan(X/sqrt(1+Y^2))], X = a/c, Y = b/c. Below the centre of
// a 1 x 1 light: four corners of 0.5 x 0.5.
double form_factor_below_centre(double half_size, double height) {
    double x = half_size / height, y = half_size / height;
    double corner = (x / std::sqrt(1 + x * x) * std::atan(y / std::sqrt(1 + x * x)) +
                     y / std::sqrt(1 + y * y) * std::atan(x / std::sqrt(1 + y * y))) /
                    (2 * std::numbers::pi);
    return 4 * corner;
}

// A diffuse plane lit by a one-sided square light (direct light only):
// L = rho / pi * E = rho * Le * F. The camera sees a patch about 0.009 wide
// below the centre, where F differs from its centre value by under 1e-4
// relative, so every pixel is an independent 64-sample estimate of the same
// value and the pixels' spread is the estimator's own variance. The light
// and the floor are grey, so the three channels are one estimate, not
// three: they must be equal, and only one enters the mean. The mean of the
// 256 pixels is compared within kSigmaTolerance (4.5) standard errors plus
// 1e-4 for F's variation: false failure about 1e-5 (t with 255 degrees of
// freedom; fixed seed).
TEST_P(OpenClAnalytic, PlaneUnderQuadLight) {
    Scene scene = test::scene_from_json(kPlaneUnderQuadLight);
    RenderResult result = render(scene);
    double expected = 0.6 * 5 * form_factor_below_centre(0.5, 1.0);
    for (std::size_t p = 0; p < result.image.rgb.size() / 3; ++p) {
        ASSERT_EQ(result.image.rgb[3 * p + 1], result.image.rgb[3 * p]) << "pixel " << p;
        ASSERT_EQ(result.image.rgb[3 * p + 2], result.image.rgb[3 * p]) << "pixel " << p;
    }
    test::RunningMean mean = test::channel_mean(result.image, 0);
    ASSERT_EQ(mean.count(), 256u);
    std::printf("plane under a quad light: mean %.6f, expected %.6f, standard error %.2e (z %+.2f)\n", mean.mean(),
                expected, mean.standard_error(), (mean.mean() - expected) / mean.standard_error());
    EXPECT_NEAR(mean.mean(), expected, test::kSigmaTolerance * mean.standard_error() + 1e-4 * expected);
    EXPECT_GT(mean.standard_error(), 0.0);  // next-event estimation over an area light is not exact
}

}  // namespace
}  // namespace wp
