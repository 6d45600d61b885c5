// The film both OpenCL backends accumulate into: the compensated float film
// of devices without fp64, forced on a device that has fp64, against the
// double film, and with sums that would overflow float.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "support/analytic_scenes.h"
#include "wavefront/wavefront_renderer.h"
#include "wavefront/wavefront_test_support.h"

namespace wp {
namespace {

RenderResult render_with_film(const Scene& scene, bool float_film) {
    WavefrontOptions options;
    options.float_film = float_film;
    return render_wavefront(scene, options, {});
}

// Kahan summation keeps a sum of n floats within 2u |sum| + O(n u^2) of the
// exact sum (Higham, "Accuracy and Stability of Numerical Algorithms", 2nd
// ed., section 4.3), u = 2^-24; the film's power-of-two scaling is exact, and
// both images round the same double mean to float at the end. So every pixel
// of the float film is within 3u of the double film's (2u for the sum, one
// rounding of the image), relative to the pixel.
TEST(Film, CompensatedFloatFilmAgreesWithTheDoubleFilm) {
    Scene scene = test::small_room(32, 48);  // 48 spp: a scale of 1/64, not 1/spp
    RenderResult double_film = render_with_film(scene, false);
    RenderResult float_film = render_with_film(scene, true);
    ASSERT_EQ(float_film.image.rgb.size(), double_film.image.rgb.size());
    constexpr double kUnitRoundoff = 0x1p-24;
    double worst = 0.0;
    for (std::size_t i = 0; i < float_film.image.rgb.size(); ++i) {
        double expected = double_film.image.rgb[i], got = float_film.image.rgb[i];
        ASSERT_TRUE(std::isfinite(got)) << i;
        if (expected > 0.0) worst = std::max(worst, std::abs(got - expected) / expected);
        EXPECT_LE(std::abs(got - expected), 3.0 * kUnitRoundoff * expected) << "pixel value " << i;
    }
    std::printf("[figure] float film against double film: worst relative difference %.3g (bound %.3g)\n", worst,
                3.0 * kUnitRoundoff);
}

// Every sample is 2e38, finite: a float sum of two overflows to Inf, and
// Kahan's correction then makes NaN. The scaled film keeps the sum finite and
// the image at 2e38, exactly as the double film has it.
TEST(Film, SumsBeyondFloatRangeStayFinite) {
    test::RenderBlock block{.width = 8, .height = 8, .spp = 2, .max_depth = 0};
    Scene scene = test::inside_emissive_sphere(block, {0.5, 0.5, 0.5}, glm::dvec3(2e38));
    for (bool float_film : {false, true}) {
        SCOPED_TRACE(float_film ? "float film" : "double film");
        RenderResult result = render_with_film(scene, float_film);
        EXPECT_EQ(result.stats.nonfinite, 0u);
        for (float value : result.image.rgb) EXPECT_EQ(value, 2e38f);
    }
}

}  // namespace
}  // namespace wp
