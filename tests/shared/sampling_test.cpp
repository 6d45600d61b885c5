// Direction and light sampling (kernels/shared/sampling.h, lights.h), float and double.
//
// Distributions: Pearson chi-square goodness of fit over bins of equal
// probability under the intended density, at significance kChiSquareAlpha =
// 1e-3 per test (a correct sampler fails a given test with probability 1e-3;
// the inputs come from the project RNG with fixed seeds, so results are
// reproducible). Densities: the returned pdf is compared with closed forms,
// and Monte Carlo integrals of 1/pdf with known solid angles, accepted within
// kSigmaTolerance = 4.5 standard errors (false failure 6.8e-6 per check).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>

#include "core/shared_math.h"
#include "support/directions.h"
#include "support/real_types.h"
#include "support/statistics.h"

namespace {

using wp::test::kRoundingTolerance;

using wp::test::kChiSquareAlpha;
using wp::test::kSigmaTolerance;
constexpr double kPi = std::numbers::pi;

template <class Real>
class Sampling : public ::testing::Test {};
TYPED_TEST_SUITE(Sampling, wp::test::RealTypes, wp::test::RealTypeNames);

using wp::test::Vec3;

constexpr int kSamples = 1000000;  // 2500 per bin with 20 x 20 bins

// The i-th pair of sampler inputs, from the project RNG.
template <class Real>
std::pair<Real, Real> uniform_pair(std::uint32_t seed, std::uint32_t i) {
    using M = wp::SharedMath<Real>;
    return {M::rng_uniform(seed, i, 0, 0, DIM_LIGHT_U), M::rng_uniform(seed, i, 0, 0, DIM_LIGHT_V)};
}

// Azimuth of a direction in the frame (t, b, n), as a fraction of a turn.
double azimuth_fraction(const glm::dvec3& w, const glm::dvec3& t, const glm::dvec3& b) {
    double phi = std::atan2(glm::dot(w, b), glm::dot(w, t));
    return phi < 0.0 ? phi / (2.0 * kPi) + 1.0 : phi / (2.0 * kPi);
}

void expect_uniform(const wp::test::Histogram2D& histogram) {
    EXPECT_EQ(histogram.out_of_range(), 0u);
    wp::test::ChiSquare chi = histogram.uniformity();
    EXPECT_GT(chi.p_value, kChiSquareAlpha) << "chi2 " << chi.statistic << " with " << chi.dof << " dof";
}

void expect_mean(const wp::test::RunningMean& estimate, double expected) {
    EXPECT_NEAR(estimate.mean(), expected, kSigmaTolerance * estimate.standard_error())
        << "standard error " << estimate.standard_error();
}

TYPED_TEST(Sampling, FrameIsOrthonormalAndRightHanded) {
    using R = TypeParam;
    using M = wp::SharedMath<R>;
    for (int i = 0; i < 500; ++i) {
        // Include the poles, where the branchless basis switches sign.
        glm::dvec3 nd = i == 0   ? glm::dvec3(0, 0, 1)
                        : i == 1 ? glm::dvec3(0, 0, -1)
                                 : wp::test::spread_direction(i, 500);
        typename M::Frame f = M::frame_from_normal(Vec3<R>(nd));
        EXPECT_NEAR(glm::length(f.tangent), 1.0, kRoundingTolerance<R>);
        EXPECT_NEAR(glm::length(f.bitangent), 1.0, kRoundingTolerance<R>);
        EXPECT_NEAR(glm::dot(f.tangent, f.bitangent), 0.0, kRoundingTolerance<R>);
        EXPECT_NEAR(glm::dot(f.tangent, f.normal), 0.0, kRoundingTolerance<R>);
        EXPECT_NEAR(glm::length(glm::cross(f.tangent, f.bitangent) - f.normal), 0.0, kRoundingTolerance<R>);
        EXPECT_NEAR(glm::length(M::frame_to_world(f, Vec3<R>(0, 0, 1)) - f.normal), 0.0, kRoundingTolerance<R>);
    }
}

// Bins hemisphere samples by (coordinate(w), phi), both of which must be
// uniform on [0, 1] under the sampler's density.
template <class Real, class Sampler, class Coordinate>
void expect_uniform_hemisphere_bins(std::uint32_t seed, Sampler sample, Coordinate coordinate) {
    wp::test::Histogram2D histogram(20, 20);
    for (int i = 0; i < kSamples; ++i) {
        auto [u1, u2] = uniform_pair<Real>(seed, i);
        glm::dvec3 w(sample(u1, u2));
        ASSERT_GE(w.z, 0.0);
        ASSERT_NEAR(glm::length(w), 1.0, kRoundingTolerance<Real>);
        histogram.add(coordinate(w), azimuth_fraction(w, {1, 0, 0}, {0, 1, 0}));
    }
    expect_uniform(histogram);
}

// Under the density cos(theta)/pi, cos^2(theta) and phi are independent and
// uniform on [0, 1) and [0, 2 pi).
TYPED_TEST(Sampling, CosineHemisphereFollowsCosineDensity) {
    using M = wp::SharedMath<TypeParam>;
    expect_uniform_hemisphere_bins<TypeParam>(1, M::sample_cosine_hemisphere,
                                              [](const glm::dvec3& w) { return w.z * w.z; });
    EXPECT_NEAR(M::cosine_hemisphere_pdf(TypeParam(0.5)), 0.5 / kPi, kRoundingTolerance<TypeParam>);
    EXPECT_EQ(M::cosine_hemisphere_pdf(TypeParam(-0.5)), TypeParam(0));
}

// Uniform over the hemisphere: cos(theta) and phi uniform.
TYPED_TEST(Sampling, UniformHemisphereIsUniform) {
    using M = wp::SharedMath<TypeParam>;
    expect_uniform_hemisphere_bins<TypeParam>(2, M::sample_uniform_hemisphere, [](const glm::dvec3& w) { return w.z; });
}

// Uniform by area over a skewed parallelogram: its (u, v) coordinates,
// recovered in double, are uniform on the unit square.
TYPED_TEST(Sampling, QuadPointsAreUniformByArea) {
    using R = TypeParam;
    using M = wp::SharedMath<R>;
    const glm::dvec3 corner(-1, 0.5, -3), e1(2, 0.25, 0), e2(0.5, 1.5, -0.5);
    const glm::dvec3 normal = glm::cross(e1, e2);
    const glm::dvec3 unit_normal = glm::normalize(normal);
    const glm::dvec3 reference(0.2, -0.3, 1.0);
    wp::test::Histogram2D histogram(20, 20);
    for (int i = 0; i < kSamples; ++i) {
        auto [u1, u2] = uniform_pair<R>(3, i);
        auto s = M::sample_quad(Vec3<R>(corner), Vec3<R>(e1), Vec3<R>(e2), Vec3<R>(reference), u1, u2);
        glm::dvec3 p = glm::dvec3(s.point) - corner;
        glm::dvec3 w = normal / glm::dot(normal, normal);
        histogram.add(glm::dot(w, glm::cross(p, e2)), glm::dot(w, glm::cross(e1, p)));
        ASSERT_NEAR(glm::length(glm::dvec3(s.normal) - unit_normal), 0.0, kRoundingTolerance<R>);
    }
    expect_uniform(histogram);
}

// Points on a triangle are uniform by area: N^2 congruent cells of the
// barycentric simplex (N strips each way, every square cell split along its
// anti-diagonal), each hit with probability 1 / N^2.
TYPED_TEST(Sampling, TrianglePointsAreUniformByArea) {
    using R = TypeParam;
    using M = wp::SharedMath<R>;
    const glm::dvec3 p0(-1, 0.5, -3), p1(1.5, 0.75, -3.2), p2(-0.25, 2.0, -2.5);
    const glm::dvec3 e1 = p1 - p0, e2 = p2 - p0, normal = glm::cross(e1, e2);
    const glm::dvec3 w = normal / glm::dot(normal, normal);
    constexpr int kStrips = 20;
    std::vector<std::uint64_t> cells(kStrips * kStrips, 0);
    for (int i = 0; i < kSamples; ++i) {
        auto [u1, u2] = uniform_pair<R>(7, i);
        auto s = M::sample_triangle(Vec3<R>(p0), Vec3<R>(p1), Vec3<R>(p2), R(0.5 * glm::length(normal)),
                                    Vec3<R>(0.2, -0.3, 1.0), u1, u2);
        glm::dvec3 p = glm::dvec3(s.point) - p0;
        double b1 = std::clamp(glm::dot(w, glm::cross(p, e2)), 0.0, 1.0);
        double b2 = std::clamp(glm::dot(w, glm::cross(e1, p)), 0.0, 1.0);
        int i1 = std::min(int(b1 * kStrips), kStrips - 1), i2 = std::min(int(b2 * kStrips), kStrips - 1);
        bool upper = b1 * kStrips - i1 + b2 * kStrips - i2 >= 1.0;
        // lower cells at (i1, i2) with i1 + i2 < N, upper ones folded into the free slots above the diagonal
        int cell = upper ? (kStrips - 1 - i1) * kStrips + (kStrips - 1 - i2) : i1 * kStrips + i2;
        ++cells[std::clamp(cell, 0, kStrips * kStrips - 1)];
        ASSERT_NEAR(glm::length(glm::dvec3(s.normal) - glm::normalize(normal)), 0.0, kRoundingTolerance<R>);
    }
    wp::test::ChiSquare chi =
        wp::test::chi_square_test(cells, std::vector<double>(cells.size(), 1.0 / (kStrips * kStrips)));
    EXPECT_GT(chi.p_value, kChiSquareAlpha) << "chi2 " << chi.statistic << " with " << chi.dof << " dof";
}

// E[1/pdf] is the solid angle the triangle subtends (Van Oosterom and
// Strackee, IEEE Trans. Biomed. Eng. 30(2), 1983).
TYPED_TEST(Sampling, TrianglePdfIntegratesToTheSubtendedSolidAngle) {
    using R = TypeParam;
    using M = wp::SharedMath<R>;
    const glm::dvec3 p0(-1, 0.5, -3), p1(1.5, 0.75, -3.2), p2(-0.25, 2.0, -2.5), x(0.2, -0.3, 1.0);
    const glm::dvec3 a = p0 - x, b = p1 - x, c = p2 - x;
    const double la = glm::length(a), lb = glm::length(b), lc = glm::length(c);
    const double solid_angle =
        2.0 * std::atan2(std::abs(glm::dot(a, glm::cross(b, c))),
                         la * lb * lc + glm::dot(a, b) * lc + glm::dot(a, c) * lb + glm::dot(b, c) * la);
    const double area = 0.5 * glm::length(glm::cross(p1 - p0, p2 - p0));
    wp::test::RunningMean inverse_pdf;
    for (int i = 0; i < kSamples; ++i) {
        auto [u1, u2] = uniform_pair<R>(8, i);
        auto s = M::sample_triangle(Vec3<R>(p0), Vec3<R>(p1), Vec3<R>(p2), R(area), Vec3<R>(x), u1, u2);
        inverse_pdf.add(1.0 / double(s.pdf_solid_angle));
    }
    expect_mean(inverse_pdf, solid_angle);
}

// From a point at height h above a corner of an a x b rectangle, the solid
// angle is atan(a b / (h sqrt(a^2 + b^2 + h^2))), and E[1/pdf] must equal it.
TYPED_TEST(Sampling, QuadPdfIntegratesToTheSubtendedSolidAngle) {
    using R = TypeParam;
    using M = wp::SharedMath<R>;
    const double a = 2.0, b = 1.0, h = 0.75;
    const double solid_angle = std::atan(a * b / (h * std::sqrt(a * a + b * b + h * h)));
    for (double side : {1.0, -1.0}) {  // the density does not depend on the side seen
        wp::test::RunningMean inverse_pdf;
        for (int i = 0; i < kSamples; ++i) {
            auto [u1, u2] = uniform_pair<R>(4, i);
            auto s = M::sample_quad(Vec3<R>(0), Vec3<R>(R(a), 0, 0), Vec3<R>(0, R(b), 0), Vec3<R>(0, 0, R(side * h)),
                                    u1, u2);
            inverse_pdf.add(1.0 / static_cast<double>(s.pdf_solid_angle));
        }
        expect_mean(inverse_pdf, solid_angle);
    }
}

struct Cone {
    double radius, distance;
};

// From outside, directions are uniform over the cone the sphere subtends:
// (1 - cos theta) / (1 - cos theta_max) and phi about the axis are uniform.
// Every sampled point lies on the sphere, faces the reference point, and
// the pdf is the constant 1 / (2 pi (1 - cos theta_max)).
TYPED_TEST(Sampling, SphereConeIsUniformOverTheSubtendedCone) {
    using R = TypeParam;
    using M = wp::SharedMath<R>;
    const glm::dvec3 axis = glm::normalize(glm::dvec3(1, 2, -3));
    const glm::dvec3 reference(0.5, -0.25, 0.125);
    // Wide, medium and tiny cones (the tiny one: 1 - cos theta_max = 5e-7, where
    // forming it by subtracting cosines would cancel in float).
    for (Cone cone : {Cone{0.8, 1.0}, Cone{1.0, 3.0}, Cone{1.0, 1000.0}}) {
        const glm::dvec3 center = reference + cone.distance * axis;
        const double sin2_max = cone.radius * cone.radius / (cone.distance * cone.distance);
        const double one_minus_cos_max = sin2_max / (1.0 + std::sqrt(1.0 - sin2_max));
        const double on_sphere_tol = kRoundingTolerance<R> * (glm::length(center) + cone.radius);
        wp::SharedMath<double>::Frame frame = wp::SharedMath<double>::frame_from_normal(axis);
        wp::test::Histogram2D histogram(10, 20);
        for (int i = 0; i < 500000; ++i) {  // 2500 per bin
            auto [u1, u2] = uniform_pair<R>(5, i);
            auto s = M::sample_sphere_cone(Vec3<R>(center), R(cone.radius), Vec3<R>(reference), u1, u2);
            glm::dvec3 point(s.point), normal(s.normal);
            ASSERT_NEAR(glm::length(point - center), cone.radius, on_sphere_tol);
            ASSERT_NEAR(glm::length(normal), 1.0, kRoundingTolerance<R>);
            ASSERT_GE(glm::dot(normal, reference - point), -on_sphere_tol);  // on the visible side
            ASSERT_NEAR(s.pdf_solid_angle * 2.0 * kPi * one_minus_cos_max, 1.0, 1e3 * kRoundingTolerance<R>);
            glm::dvec3 w = glm::normalize(point - reference);
            double cos_theta = glm::dot(w, axis);
            double sin2 = glm::dot(glm::cross(w, axis), glm::cross(w, axis));
            // Points on the silhouette may land a rounding error outside the cone.
            double cone_fraction = sin2 / (1.0 + cos_theta) / one_minus_cos_max;
            ASSERT_LE(cone_fraction, 1.0 + 1e3 * kRoundingTolerance<R>);
            histogram.add(std::min(cone_fraction, 1.0), azimuth_fraction(w, frame.tangent, frame.bitangent));
        }
        SCOPED_TRACE("radius " + std::to_string(cone.radius) + " distance " + std::to_string(cone.distance));
        expect_uniform(histogram);
    }
}

// Independent check of the cone's solid angle: the fraction of uniformly
// random directions that hit the sphere is (1 - cos theta_max) / 2, the
// pdf's 1 / (4 pi pdf). Binomial standard error, 4.5 sigma.
TYPED_TEST(Sampling, SphereConePdfMatchesHitFraction) {
    using R = TypeParam;
    using M = wp::SharedMath<R>;
    const Vec3<R> center(R(0.5), R(-1), R(2.5)), reference(0);
    const R radius(1);
    auto s = M::sample_sphere_cone(center, radius, reference, R(0.5), R(0.5));
    double expected_fraction = 1.0 / (4.0 * kPi * static_cast<double>(s.pdf_solid_angle));
    int hits = 0;
    for (int i = 0; i < kSamples; ++i) {
        auto [u1, u2] = uniform_pair<double>(6, i);
        double z = 1.0 - 2.0 * u1, r = std::sqrt(1.0 - z * z), phi = 2.0 * kPi * u2;
        Vec3<R> w(glm::dvec3(r * std::cos(phi), r * std::sin(phi), z));
        hits += M::intersect_sphere(center, radius, reference, w, M::real_max) != M::real_max;
    }
    double sigma = std::sqrt(expected_fraction * (1.0 - expected_fraction) / kSamples);
    EXPECT_NEAR(static_cast<double>(hits) / kSamples, expected_fraction, kSigmaTolerance * sigma);
}

// Uniform by area: the normal's z and phi are uniform (Archimedes).
TYPED_TEST(Sampling, SphereAreaIsUniformByArea) {
    using R = TypeParam;
    using M = wp::SharedMath<R>;
    const Vec3<R> center(R(1), R(-2), R(0.5));
    wp::test::Histogram2D histogram(20, 20);
    for (int i = 0; i < kSamples; ++i) {
        auto [u1, u2] = uniform_pair<R>(7, i);
        auto s = M::sample_sphere_area(center, R(2), Vec3<R>(0), u1, u2);
        glm::dvec3 n(s.normal);
        ASSERT_NEAR(glm::length(glm::dvec3(s.point - center)), 2.0, 4 * kRoundingTolerance<R>);
        histogram.add((n.z + 1.0) / 2.0, azimuth_fraction(n, {1, 0, 0}, {0, 1, 0}));
    }
    expect_uniform(histogram);
}

// Every direction from inside a sphere meets it once, so E[1/pdf] = 4 pi;
// from a point on the sphere, half of them do: 2 pi.
TYPED_TEST(Sampling, SphereAreaPdfIntegratesToTheSeenSolidAngle) {
    using R = TypeParam;
    using M = wp::SharedMath<R>;
    const Vec3<R> center(R(1), R(-2), R(0.5));
    const R radius(2);
    const Vec3<R> inside = center + Vec3<R>(R(0.6), R(-0.4), R(1.1));
    const Vec3<R> on_surface = center + radius * glm::normalize(Vec3<R>(R(0.3), R(0.9), R(-0.2)));
    for (auto [reference, solid_angle] : {std::pair{inside, 4.0 * kPi}, std::pair{on_surface, 2.0 * kPi}}) {
        wp::test::RunningMean inverse_pdf;
        for (int i = 0; i < kSamples; ++i) {
            auto [u1, u2] = uniform_pair<R>(8, i);
            inverse_pdf.add(
                1.0 / static_cast<double>(M::sample_sphere_area(center, radius, reference, u1, u2).pdf_solid_angle));
        }
        expect_mean(inverse_pdf, solid_angle);
    }
}

TYPED_TEST(Sampling, SphereSamplingUsesConeOutsideAndAreaInside) {
    using R = TypeParam;
    using M = wp::SharedMath<R>;
    const Vec3<R> center(R(0), R(0), R(-3));
    const R radius(1), u1(0.3), u2(0.7);
    for (Vec3<R> reference : {Vec3<R>(0), Vec3<R>(0, 0, R(-2.5)), Vec3<R>(0, 0, R(-2))}) {
        bool outside = glm::length(glm::dvec3(reference - center)) > 1.01;
        auto expected = outside ? M::sample_sphere_cone(center, radius, reference, u1, u2)
                                : M::sample_sphere_area(center, radius, reference, u1, u2);
        auto s = M::sample_sphere(center, radius, reference, u1, u2);
        EXPECT_EQ(s.point, expected.point);
        EXPECT_EQ(s.pdf_solid_angle, expected.pdf_solid_angle);
    }
}

TYPED_TEST(Sampling, LightSelectionFollowsTheCdf) {
    using R = TypeParam;
    using M = wp::SharedMath<R>;
    const R cdf[] = {R(0.1), R(0.4), R(0.45), R(1)};
    const std::vector<double> pmf = {0.1, 0.3, 0.05, 0.55};
    std::vector<std::uint64_t> counts(4, 0);
    for (int i = 0; i < kSamples; ++i) {
        std::uint32_t index = M::select_light(cdf, 4, M::rng_uniform(9, i, 0, 0, DIM_LIGHT_SELECT));
        ASSERT_LT(index, 4u);
        ++counts[index];
    }
    wp::test::ChiSquare chi = wp::test::chi_square_test(counts, pmf);
    EXPECT_GT(chi.p_value, kChiSquareAlpha) << "chi2 " << chi.statistic;
    for (std::uint32_t i = 0; i < 4; ++i) EXPECT_NEAR(M::light_selection_pmf(cdf, i), pmf[i], kRoundingTolerance<R>);
    // Intervals are [cdf[i-1], cdf[i]).
    EXPECT_EQ(M::select_light(cdf, 4, R(0)), 0u);
    EXPECT_EQ(M::select_light(cdf, 4, std::nextafter(R(0.1), R(0))), 0u);
    EXPECT_EQ(M::select_light(cdf, 4, R(0.1)), 1u);
    EXPECT_EQ(M::select_light(cdf, 4, std::nextafter(R(1), R(0))), 3u);
    const R single[] = {R(1)};
    EXPECT_EQ(M::select_light(single, 1, R(0.99)), 0u);
    EXPECT_EQ(M::light_selection_pmf(single, 0), R(1));
}

}  // namespace
