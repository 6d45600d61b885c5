// The path estimator's terms (kernels/shared/estimator.h, direct_light.h),
// float and double: the multiple importance sampling weights, the emission a
// hit adds, Russian roulette, the shadow ray, and next-event estimation at a
// diffuse point against the closed-form radiance under a square and a
// spherical light, alone and combined with BSDF sampling by the power
// heuristic. Means are accepted within kSigmaTolerance = 4.5 standard errors
// of the estimate (false failure 6.8e-6 per check); fixed seeds.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>

#include "core/shared_math.h"
#include "support/analytic_scenes.h"
#include "support/real_types.h"
#include "support/statistics.h"

namespace {

using wp::test::kRoundingTolerance;
using wp::test::kSigmaTolerance;
using wp::test::Vec3;

template <class Real>
class Estimator : public ::testing::Test {};
TYPED_TEST_SUITE(Estimator, wp::test::RealTypes, wp::test::RealTypeNames);

// Veach's power heuristic with beta = 2, w = f^2 / (f^2 + g^2), written here
// as that formula in long double (whose range holds the squares of every
// density a float or double holds), against estimator.h's form that squares
// no density: from 1e-12 to 1e30 (a small light far away has solid-angle
// densities above 1e19), within 4 units of roundoff of the weight, or below
// the type's smallest normal number where the exact weight is. The two
// weights of one sample sum to 1, and a few exact cases tell the power
// heuristic from the balance heuristic f / (f + g) (2/3 where power gives 0.8).
TYPED_TEST(Estimator, PowerHeuristicIsVeachsBetaTwo) {
    using R = TypeParam;
    using M = wp::SharedMath<R>;
    auto veach = [](long double f, long double g) { return f > 0 ? f * f / (f * f + g * g) : 0.0L; };
    const double eps = std::numeric_limits<R>::epsilon(), smallest = double(std::numeric_limits<R>::min());
    int compared = 0;
    for (double f_exponent = -12; f_exponent <= 30; f_exponent += 0.75)
        for (double g_exponent = -12; g_exponent <= 30; g_exponent += 0.75) {
            const R f = R(std::pow(10.0, f_exponent)), g = R(std::pow(10.0, g_exponent));
            const double expected = double(veach(f, g)), found = double(M::power_heuristic(f, g));
            ASSERT_NEAR(found, expected, 4 * eps * expected + smallest) << "f " << f << ", g " << g;
            EXPECT_NEAR(found + double(M::power_heuristic(g, f)), 1.0, 4 * eps) << "f " << f << ", g " << g;
            ++compared;
        }
    EXPECT_GT(compared, 1000);
    EXPECT_EQ(M::power_heuristic(R(1), R(1)), R(0.5));
    EXPECT_NEAR(double(M::power_heuristic(R(2), R(1))), 0.8, 2 * eps);
    EXPECT_NEAR(double(M::power_heuristic(R(1), R(3))), 0.1, 2 * eps);
    EXPECT_EQ(M::power_heuristic(R(0), R(1)), R(0));  // a strategy that cannot make the sample
    EXPECT_EQ(M::power_heuristic(R(1), R(0)), R(1));
}

// The two strategies' weights for one sample, emission_weight (the
// bounce's) and light_sample_weight, each given its own density first, sum
// to 1 over densities from 1e-15 to 1e15 apart (whose squares would overflow
// float), and each lies in [0, 1].
TYPED_TEST(Estimator, EmissionAndLightSampleWeightsOfOneSampleSumToOne) {
    using R = TypeParam;
    using M = wp::SharedMath<R>;
    for (double light_exponent = -15; light_exponent <= 15; light_exponent += 2.5) {
        for (double bsdf_exponent = -15; bsdf_exponent <= 15; bsdf_exponent += 2.5) {
            R light_pdf = R(std::pow(10.0, light_exponent) * 1.7), bsdf_pdf = R(std::pow(10.0, bsdf_exponent) * 0.6);
            R emission = M::emission_weight(0, bsdf_pdf, light_pdf, 1, 1);
            R light_sample = M::light_sample_weight(light_pdf, bsdf_pdf, 1);
            EXPECT_NEAR(double(emission) + double(light_sample), 1.0, 4 * std::numeric_limits<R>::epsilon())
                << light_pdf << " " << bsdf_pdf;
            EXPECT_GE(emission, R(0));
            EXPECT_LE(emission, R(1));
            if (light_exponent > bsdf_exponent) {
                EXPECT_GT(light_sample, emission) << "the denser strategy weighs more";
            }
        }
    }
    // A strategy that cannot make the sample gets none of it.
    EXPECT_EQ(M::emission_weight(0, R(0), R(2), 1, 1), R(0));
    EXPECT_EQ(M::emission_weight(0, R(2), R(0), 1, 1), R(1));
    EXPECT_EQ(M::light_sample_weight(R(0), R(2), 1), R(0));
}

// docs/architecture.md, "Emission": after the camera or a specular vertex
// all of it, without next-event estimation all of it, after a diffuse vertex
// with next-event estimation none (the light sample counts it) or the power
// heuristic's share; the light sample counts in full without MIS.
TYPED_TEST(Estimator, EmissionWeightFollowsTheStrategies) {
    using R = TypeParam;
    using M = wp::SharedMath<R>;
    const R bsdf_pdf = R(0.3), light_pdf = R(0.4);
    for (int nee : {0, 1})
        for (int mis : {0, 1}) {
            if (mis && !nee) continue;  // multiple importance sampling needs the light sample
            EXPECT_EQ(M::emission_weight(1, bsdf_pdf, light_pdf, nee, mis), R(1)) << nee << mis;
        }
    EXPECT_EQ(M::emission_weight(0, bsdf_pdf, light_pdf, 0, 0), R(1));
    EXPECT_EQ(M::emission_weight(0, bsdf_pdf, light_pdf, 1, 0), R(0));
    EXPECT_NEAR(M::emission_weight(0, bsdf_pdf, light_pdf, 1, 1), 0.09 / (0.09 + 0.16), kRoundingTolerance<R>);
    EXPECT_EQ(M::light_sample_weight(light_pdf, bsdf_pdf, 0), R(1));
    EXPECT_NEAR(M::light_sample_weight(light_pdf, bsdf_pdf, 1), 0.16 / (0.09 + 0.16), kRoundingTolerance<R>);
}

TYPED_TEST(Estimator, EmissionIsSeenFromTheEmittingSide) {
    using R = TypeParam;
    using M = wp::SharedMath<R>;
    const Vec3<R> emission(2, 1, 0), throughput(0.5, 0.25, 1), none(0);
    EXPECT_EQ(M::emission_seen(emission, 0, 1, R(0.5), throughput), Vec3<R>(0.5, 0.125, 0));
    EXPECT_EQ(M::emission_seen(emission, 0, 0, R(0.5), throughput), none);  // from behind
    EXPECT_EQ(M::emission_seen(emission, 1, 0, R(0.5), throughput), Vec3<R>(0.5, 0.125, 0));
    EXPECT_EQ(M::emission_seen(emission, 1, 1, R(0), throughput), none);
    EXPECT_EQ(M::emission_seen(none, 1, 1, R(1), throughput), none);
    // No weight at all: even an infinite throughput adds nothing (not 0 * inf).
    const R inf = std::numeric_limits<R>::infinity();
    EXPECT_EQ(M::emission_seen(emission, 0, 1, R(0), Vec3<R>(inf)), none);
}

// Over a fine grid of u, the mean throughput after the roulette (0 where the
// path dies) is the throughput before; a path inside glass is judged by its
// throughput with the refractions' 1/eta^2 factored out; before rr_depth the
// roulette does not play.
TYPED_TEST(Estimator, RouletteKeepsTheExpectedThroughput) {
    using R = TypeParam;
    using M = wp::SharedMath<R>;
    const int steps = 100000;
    for (Vec3<R> throughput : {Vec3<R>(0.3, 0.1, 0.2), Vec3<R>(0.01, 0.002, 0.0), Vec3<R>(2, 0.5, 1)}) {
        for (R eta_scale : {R(1), R(2.25)}) {
            double mean = 0;
            int survived = 0;
            for (int k = 0; k < steps; ++k) {
                auto outcome = M::russian_roulette(throughput, eta_scale, 1, R((k + 0.5) / steps));
                if (outcome.survives) mean += outcome.throughput.x, ++survived;
            }
            mean /= steps;
            double survival =
                std::clamp(double(std::max({throughput.x, throughput.y, throughput.z})) * eta_scale, 0.05, 1.0);
            EXPECT_NEAR(survived / double(steps), survival, 1.0 / steps + kRoundingTolerance<R>);
            EXPECT_NEAR(mean, throughput.x, throughput.x * (1.0 / (survival * steps) + kRoundingTolerance<R>));
            auto idle = M::russian_roulette(throughput, eta_scale, 0, R(0.9999));
            EXPECT_TRUE(idle.survives);
            EXPECT_EQ(idle.throughput, throughput);
        }
    }
}

// From points on a floor to points all over a quad light, up to grazing
// angles and 1e3 away: the shadow ray leaves from above the floor, points at
// the light point, and ends before the light (the light's own test along it
// finds the light no nearer than the ray's end), so that the light never
// shadows itself.
TYPED_TEST(Estimator, ShadowRayEndsShortOfTheLight) {
    using R = TypeParam;
    using M = wp::SharedMath<R>;
    const Vec3<R> nf(0, 1, 0);
    int traced = 0;
    for (double distance : {1.0, 30.0, 1000.0})
        for (double height : {1.0, 0.1, 0.01}) {
            const Vec3<R> corner(R(distance), R(height * distance), R(-1)), edge1(2, 0, 0), edge2(0, 0, 2);
            for (int i = 0; i <= 10; ++i)
                for (int j = 0; j <= 10; ++j) {
                    Vec3<R> x(R(0.37 * i), R(0), R(0.21 * j)), point = corner + R(0.1 * i) * edge1 + R(0.1 * j) * edge2;
                    Vec3<R> light_normal = glm::normalize(glm::cross(edge1, edge2));  // down: faces the floor
                    bool faces = M::light_faces(light_normal, point, x);
                    ASSERT_TRUE(faces);
                    R x_error = M::shape_point_error(R(4));  // a point on a floor of magnitude 4
                    auto ray = M::shadow_ray(x, x_error, nf, point, light_normal, faces,
                                             M::quad_magnitude(corner, edge1, edge2));
                    ASSERT_GT(ray.origin.y, R(0));
                    ASSERT_NEAR(glm::length(ray.direction), 1.0, kRoundingTolerance<R>);
                    ASSERT_GT(glm::dot(ray.direction, glm::normalize(point - x)), R(1) - R(kRoundingTolerance<R>));
                    R t = M::intersect_quad(corner, edge1, edge2, ray.origin, ray.direction, M::real_max);
                    if (t == M::real_max) continue;  // an edge point missed by rounding
                    ASSERT_GE(t, ray.distance) << "distance " << distance << " height " << height << " " << i << j;
                    ++traced;
                }
        }
    EXPECT_GT(traced, 900);
}

// A diffuse point under the centre of a square light, and under a spherical
// one: the mean of what next-event estimation adds there (throughput 1) is
// the closed-form radiance the point reflects (analytic_scenes.h). With
// multiple importance sampling, the light sample's weighted contribution plus
// the emission that a BSDF-sampled direction finds, weighted by
// emission_weight, are unbiased together.
template <class Real>
struct DiffusePointUnderALight {
    using M = wp::SharedMath<Real>;
    Vec3<Real> x{0, 0, 0}, n{0, 1, 0}, albedo{0.6, 0.6, 0.6}, emission{3, 3, 3};
    // A light's point sample and the ray-hit density of its shape (0: missed).
    std::function<typename M::LightSample(Real, Real)> sample;
    std::function<Real(const Vec3<Real>&)> light_pdf_along;
    Real magnitude;

