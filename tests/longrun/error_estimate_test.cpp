// --target-error: the estimate on films of known samples, its schedule, and
// the stopping point and image, the same bits on every backend and
// wavefront size.
#include "longrun/error_estimate.h"

#include <gtest/gtest.h>

#include <cstring>

#include "longrun/render_loop.h"
#include "megakernel/megakernel_renderer.h"
#include "reference/reference_renderer.h"
#include "wavefront/wavefront_renderer.h"
#include "wavefront/wavefront_test_support.h"

namespace wp {
namespace {

TEST(ErrorEstimate, ChecksGrowByAQuarter) {
    std::vector<std::uint64_t> checks{next_error_check(0)};
    while (checks.size() < 10) checks.push_back(next_error_check(checks.back()));
    EXPECT_EQ(checks, (std::vector<std::uint64_t>{4, 5, 6, 7, 8, 10, 12, 15, 18, 22}));
    // Between two checks (a resumed render), the schedule's next one.
    EXPECT_EQ(next_error_check(20), 22u);
    EXPECT_EQ(next_error_check(9), 10u);
}

// One pixel: samples 1 and 3 in every channel (mean 2, s^2 = 2, standard
// error 1): 1 / 2. A second pixel of samples 2 and 2 adds no variance and
// the same mean: sqrt(1/2) / 2.
TEST(ErrorEstimate, IsTheRmsStandardErrorOverTheMeanPixel) {
    auto film_of = [](const std::vector<std::vector<float>>& pixels) {
        Film film = Film::empty(int(pixels.size()), 1, 0, true);
        for (std::size_t p = 0; p < pixels.size(); ++p)
            for (int c = 0; c < 3; ++c)
                for (float v : pixels[p]) {
                    film.sums[3 * p + c] = film_sum_add(film.sums[3 * p + c], film_sum_from_float(v));
                    film.squares[3 * p + c] = film_sum_add(film.squares[3 * p + c], film_sum_from_float_squared(v));
                }
        film.items.end = pixels.size() * pixels[0].size();
        return film;
    };
    EXPECT_DOUBLE_EQ(relative_standard_error(film_of({{1, 3}})), 0.5);
    EXPECT_DOUBLE_EQ(relative_standard_error(film_of({{1, 3}, {2, 2}})), std::sqrt(0.5) / 2);
    EXPECT_EQ(relative_standard_error(film_of({{0, 0}})), 0.0);  // black: nothing to estimate
    Film uneven = film_of({{1, 3}, {2, 2}});
    uneven.items.end = 3;  // pixel 0 has 2 samples, pixel 1 one
    EXPECT_THROW(relative_standard_error(uneven), std::invalid_argument);
}

// The room at 24x24, up to 256 spp, target 25% (its glass and mirror make
// fireflies: 14% at 256 spp): every backend stops at the
// same check with the same film bits, whatever the wavefront size.
TEST(TargetError, StopsAtTheSameSampleWithTheSameBitsEverywhere) {
    Scene scene = test::small_room(24, 256);
    const std::uint64_t pixels = 24 * 24;
    auto run = [&](FilmRenderer& renderer) {
        LongRunPlan plan;
        plan.items = {0, pixels * 256};
        plan.pixels = pixels;
        plan.target_error = 0.25;
        return run_long_render(renderer, plan, {});
    };
    WavefrontOptions small, large;
    small.wavefront = 256;
    small.film_squares = large.film_squares = true;
    large.wavefront = 4096;
    const LongRunResult first = run(*make_wavefront_renderer(scene, small, {}));
    EXPECT_EQ(first.reason, StopReason::TargetError);
    EXPECT_LE(first.error, 0.25);
    const std::uint64_t spp = first.film.items.end / pixels;
    EXPECT_EQ(first.film.items.end % pixels, 0u);
    std::printf("[figure] room 24x24, target error 0.25: stopped at %llu spp, estimate %.4f\n",
                static_cast<unsigned long long>(spp), first.error);
    const LongRunResult others[] = {
        run(*make_wavefront_renderer(scene, large, {})),
        run(*make_megakernel_renderer(scene, {"", false, true}, {})),
        run(*make_reference_renderer(scene, {2, false, true})),
    };
    for (const LongRunResult& other : others) {
        EXPECT_EQ(other.film.items, first.film.items);
        EXPECT_EQ(other.error, first.error);
        EXPECT_EQ(
            std::memcmp(other.film.sums.data(), first.film.sums.data(), sizeof(film_sum) * first.film.sums.size()), 0);
    }
}

}  // namespace
}  // namespace wp
