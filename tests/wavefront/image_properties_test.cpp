// Whole-image properties of the wavefront: determinism, independence of the
// wavefront size, statistical agreement with the reference, analytic scenes.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "reference/reference_renderer.h"
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
    RenderResult a = render_wavefront(scene, {"", 64}, {});
    RenderResult b = render_wavefront(scene, {"", 64}, {});
    RenderResult c = render_wavefront(scene, {"", 4096}, {});
    EXPECT_EQ(a.image.rgb, b.image.rgb);
    EXPECT_EQ(a.image.rgb, c.image.rgb);
    EXPECT_EQ(a.stats.extension_rays, c.stats.extension_rays);
    EXPECT_EQ(a.stats.shadow_rays, c.stats.shadow_rays);
}

// Independent estimates (different seeds) of the same image: the difference
// of two 8x8-pixel region means has a standard deviation of at most
// sqrt(s1^2 + s2^2 / n) where s are the pixel standard deviations within the
// region (which include the image's own variation, so the bound is
// conservative). |z| < 4.4 per region: a false failure below 1e-5 per region,
// 2e-4 for the 16 regions.
TEST(WavefrontImage, RegionMeansAgreeWithReferenceAt64Spp) {
    RenderResult wavefront = render_wavefront(small_room(64, 1), {}, {});
    RenderResult reference = render_reference(small_room(64, 2), ReferenceOptions{2, false});
    const Image& w = wavefront.image;
    constexpr int kRegion = 8;
    for (int ry = 0; ry < w.height / kRegion; ++ry)
        for (int rx = 0; rx < w.width / kRegion; ++rx)
            for (int c = 0; c < 3; ++c) {
                double sum[2] = {0, 0}, sum2[2] = {0, 0};
                for (int y = ry * kRegion; y < (ry + 1) * kRegion; ++y)
                    for (int x = rx * kRegion; x < (rx + 1) * kRegion; ++x) {
                        std::size_t i = 3 * (std::size_t(y) * w.width + x) + c;
                        double v[2] = {w.rgb[i], reference.image.rgb[i]};
                        for (int k = 0; k < 2; ++k) sum[k] += v[k], sum2[k] += v[k] * v[k];
                    }
                double n = kRegion * kRegion, variance = 0;
                for (int k = 0; k < 2; ++k) variance += (sum2[k] - sum[k] * sum[k] / n) / (n - 1) / n;
                double difference = sum[0] / n - sum[1] / n;
                EXPECT_LE(std::fabs(difference), 4.4 * std::sqrt(variance) + 1e-6)
                    << "region (" << rx << ", " << ry << ") channel " << c;
            }
}

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
TEST(WavefrontAnalytic, EmissiveSphereInterior) {
    Scene scene = test::scene_from_json(kEmissiveSphereInterior);
    RenderResult result = render_wavefront(scene, {}, {});
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
  "render": {"spp": 2, "max_depth": 4, "rr_depth": 100, "seed": 5},
  "background": [0.8, 0.6, 0.4],
  "materials": {"grey": {"type": "diffuse", "albedo": [0.3, 0.5, 0.7]}},
  "shapes": [{"type": "sphere", "center": [0, 0, -4], "radius": 0.6, "material": "grey"}]
})";

// A convex diffuse sphere under a uniform background B, without lights: every
// bounce off the sphere escapes it, so a path that hits shows exactly rho * B
// and one that misses shows B. The centre pixels are all sphere; the corner
// pixels all background.
TEST(WavefrontAnalytic, ConvexSphereUnderBackground) {
    Scene scene = test::scene_from_json(kSphereUnderBackground);
    RenderResult result = render_wavefront(scene, {}, {});
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
// relative. The image mean is compared within 4.4 standard errors (from the
// pixel spread; false failure about 1e-5).
TEST(WavefrontAnalytic, PlaneUnderQuadLight) {
    Scene scene = test::scene_from_json(kPlaneUnderQuadLight);
    RenderResult result = render_wavefront(scene, {}, {});
    double expected = 0.6 * 5 * form_factor_below_centre(0.5, 1.0);
    double sum = 0, sum2 = 0, n = result.image.rgb.size();
    for (float v : result.image.rgb) sum += v, sum2 += double(v) * v;
    double mean = sum / n, standard_error = std::sqrt((sum2 / n - mean * mean) / (n - 1));
    EXPECT_NEAR(mean, expected, 4.4 * standard_error + 1e-4 * expected);
    EXPECT_GT(standard_error, 0.0);  // next-event estimation over an area light is not exact
}

}  // namespace
}  // namespace wp
