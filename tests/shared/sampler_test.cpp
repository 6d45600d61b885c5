// The camera's sampler (kernels/shared/sampler.h): Sobol's points, each
// prefix of 2^m samples a (0,m,2)-net after both scrambles and each choice's
// numbers stratified, every number uniform over pixels, the streams
// independent of one another, and the error
// on a smooth integrand far below independent numbers'. Chi-square tests at
// kChiSquareAlpha (1e-3) with fixed keys; see support/statistics.h.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <set>
#include <utility>
#include <vector>

#include "core/shared_math.h"
#include "support/statistics.h"

namespace {

using F = wp::SharedMath<float>;
using D = wp::SharedMath<double>;
using wp::test::kChiSquareAlpha;

// The camera's number with the Sobol' sampler (render.sampler "sobol").
template <class M>
auto camera_uniform(std::uint32_t seed, std::uint32_t pixel, std::uint32_t sample, std::uint32_t bounce,
                    std::uint32_t dimension) {
    return M::camera_uniform(seed, pixel, sample, bounce, dimension, 1);
}

// Sobol's point i in the textbook way (Bratley and Fox, ACM TOMS 14(1),
// 1988): the XOR of the direction numbers v_k of i's set bits, v_k from the
// recurrence of the dimension's primitive polynomial (x + 1 for the second:
// m_k = 2 m_(k-1) xor m_(k-1), m_1 = 1; none for the first: m_k = 1).
std::uint32_t textbook_sobol(std::uint32_t i, int dimension) {
    std::uint32_t v = 1u << 31, point = 0;
    for (int k = 0; k < 32; ++k, i >>= 1) {
        if (i & 1u) point ^= v;
        v = dimension == 0 ? v >> 1 : v ^ (v >> 1);
    }
    return point;
}

TEST(Sampler, SobolPointsAreTheTextbooks) {
    // The first eight points of dimensions 1 and 2 in index order (not the
    // Gray-code order of Antonov and Saleev, which lists 0.375 fifth).
    const double first[8] = {0, 0.5, 0.25, 0.75, 0.125, 0.625, 0.375, 0.875};
    const double second[8] = {0, 0.5, 0.75, 0.25, 0.625, 0.125, 0.375, 0.875};
    for (std::uint32_t i = 0; i < 8; ++i) {
        EXPECT_EQ(F::reverse_bits(i) * 0x1p-32, first[i]) << i;
        EXPECT_EQ(F::reverse_bits(F::sobol_second_dimension_reversed(i)) * 0x1p-32, second[i]) << i;
    }
    for (std::uint32_t i = 0; i < (1u << 16); ++i) {
        for (std::uint32_t index : {i, i * 65599u + 0x9e3779b9u}) {
            ASSERT_EQ(F::reverse_bits(index), textbook_sobol(index, 0)) << index;
            ASSERT_EQ(F::reverse_bits(F::sobol_second_dimension_reversed(index)), textbook_sobol(index, 1)) << index;
        }
    }
}

// Whether the points put exactly one point in each cell of every grid of
// 2^a x 2^(m - a) cells (there are 2^m points).
bool is_net(const std::vector<std::pair<float, float>>& points, int m) {
    for (int a = 0; a <= m; ++a) {
        std::set<std::pair<int, int>> cells;
        for (auto [x, y] : points)
            cells.insert({static_cast<int>(std::ldexp(x, a)), static_cast<int>(std::ldexp(y, m - a))});
        if (cells.size() != points.size()) return false;
    }
    return true;
}

// Both scrambles keep the net: every block of 2^m samples of one pair, for
// m up to 10, the first block and the next.
TEST(Sampler, EachBlockOfAPowerOfTwoSamplesIsANet) {
    for (std::uint32_t seed : {0u, 7u})
        for (std::uint32_t pixel : {0u, 1u, 4095u})
            for (std::uint32_t bounce : {0u, 3u})
                for (std::uint32_t dimension = 0; dimension < 2 * DIM_SOBOL_PAIRS; dimension += 2)
                    for (int m = 0; m <= 10; ++m)
                        for (std::uint32_t block = 0; block < 2; ++block) {
                            std::vector<std::pair<float, float>> points;
                            for (std::uint32_t i = 0; i < (1u << m); ++i) {
                                std::uint32_t sample = (block << m) + i;
                                points.push_back({camera_uniform<F>(seed, pixel, sample, bounce, dimension),
                                                  camera_uniform<F>(seed, pixel, sample, bounce, dimension + 1)});
                            }
                            ASSERT_TRUE(is_net(points, m))
                                << "seed " << seed << " pixel " << pixel << " bounce " << bounce << " dimension "
                                << dimension << " m " << m << " block " << block;
                        }
}

// A choice's number (a dimension past the pairs) is a (0,1)-sequence: each
// block of 2^m samples of a pixel puts one number in each 1/2^m of [0, 1),
// for m up to 12, the first block and the next. Independent numbers (the
// rng_uniform of the same dimension) fail at m = 2 already with probability
// 1 - 4!/4^4 per block.
TEST(Sampler, EachChoiceStratifiesEveryBlockOfAPowerOfTwoSamples) {
    for (std::uint32_t seed : {0u, 7u})
        for (std::uint32_t pixel : {0u, 1u, 4095u})
            for (std::uint32_t bounce : {0u, 3u})
                for (std::uint32_t dimension = 2 * DIM_SOBOL_PAIRS; dimension <= DIM_ROULETTE; ++dimension)
                    for (int m = 0; m <= 12; ++m)
                        for (std::uint32_t block = 0; block < 2; ++block) {
                            std::set<int> strata;
                            for (std::uint32_t i = 0; i < (1u << m); ++i)
                                strata.insert(static_cast<int>(std::ldexp(
                                    camera_uniform<F>(seed, pixel, (block << m) + i, bounce, dimension), m)));
                            ASSERT_EQ(strata.size(), 1u << m)
                                << "seed " << seed << " pixel " << pixel << " bounce " << bounce << " dimension "
                                << dimension << " m " << m << " block " << block;
                        }
}

// Over pixels (one randomisation each) a sample's numbers are uniform, in
// each dimension and in pairs: 400 000 pixels, 1000 bins (1-D) and 32 x 32
// (2-D). A scramble that left any digit unflipped fails.
TEST(Sampler, UniformOverPixels) {
    const std::uint32_t n = 400000;
    for (std::uint32_t sample : {0u, 1u, 37u})
        for (std::uint32_t dimension = 0; dimension <= DIM_ROULETTE; ++dimension) {
            std::vector<std::uint64_t> counts(1000, 0);
            for (std::uint32_t pixel = 0; pixel < n; ++pixel)
                ++counts[static_cast<int>(camera_uniform<F>(5, pixel, sample, 2, dimension) * 1000)];
            wp::test::ChiSquare chi = wp::test::chi_square_test(counts, std::vector<double>(1000, 1e-3));
            EXPECT_GT(chi.p_value, kChiSquareAlpha) << "sample " << sample << " dimension " << dimension;
        }
    wp::test::Histogram2D histogram(32, 32);
    for (std::uint32_t pixel = 0; pixel < n; ++pixel)
        histogram.add(camera_uniform<F>(5, pixel, 3, 1, DIM_BSDF_U), camera_uniform<F>(5, pixel, 3, 1, DIM_BSDF_V));
    wp::test::ChiSquare chi = histogram.uniformity();
    EXPECT_GT(chi.p_value, kChiSquareAlpha) << "chi2 " << chi.statistic;
}

// Two streams' points (pairs' or choices'), or one stream's at two bounces,
// are independent over a pixel's samples: 512 pixels x 1024 samples in 32 x 32 bins. Without the
// index shuffle sample i takes the same Sobol' point in every pair and the
// first digits agree (chi2 in the hundreds of thousands).
TEST(Sampler, StreamsAreIndependentOfOneAnother) {
    struct Draws {
        std::uint32_t bounce_a, dimension_a, bounce_b, dimension_b;
    };
    const Draws draws[] = {
        {0, DIM_FILM_X, 0, DIM_LIGHT_U},       {0, DIM_LIGHT_U, 0, DIM_BSDF_U},
        {1, DIM_BSDF_U, 2, DIM_BSDF_U},        {0, DIM_FILM_Y, 1, DIM_LIGHT_V},
        {3, DIM_BSDF_V, 3, DIM_ROULETTE},      {0, DIM_LIGHT_SELECT, 1, DIM_LIGHT_SELECT},
        {2, DIM_BSDF_LOBE, 2, DIM_BSDF_U},     {2, DIM_BSDF_LOBE, 2, DIM_ROULETTE},
        {1, DIM_LIGHT_SELECT, 1, DIM_LIGHT_U},
    };
    for (const Draws& d : draws) {
        wp::test::Histogram2D histogram(32, 32);
        for (std::uint32_t i = 0; i < 512u * 1024u; ++i)
            histogram.add(camera_uniform<F>(9, i / 1024, i % 1024, d.bounce_a, d.dimension_a),
                          camera_uniform<F>(9, i / 1024, i % 1024, d.bounce_b, d.dimension_b));
        wp::test::ChiSquare chi = histogram.uniformity();
        EXPECT_GT(chi.p_value, kChiSquareAlpha)
            << "bounce " << d.bounce_a << " dimension " << d.dimension_a << " against bounce " << d.bounce_b
            << " dimension " << d.dimension_b << ": chi2 " << chi.statistic;
    }
}

// The mean of f(x, y) = exp(x) cos(y) (smooth; integral (e - 1) sin 1) over 256
// samples, in 4096 pixels: unbiased, the mean over pixels within 4 standard
// errors (from the spread over pixels) of the integral; and the RMS error
// at least 10x below independent numbers' (theory: n^-1.5 against n^-0.5).
TEST(Sampler, IntegratesASmoothFunctionUnbiasedAndFarBetterThanIndependentNumbers) {
    const double exact = (std::exp(1.0) - 1.0) * std::sin(1.0);
    const int pixels = 4096, samples = 256;
    auto rms_error = [&](auto draw) {
        double sum = 0, sum_squares = 0;
        for (int pixel = 0; pixel < pixels; ++pixel) {
            double mean = 0;
            for (int s = 0; s < samples; ++s) {
                auto [x, y] = draw(pixel, s);
                mean += std::exp(x) * std::cos(y) / samples;
            }
            sum += mean - exact;
            sum_squares += (mean - exact) * (mean - exact);
        }
        double bias = sum / pixels, rms = std::sqrt(sum_squares / pixels);
        double standard_error = std::sqrt((sum_squares / pixels - bias * bias) / (pixels - 1));
        EXPECT_LT(std::fabs(bias), 4 * standard_error) << "bias " << bias;
        return rms;
    };
    double sobol = rms_error([](int pixel, int s) {
        return std::pair<double, double>(camera_uniform<D>(2, pixel, s, 1, DIM_BSDF_U),
                                         camera_uniform<D>(2, pixel, s, 1, DIM_BSDF_V));
    });
    double independent = rms_error([](int pixel, int s) {
        return std::pair<double, double>(D::rng_uniform(2, pixel, s, 1, DIM_BSDF_U),
                                         D::rng_uniform(2, pixel, s, 1, DIM_BSDF_V));
    });
    EXPECT_GT(independent / sobol, 10.0) << "RMS error " << sobol << " against " << independent;
}

// render.sampler "independent": a pair's two numbers are independent
// numbers (400 000 samples of 400 pixels in 32 x 32 bins), and a pixel's
// first 256 pairs are no net (with probability 1 - 256! / 256^256 per grid).
TEST(Sampler, TheIndependentSamplerDrawsNoNet) {
    wp::test::Histogram2D histogram(32, 32);
    for (std::uint32_t i = 0; i < 400000; ++i) {
        F::CameraPair pair = F::camera_pair(4, i / 1000, i % 1000, 1, DIM_LIGHT_U, 0);
        histogram.add(pair.u, pair.v);
    }
    wp::test::ChiSquare chi = histogram.uniformity();
    EXPECT_GT(chi.p_value, kChiSquareAlpha) << "chi2 " << chi.statistic;
    std::vector<std::pair<float, float>> points;
    for (std::uint32_t sample = 0; sample < 256; ++sample) {
        F::CameraPair pair = F::camera_pair(4, 7, sample, 1, DIM_BSDF_U, 0);
        points.push_back({pair.u, pair.v});
    }
    EXPECT_FALSE(is_net(points, 8));
}

TEST(Sampler, FloatAndDoubleDrawIdenticalNumbers) {
    for (std::uint32_t i = 0; i < 1000; ++i) {
        float f = camera_uniform<F>(1, i, i / 3, i % 7, i % (DIM_ROULETTE + 1));
        double d = camera_uniform<D>(1, i, i / 3, i % 7, i % (DIM_ROULETTE + 1));
        EXPECT_EQ(static_cast<double>(f), d);
        EXPECT_GE(f, 0.0f);
        EXPECT_LT(f, 1.0f);
    }
}

}  // namespace