    // One light sample and one BSDF sample (the latter only with mis).
    double estimate(std::uint32_t i, int mis) const {
        auto u = [&](std::uint32_t dimension) { return M::rng_uniform(9u, i, 0u, 0u, dimension); };
        typename M::LightSample ls = sample(u(0), u(1));
        Vec3<Real> wi = M::direct_light_direction(ls, x);
        auto direct = M::direct_light(x, Real(0), n, n, 0, wi, M::diffuse_eval(albedo, n, wi), M::diffuse_pdf(n, wi, 0),
                                      ls, magnitude, Real(1), emission, 0, mis, 0);
        double total = direct.carries ? double(direct.contribution.x) : 0.0;
        if (mis) {
            auto s = M::diffuse_sample(albedo, n, n, u(2), u(3), 0, 0);
            Real light_pdf = light_pdf_along(s.direction);
            Real weight = M::emission_weight(0, s.pdf, light_pdf, 1, 1);
            if (light_pdf > 0) total += M::emission_seen(emission, 0, 1, weight, s.weight).x;
        }
        return total;
    }
};

template <class Real>
void expect_radiance(const DiffusePointUnderALight<Real>& point, double expected, const char* label) {
    for (int mis : {0, 1}) {
        wp::test::RunningMean radiance;
        for (std::uint32_t i = 0; i < 200000; ++i) radiance.add(point.estimate(i, mis));
        EXPECT_NEAR(radiance.mean(), expected, kSigmaTolerance * radiance.standard_error())
            << label << ", mis " << mis << ": standard error " << radiance.standard_error();
    }
}

TYPED_TEST(Estimator, NextEventEstimationUnderASquareLight) {
    using R = TypeParam;
    using M = wp::SharedMath<R>;
    const double half_side = 0.8, height = 1.2;
    const Vec3<R> corner(R(-half_side), R(height), R(-half_side)), edge1(R(2 * half_side), 0, 0),
        edge2(0, 0, R(2 * half_side));  // edge1 x edge2 points down, at the point
    DiffusePointUnderALight<R> point;
    point.sample = [&](R u, R v) { return M::sample_quad(corner, edge1, edge2, point.x, u, v); };
    point.light_pdf_along = [&](const Vec3<R>& d) {
        R t = M::intersect_quad(corner, edge1, edge2, point.x, d, M::real_max);
        return t == M::real_max
                   ? R(0)
                   : M::quad_light_pdf(edge1, edge2, point.x, point.x + t * d, M::quad_normal(edge1, edge2));
    };
    point.magnitude = M::quad_magnitude(corner, edge1, edge2);
    expect_radiance(point, wp::test::plane_under_square_light_radiance(0.6, 3.0, half_side, height), "square light");
}

TYPED_TEST(Estimator, NextEventEstimationUnderASphereLight) {
    using R = TypeParam;
    using M = wp::SharedMath<R>;
    const double radius = 0.5, height = 1.5;
    const Vec3<R> center(0, R(height), 0);
    DiffusePointUnderALight<R> point;
    point.sample = [&](R u, R v) { return M::sample_sphere(center, R(radius), point.x, u, v); };
    point.light_pdf_along = [&](const Vec3<R>& d) {
        R t = M::intersect_sphere(center, R(radius), point.x, d, M::real_max);
        Vec3<R> hit = point.x + t * d;
        return t == M::real_max ? R(0)
                                : M::sphere_light_pdf(center, R(radius), point.x, hit, M::sphere_normal(center, hit));
    };
    point.magnitude = M::sphere_magnitude(center, R(radius));
    expect_radiance(point, wp::test::plane_under_sphere_light_radiance(0.6, 3.0, radius, height), "sphere light");
}

}  // namespace
