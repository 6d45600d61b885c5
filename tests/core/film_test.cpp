// The exact film sums (kernels/shared/film_sum.h) and the host film: sums
// against 128-bit integer arithmetic, rounding of the smallest values, the
// same bits in any order and any split, conversions to double, and each
// pixel's sample count from a range of work items.
#include "core/film.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <numbers>
#include <random>

namespace wp {
namespace {

__extension__ typedef __int128 int128;

bool same(const film_sum& a, const film_sum& b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// `value` times 2^shift as a film sum (sign-extended to every limb).
film_sum shifted(int128 value, int shift) {
    film_sum s = film_sum_zero();
    const film_limb sign = value < 0 ? ~film_limb(0) : 0;
    film_limb words[5] = {film_limb(value), film_limb(static_cast<unsigned __int128>(value) >> 64), sign, sign, sign};
    for (int i = WP_FILM_LIMBS - 1; i >= 0; --i) {
        int from = i - shift / 64, bit = shift % 64;
        film_limb high = from >= 0 ? words[from] << bit : 0;
        film_limb low = from >= 1 && bit != 0 ? words[from - 1] >> (64 - bit) : 0;
        s.limb[i] = high | low;
    }
    return s;
}

// A film sum that fits 128 bits, as one.
int128 low_128(const film_sum& s) {
    const film_limb sign = (s.limb[1] >> 63) != 0 ? ~film_limb(0) : 0;
    EXPECT_EQ(s.limb[2], sign);
    EXPECT_EQ(s.limb[3], sign);
    return int128((static_cast<unsigned __int128>(s.limb[1]) << 64) | s.limb[0]);
}

// Floats of both signs from 2^-26 to 2^40: with 24-bit significands every
// one is a whole multiple of 2^-49, so 2^49 times their sum is an integer
// that 128 bits hold exactly.
std::vector<float> moderate_floats(std::size_t count, std::uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> exponent(-26.0, 40.0);
    std::vector<float> values(count);
    for (std::size_t i = 0; i < count; ++i)
        values[i] = static_cast<float>((i % 3 == 0 ? -1.0 : 1.0) * std::exp2(exponent(rng)));
    return values;
}

TEST(FilmSum, SumsEqual128BitIntegerArithmetic) {
    const std::vector<float> values = moderate_floats(5000, 1);
    film_sum sum = film_sum_zero();
    int128 exact = 0;  // times 2^49
    for (float v : values) {
        sum = film_sum_add(sum, film_sum_from_float(v));
        exact += int128(std::ldexp(double(v), 49));  // exact: v * 2^49 is an integer below 2^89
    }
    // The film holds 2^100 times the sum: 2^51 times `exact`.
    EXPECT_TRUE(same(sum, shifted(exact, 51)));
    EXPECT_TRUE(same(film_sum_from_float(-3.0f), shifted(-3, 100)));
}

TEST(FilmSum, AnyOrderAndAnySplitGiveTheSameBits) {
    std::mt19937 rng(2);
    std::uniform_int_distribution<std::uint32_t> bits;
    std::vector<float> values;
    while (values.size() < 4000) {  // every finite float, subnormals included
        std::uint32_t b = bits(rng);
        float v;
        std::memcpy(&v, &b, sizeof v);
        if (std::isfinite(v)) values.push_back(v);
    }
    auto sum_of = [](auto first, auto last) {
        film_sum s = film_sum_zero();
        for (auto it = first; it != last; ++it) s = film_sum_add(s, film_sum_from_float(*it));
        return s;
    };
    const film_sum in_order = sum_of(values.begin(), values.end());
    for (std::size_t split : {std::size_t(1), std::size_t(1234), std::size_t(3999)}) {
        film_sum merged =
            film_sum_add(sum_of(values.begin(), values.begin() + split), sum_of(values.begin() + split, values.end()));
        EXPECT_TRUE(same(merged, in_order)) << split;
    }
    std::shuffle(values.begin(), values.end(), rng);
    EXPECT_TRUE(same(sum_of(values.begin(), values.end()), in_order));
}

TEST(FilmSum, ValueMinusItselfIsZero) {
    for (float v : {1.0f, 3.5e-30f, 1e-45f, 3.4e38f, 0.1f}) {
        film_sum s = film_sum_add(film_sum_from_float(v), film_sum_from_float(-v));
        EXPECT_TRUE(same(s, film_sum_zero())) << v;
    }
}

// The quantum is 2^-100; smaller values round to the nearest multiple, ties to even.
TEST(FilmSum, ValuesBelowTheQuantumRoundToNearestEven) {
    auto quanta = [](float v) { return low_128(film_sum_from_float(v)); };
    EXPECT_TRUE(quanta(std::ldexp(1.0f, -100)) == 1);
    EXPECT_TRUE(quanta(std::ldexp(1.0f, -101)) == 0);    // half: to even 0
    EXPECT_TRUE(quanta(std::ldexp(3.0f, -101)) == 2);    // one and a half: to even 2
    EXPECT_TRUE(quanta(std::ldexp(5.0f, -102)) == 1);    // 1.25
    EXPECT_TRUE(quanta(std::ldexp(7.0f, -102)) == 2);    // 1.75
    EXPECT_TRUE(quanta(-std::ldexp(3.0f, -101)) == -2);  // sign after rounding
    EXPECT_TRUE(quanta(std::numeric_limits<float>::denorm_min()) == 0);
}

TEST(FilmSum, ConvertsBackToTheFloatItHolds) {
    for (float v : {1.0f, -2.5f, 3.4e38f, 6.7e-24f, 123456.789f, -0.1f})
        EXPECT_EQ(film_sum_to_double(film_sum_from_float(v)), double(v)) << v;
    EXPECT_EQ(film_sum_to_double(film_sum_zero()), 0.0);
}

TEST(FilmSum, SquaresAreExact) {
    for (float v : {3.0f, -1.5f, 1e10f, std::ldexp(0.75f, -20)})
        EXPECT_EQ(film_sum_to_double(film_sum_from_float_squared(v)), double(v) * double(v)) << v;
}

TEST(FilmSum, DoublesKeepTheirBitsAndHugeOnesClamp) {
    EXPECT_EQ(film_sum_to_double(film_sum_from_double(0.1)), 0.1);
    EXPECT_EQ(film_sum_to_double(film_sum_from_double(-1e40)), -1e40);
    EXPECT_EQ(film_sum_to_double(film_sum_from_double(1e300)), std::ldexp(1.0, WP_FILM_CLAMP_BITS));
}

// Double rounding through a 64-bit window would turn 2^64 + 2^11 + 1 (a
// half-way case decided by the last bit) into 2^64; the sticky bit keeps it.
TEST(FilmSum, ToDoubleRoundsOnceToNearest) {
    film_sum s = film_sum_zero();
    s.limb[1] = 1;                                                // 2^64 quanta ...
    s.limb[0] = 1u << 11;                                         // ... plus half an ulp of 2^64 in double (2^12)
    EXPECT_EQ(film_sum_to_double(s), std::ldexp(1.0, 64 - 100));  // tie: to even
    s.limb[0] += 1;                                               // just above half
    EXPECT_EQ(film_sum_to_double(s), std::ldexp(1.0 + std::ldexp(1.0, -52), 64 - 100));
}

TEST(Film, SampleCountsFollowTheRange) {
    // 5 pixels, items 7..18: pixel p gets items p, p + 5, p + 10, p + 15 in range.
    Film film = Film::empty(5, 1, 7, false);
    film.items.end = 18;
    std::vector<std::uint64_t> counts;
    for (std::uint64_t p = 0; p < 5; ++p) counts.push_back(film.samples_of(p));
    EXPECT_EQ(counts, (std::vector<std::uint64_t>{2, 2, 3, 2, 2}));  // 10 15 | 11 16 | 7 12 17 | 8 13 | 9 14
    EXPECT_EQ(film.min_samples(), 2u);
    EXPECT_EQ(film.max_samples(), 3u);
}

TEST(Film, AppendAddsAdjacentRangesOnly) {
    Film a = Film::empty(2, 1, 0, false), b = Film::empty(2, 1, 4, false), c = Film::empty(2, 1, 5, false);
    a.items.end = 4;
    b.items.end = 6;
    a.sums[0] = film_sum_from_float(1.0f);
    b.sums[0] = film_sum_from_float(2.0f);
    EXPECT_THROW(a.append(c), std::invalid_argument);
    a.append(b);
    EXPECT_EQ(a.items, (ItemRange{0, 6}));
    EXPECT_EQ(film_sum_to_double(a.sums[0]), 3.0);
    EXPECT_EQ(a.image().rgb[0], 1.0f);  // 3 over pixel 0's 3 samples
}

// Adaptive sampling: 5 pixels with 4 samples each (items 0..20), then a
// round over pixels 1 and 3: item w of the round is pixel {1, 3}[w % 2],
// sample w / 2, from 8 (sample 4 of each) on.
TEST(Film, RoundsCountEachPixelsOwnSamples) {
    Film film = Film::empty(5, 1, 0, false);
    film.items.end = 20;
    for (int p = 0; p < 5; ++p) film.sums[3 * p] = film_sum_from_float(float(4 * (p + 1)));
    EXPECT_THROW(film.begin_round({}), std::invalid_argument);
    film.begin_round({1, 3});
    EXPECT_EQ(film.items, (ItemRange{8, 8}));
    EXPECT_EQ(film.round_pixel_count(), 2u);
    film.items.end = 13;  // samples 4, 5 of pixels 1 and 3, and sample 6 of pixel 1
    EXPECT_EQ(film.sample_counts(), (std::vector<std::uint64_t>{4, 7, 4, 6, 4}));
    EXPECT_EQ(film.samples_of(1), 7u);
    EXPECT_EQ(film.samples_of(2), 4u);
    EXPECT_EQ(film.min_samples(), 4u);
    EXPECT_EQ(film.max_samples(), 7u);
    EXPECT_EQ(film.image().rgb[3 * 1], 8.0f / 7.0f);  // pixel 1's sum over its own 7 samples
    EXPECT_EQ(film.image().rgb[3 * 2], 3.0f);
    EXPECT_THROW(film.begin_round({0, 1}), std::invalid_argument);  // 4 and 7 samples: not one round
    Film next = Film::empty(5, 1, 13, false);
    EXPECT_THROW(film.append(next), std::invalid_argument);
}

// The ranks' films of interleaved slices: sums added whatever the ranges,
// this film's range kept; sizes and squares must still match.
TEST(Film, AddSumsAddsAnyRangesAndKeepsItsOwn) {
    Film a = Film::empty(2, 1, 0, true), b = Film::empty(2, 1, 9, true);
    a.items.end = 2;
    b.items.end = 11;
    a.sums[3] = film_sum_from_float(1.5f);
    b.sums[3] = film_sum_from_float(2.0f);
    b.squares[0] = film_sum_from_float(4.0f);
    a.add_sums(b);
    EXPECT_EQ(a.items, (ItemRange{0, 2}));
    EXPECT_EQ(film_sum_to_double(a.sums[3]), 3.5);
    EXPECT_EQ(film_sum_to_double(a.squares[0]), 4.0);
    EXPECT_THROW(a.add_sums(Film::empty(1, 2, 0, true)), std::invalid_argument);
    EXPECT_THROW(a.add_sums(Film::empty(2, 1, 0, false)), std::invalid_argument);
}

// SPPM's image from a hand-built photon estimate: 3 pixels, 4 iterations
// (items 0..12), 1,000 photons emitted per iteration, so 4,000 in all. A
// pixel's value is its camera passes' mean plus tau / (4,000 pi r^2): every
// photon emitted stands for its flux over the disc, whether or not it came
// near (Hachisuka and Jensen 2009, eq. 8). Pixel 0: r = 1/2, tau = (1500,
// 3000, 750) pi, so tau / (1000 pi) = (1.5, 3, 0.75) on top of Ld = (0.5,
// 0.25, 0); pixel 1 has had no visible point (r = 0): Ld alone; pixel 2:
// r = 1/4, tau = 50 pi, so 50 / 250 = 0.2, no Ld. Dividing by the photons
// plus one, or the iterations plus one, or by r for r^2, misses these by
// far more than the float rounding allowed.
TEST(Film, SppmImageIsTheFluxOverThePhotonsEmittedAndTheDisc) {
    const double pi = std::numbers::pi;
    Film film = Film::empty(3, 1, 0, false);
    film.items.end = 12;
    const double ld[3][3] = {{0.5, 0.25, 0.0}, {1.0, 2.0, 0.125}, {0.0, 0.0, 0.0}};
    for (int p = 0; p < 3; ++p)
        for (int c = 0; c < 3; ++c) film.sums[3 * p + c] = film_sum_from_double(4.0 * ld[p][c]);
    film.photons = PhotonEstimate::start(3, 1000);
    film.photons.count = {40.0, 0.0, 3.0};
    film.photons.radius = {0.5, 0.0, 0.25};
    film.photons.footprint = {0.25, 0.0, 0.5};  // the footprint takes no part in the image
    film.photons.flux = {1500 * pi, 3000 * pi, 750 * pi, 0.0, 0.0, 0.0, 50 * pi, 50 * pi, 0.0};
    const Image image = film.image();
    const std::vector<float> expected{2.0f, 3.25f, 0.75f, 1.0f, 2.0f, 0.125f, 0.2f, 0.2f, 0.0f};
    for (std::size_t i = 0; i < expected.size(); ++i) EXPECT_FLOAT_EQ(image.rgb[i], expected[i]) << i;
}

}  // namespace
}  // namespace wp
