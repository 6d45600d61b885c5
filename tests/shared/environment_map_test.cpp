// The environment map (kernels/shared/environment_map.h and the host's
// distribution, src/scene/environment_layout.h), float and double: its
// lookup against Mitsuba 3.9.1's values, its sampling against its density (a
// chi-square test), the density's integral over the sphere, and the density
// of a constant map (nearly uniform over the sphere: the sin(theta) of the
// texels' weights cancels the map's Jacobian).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <numbers>
#include <optional>
#include <vector>

#include "core/shared_math.h"
#include "scene/environment_layout.h"
#include "support/real_types.h"
#include "support/sphere_chi_square.h"
#include "support/statistics.h"

namespace {
// A namespace of its own: the sanitizer build compiles test files together (unity).
namespace environment_map_test {

using wp::test::Vec3;

template <class Real>
class EnvironmentMaps : public ::testing::Test {};
TYPED_TEST_SUITE(EnvironmentMaps, wp::test::RealTypes, wp::test::RealTypeNames);

wp::Scene scene_with_map(int width, int height, const std::vector<float>& texels, double scale,
                         const glm::dmat3& to_world) {
    wp::Scene scene;
    scene.environment_map = wp::EnvironmentMap{"test.exr", width, height, texels, scale, to_world, ""};
    return scene;
}

// 4 x 3 texels, texel (x, y) = (1 + x + 10 y, (x + 1) / 2, (y + 1) / 4).
std::vector<float> ramp_texels() {
    std::vector<float> texels;
    for (int y = 0; y < 3; ++y) {
        for (int x = 0; x < 4; ++x) {
            texels.insert(texels.end(), {float(1 + x + 10 * y), 0.5f * float(x + 1), 0.25f * float(y + 1)});
        }
    }
    return texels;
}

// Mitsuba 3.9.1's envmap (llvm_ad_rgb) of ramp_texels, its eval for a ray
// leaving along each direction (normalized), printed to 8 digits: columns
// centre-aligned and wrapping, rows corner-aligned, bilinear.
TYPED_TEST(EnvironmentMaps, RadianceIsMitsubasLookup) {
    using R = TypeParam;
    using M = wp::SharedMath<R>;
    const wp::EnvironmentLayout<R> layout =
        wp::environment_layout<R>(scene_with_map(4, 3, ramp_texels(), 1.0, glm::dmat3(1.0)));
    struct Case {
        glm::dvec3 direction, mitsuba;
    };
    const Case cases[] = {
        {{0.3, 0.5, -0.8}, {8.444086, 0.9073994, 0.4157322}},  {{-0.7, 0.1, 0.2}, {12.453803, 1.6614144, 0.47827435}},
        {{0.0, -0.9, 0.4}, {19.837502, 1.25, 0.6834375}},      {{0.6, -0.2, 0.77}, {13.365118, 1.0392976, 0.53216314}},
        {{0.05, 0.99, 0.1}, {2.9207518, 1.1024166, 0.267898}},
    };
    for (const Case& c : cases) {
        const Vec3<R> d(glm::normalize(c.direction));
        const glm::dvec3 radiance(M::environment_radiance(layout.map, layout.data.data(), d));
        for (int k = 0; k < 3; ++k)
            EXPECT_NEAR(radiance[k], c.mitsuba[k], 2e-5 * c.mitsuba[k]) << c.direction.x << " channel " << k;
    }
}

// A map with structure: a dark band, a black cell region (no density
// there), a bright spot, under a frame that turns its pole away from +y.
struct TestMap {
    int width, height;
    std::vector<float> texels;
    glm::dmat3 to_world;
};

TestMap structured_map(bool turned) {
    TestMap map{16, 9, {}, glm::dmat3(1.0)};
    for (int y = 0; y < map.height; ++y) {
        for (int x = 0; x < map.width; ++x) {
            float value = 0.2f + 0.1f * float(x % 5) + 0.05f * float(y);
            if (x >= 4 && x < 7 && y >= 5 && y < 8) value = 0.0f;  // two cells' rows of black
            if (x == 11 && y == 2) value = 25.0f;                  // the sun
            map.texels.insert(map.texels.end(), {value, 0.5f * value, 0.25f * value + 0.01f});
        }
    }
    if (turned)
        map.to_world = glm::dmat3(glm::rotate(glm::dmat4(1.0), 0.9, glm::normalize(glm::dvec3(1.0, 0.3, -0.4))));
    return map;
}

// The histogram's pole: not the map's (+y), about which the density's
// 1 / sin(t) would leave the quadrature of the histogram's polar cells short.
const glm::dvec3 kPole = glm::normalize(glm::dvec3(0.3, 0.2, 0.9));

// The samples follow the density environment_pdf gives (Mitsuba's chi2
// test, support/sphere_chi_square.h: 32 x 64 cells of equal solid angle
// about kPole, 2e5 samples, cells expected to hold fewer than 5 pooled). 2 cases (the map in its own frame and turned),
// each tested at level 1 - (1 - 1e-3)^(1/2) = 5.0e-4 (Sidak's correction): a correct sampler fails this test (of one
// precision) with probability 1e-3; the seeds are fixed, so the outcome is the same on every run. Every sample's
// density is environment_pdf's for its direction and positive, and its
// radiance the lookup's; the density integrates to 1 over the sphere.
TYPED_TEST(EnvironmentMaps, SamplesFollowTheirPdf) {
    using R = TypeParam;
    using M = wp::SharedMath<R>;
    const double level = 1.0 - std::pow(1.0 - wp::test::kChiSquareAlpha, 1.0 / 2.0);
    const double relative = std::is_same_v<R, float> ? 2e-3 : 1e-9;  // the round trip through the direction
    std::uint64_t seed = 7;
    for (bool turned : {false, true}) {
        const TestMap map = structured_map(turned);
        const wp::EnvironmentLayout<R> layout =
            wp::environment_layout<R>(scene_with_map(map.width, map.height, map.texels, 1.0, map.to_world));
        wp::test::UnitRandom<R> random(seed++);
        int checked = 0;
        auto sample = [&]() -> std::optional<glm::dvec3> {
            const R u1 = random(), u2 = random();
            const typename M::EnvironmentSample s = M::environment_sample(layout.map, layout.data.data(), u1, u2);
            if (!(s.pdf > R(0))) return std::nullopt;
            if (checked < 2000) {  // the sample's density and radiance are those of its direction
                ++checked;
                const R pdf = M::environment_pdf(layout.map, layout.data.data(), s.direction);
                EXPECT_NEAR(double(pdf), double(s.pdf), relative * double(s.pdf) + 1e-6);
                const glm::dvec3 radiance(M::environment_radiance(layout.map, layout.data.data(), s.direction));
                EXPECT_NEAR(radiance.x, double(s.radiance.x), relative * 30.0);
            }
            return glm::dvec3(s.direction);
        };
        auto pdf = [&](const glm::dvec3& wi) {
            return double(M::environment_pdf(layout.map, layout.data.data(), Vec3<R>(wi)));
        };
        const wp::test::SphereChiSquare result = wp::test::sphere_chi_square(sample, pdf, kPole, 200000);
        EXPECT_TRUE(result.failure.empty()) << "turned " << turned << ": " << result.describe();
        EXPECT_GT(result.chi_square.p_value, level) << "turned " << turned << ": " << result.describe();
        EXPECT_EQ(result.sampled_fraction, 1.0) << "turned " << turned;
    }
}

// The density integrates to 1 over the sphere: in (u, v), where the solid
// angle is 2 pi^2 sin(t) du dv, by the midpoint rule on a grid 8 times finer
// than the cells, whose cells lie inside the map's (the density times
// sin(t) is bilinear on each, which the midpoint rule integrates exactly):
// 1 within the densities' rounding. The density's 1 / sin(t), the Jacobian, is what makes it 1.
TYPED_TEST(EnvironmentMaps, PdfIntegratesToOne) {
    using R = TypeParam;
    using M = wp::SharedMath<R>;
    const TestMap map = structured_map(true);
    const wp::EnvironmentLayout<R> layout =
        wp::environment_layout<R>(scene_with_map(map.width, map.height, map.texels, 1.0, map.to_world));
    const int columns = 8 * map.width, rows = 8 * (map.height - 1);
    double integral = 0.0;
    for (int j = 0; j < rows; ++j) {
        const double theta = std::numbers::pi * (j + 0.5) / rows;
        for (int i = 0; i < columns; ++i) {
            const double phi = 2.0 * std::numbers::pi * (i + 0.5) / columns;
            const glm::dvec3 local(std::sin(theta) * std::sin(phi), std::cos(theta), -std::sin(theta) * std::cos(phi));
            const double pdf =
                double(M::environment_pdf(layout.map, layout.data.data(), Vec3<R>(map.to_world * local)));
            integral += pdf * 2.0 * std::numbers::pi * std::numbers::pi * std::sin(theta) / (double(columns) * rows);
        }
    }
    const double tolerance = std::is_same_v<R, float> ? 1e-4 : 1e-9;
    EXPECT_NEAR(integral, 1.0, tolerance);
}

// A constant map's texels weigh the mean of sin(t) over their band of rows,
// s_y (t from half a row above to half a row below, within [0, pi]), so its
// density at t between rows y and y + 1 is the blend of s_y and s_y+1 over
// (the cells' mean weight times 2 pi^2 sin(t)): near 1 / (4 pi), the uniform
// sphere's, away from the poles (within 0.2% at the equator with these
// 64 x 33 texels); checked at every direction of a grid to the cumulative
// sums' rounding. Without sin(t) in the weights it would be
// 1 / (2 pi^2 sin(t)), 57% above it at the equator.
TYPED_TEST(EnvironmentMaps, ConstantMapsDensityIsNearlyUniform) {
    using R = TypeParam;
    using M = wp::SharedMath<R>;
    const int width = 64, height = 33, rows = height - 1;
    const wp::EnvironmentLayout<R> layout = wp::environment_layout<R>(
        scene_with_map(width, height, std::vector<float>(std::size_t(3 * width * height), 0.7f), 2.0, glm::dmat3(1.0)));
    const double row_angle = std::numbers::pi / rows;
    auto band_mean_sin = [&](int y) {  // integral of sin over the band / its width
        const double top = std::max((y - 0.5) * row_angle, 0.0);
        const double bottom = std::min((y + 0.5) * row_angle, std::numbers::pi);
        return (std::cos(top) - std::cos(bottom)) / (bottom - top);
    };
    double mean_cell = 0.0;
    for (int y = 0; y < rows; ++y) mean_cell += 0.5 * (band_mean_sin(y) + band_mean_sin(y + 1)) / rows;
    const double tolerance = std::is_same_v<R, float> ? 1e-4 : 1e-9;
    for (double theta = 0.03; theta < std::numbers::pi; theta += 0.05) {
        const int row = std::min(int(theta / row_angle), rows - 1);
        const double fy = theta / row_angle - row;
        const double weight = (1.0 - fy) * band_mean_sin(row) + fy * band_mean_sin(row + 1);
        const double expected = weight / (mean_cell * 2.0 * std::numbers::pi * std::numbers::pi * std::sin(theta));
        for (double phi = 0.0; phi < 2.0 * std::numbers::pi; phi += 0.3) {
            const glm::dvec3 d(std::sin(theta) * std::sin(phi), std::cos(theta), -std::sin(theta) * std::cos(phi));
            const double pdf = double(M::environment_pdf(layout.map, layout.data.data(), Vec3<R>(d)));
            EXPECT_NEAR(pdf, expected, tolerance * expected) << "theta " << theta << " phi " << phi;
        }
    }
    const double equator = double(M::environment_pdf(layout.map, layout.data.data(), Vec3<R>(1.0, 0.0, 0.0)));
    EXPECT_NEAR(equator, 0.25 / std::numbers::pi, 2e-3 * 0.25 / std::numbers::pi);
    // and the radiance is the map's value times the scale, everywhere
    const glm::dvec3 radiance(M::environment_radiance(layout.map, layout.data.data(), Vec3<R>(0.0, 1.0, 0.0)));
    EXPECT_NEAR(radiance.y, 1.4, 1e-6);
}

}  // namespace environment_map_test
}  // namespace
