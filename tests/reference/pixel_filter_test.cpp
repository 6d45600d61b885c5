// The pixel filters (kernels/shared/pixel_filter.h) against their definition:
// the camera sees an emitter of radiance Le over the right half of the film
// and black over the left, the edge on a pixel boundary. A pixel whose centre
// lies d pixels left of the edge then has the expected value
//   Le * (the filter's normalised integral over x > d),
// computed here by quadrature of the filter (tent: max(0, 1 - |x| / r);
// gaussian: the Gaussian of standard deviation s truncated at 4 s), not by
// the sampler under test; and within 2.7e-4 Le of the same integral of
// Mitsuba 3's gaussian, which subtracts its value at 4 s (the bound
// pixel_filter.h states, checked here too).
//
// Acceptance: per column (expect_columns_match says which bound where),
// |mean - expected| <= 4.5 standard errors of the mean over the column's
// pixels (independent; which side of the edge the samples land on is the
// estimator's only variance) plus 2e-6 Le for rounding. A normal estimate
// falls outside with probability 6.8e-6; the at most 2 x 2 x 2 x 16 column
// checks here fail spuriously with probability < 1e-3, and the seeds are
// fixed. The box filter is exact: its pixels are 0 or Le.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <type_traits>

#include "reference/reference_renderer.h"
#include "support/analytic_scenes.h"
#include "support/image_statistics.h"
#include "support/real_types.h"

namespace {
namespace pixel_filter_test {

constexpr int kWidth = 16, kHeight = 64;
constexpr double kLe = 2.0;

// The camera at the origin looks down -z at an emitting quad that covers
// x >= 0 of the plane z = -1 as far as the view reaches: film column
// kWidth / 2 begins exactly at the quad's edge.
wp::Scene half_lit_film(const wp::PixelFilter& filter) {
    wp::test::RenderBlock block{.width = kWidth, .height = kHeight, .spp = 16, .max_depth = 1};
    wp::Scene scene = wp::test::empty_scene(block, {0, 0, -1}, 40.0);
    scene.camera.filter = filter;
    // edge1 x edge2 = (0, 0, 100): the quad faces the camera.
    scene.quads.push_back(
        {{0, -10, -1}, {10, 0, 0}, {0, 20, 0}, wp::test::add_material(scene, wp::test::emitter(glm::dvec3(kLe)))});
    wp::build_light_table(scene);
    return scene;
}

// The filter's value at offset x (one axis), unnormalised; `windowed`: a
// gaussian less its value at the window, as Mitsuba 3 defines it.
double filter_value(const wp::PixelFilter& filter, double x, bool windowed = false) {
    if (filter.type == wp::FilterType::Tent) return std::fmax(0.0, 1.0 - std::fabs(x) / filter.radius);
    auto g = [&](double t) { return std::exp(-t * t / (2.0 * filter.stddev * filter.stddev)); };
    if (std::fabs(x) > 4.0 * filter.stddev) return 0.0;
    return g(x) - (windowed ? g(4.0 * filter.stddev) : 0.0);
}

double filter_radius(const wp::PixelFilter& filter) {
    return filter.type == wp::FilterType::Tent ? filter.radius : 4.0 * filter.stddev;
}

// The normalised integral of the filter over x > d (composite Simpson's rule
// on 20000 intervals: error far below the test's tolerance for these kinks).
double filter_mass_beyond(const wp::PixelFilter& filter, double d, bool windowed = false) {
    const double r = filter_radius(filter);
    auto integral = [&](double a, double b) {
        if (b <= a) return 0.0;
        const int n = 20000;
        const double h = (b - a) / n;
        double sum = filter_value(filter, a, windowed) + filter_value(filter, b, windowed);
        for (int i = 1; i < n; ++i) sum += (i % 2 ? 4.0 : 2.0) * filter_value(filter, a + i * h, windowed);
        return sum * h / 3.0;
    };
    // Split at 0, the tent's kink, so that Simpson's rule sees smooth pieces.
    auto over = [&](double a, double b) { return integral(a, std::fmin(b, 0.0)) + integral(std::fmax(a, 0.0), b); };
    return over(std::fmax(d, -r), r) / over(-r, r);
}

// Mitsuba's windowed gaussian spreads an edge within 2.7e-4 of the truncated
// one (pixel_filter.h's bound), at every distance from the edge.
TEST(PixelFilter, TruncatedGaussianWithinItsBoundOfMitsubasWindowed) {
    const wp::PixelFilter gaussian{.type = wp::FilterType::Gaussian, .stddev = 0.5};
    double largest = 0.0;
    for (double d = -2.0; d <= 2.0; d += 1.0 / 64.0)
        largest =
            std::fmax(largest, std::fabs(filter_mass_beyond(gaussian, d) - filter_mass_beyond(gaussian, d, true)));
    EXPECT_LE(largest, 2.7e-4);
    EXPECT_GE(largest, 2.6e-4);  // the bound is the difference, not a loose guess
}

template <class Real>
class PixelFilterRender : public ::testing::Test {
 protected:
    static wp::Image render(const wp::Scene& scene) {
        return wp::render_reference(scene, {.threads = 2, .double_precision = std::is_same_v<Real, double>}).image;
    }

    // Each column against Le times the filter's mass p on the lit side: exactly
    // where the filter cannot reach the edge; within the standard error where
    // at least 1% of the samples land on the far side (some 10 of the
    // column's 1024: the column mean is then near normal); within 0.02 Le
    // where fewer do, as the spread of a handful of rare samples is no
    // standard error.
    static void expect_columns_match(const wp::PixelFilter& filter, const std::string& what) {
        wp::Image image = render(half_lit_film(filter));
        for (int column = 0; column < kWidth; ++column) {
            double distance_to_edge = kWidth / 2 - (column + 0.5);
            double p = filter_mass_beyond(filter, distance_to_edge), far_side = std::fmin(p, 1.0 - p);
            double expected = kLe * p;
            wp::test::RunningMean mean = wp::test::channel_mean(image, 0, [&](int x, int) { return x == column; });
            double tolerance = far_side == 0.0   ? 0.0
                               : far_side < 0.01 ? 0.02 * kLe
                                                 : wp::test::kSigmaTolerance * mean.standard_error();
            EXPECT_NEAR(mean.mean(), expected, tolerance + 2e-6 * kLe)
                << what << ", column " << column << ", far side " << far_side << ", standard error "
                << mean.standard_error();
        }
    }
};
TYPED_TEST_SUITE(PixelFilterRender, wp::test::RealTypes, wp::test::RealTypeNames);

TYPED_TEST(PixelFilterRender, BoxKeepsEachSampleInItsPixel) {
    wp::Image image = this->render(half_lit_film({}));
    for (int y = 0; y < kHeight; ++y)
        for (int x = 0; x < kWidth; ++x)
            ASSERT_EQ(wp::test::pixel_channel(image, x, y, 0), x < kWidth / 2 ? 0.0f : float(kLe)) << x << ", " << y;
}

TYPED_TEST(PixelFilterRender, TentSpreadsAsItsIntegral) {
    for (double radius : {1.0, 2.5}) {
        this->expect_columns_match({.type = wp::FilterType::Tent, .radius = radius},
                                   "tent of radius " + std::to_string(radius));
    }
}

TYPED_TEST(PixelFilterRender, GaussianSpreadsAsItsIntegral) {
    for (double stddev : {0.5, 0.8}) {
        this->expect_columns_match({.type = wp::FilterType::Gaussian, .stddev = stddev},
                                   "gaussian of stddev " + std::to_string(stddev));
    }
}

}  // namespace pixel_filter_test
}  // namespace
