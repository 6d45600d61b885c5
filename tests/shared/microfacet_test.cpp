// The microfacet distributions (kernels/shared/materials/microfacet.h), float
// and double: D, G1 and the visible-normal density against independent
// formulas (support/microfacet_reference.h), their normalisations, and
// Beckmann's numerical inversion. The sampling itself is tested through the
// rough materials' chi-square tests (roughconductor_test.cpp).
//
// Integrals are deterministic quadratures over the normals
// (integrate_over_normals), accurate to about 1e-6 for these roughnesses.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "core/shared_math.h"
#include "support/microfacet_reference.h"
#include "support/real_types.h"

namespace {
// A namespace of its own: the sanitizer build compiles test files together (unity).
namespace microfacet_test {

using wp::test::MicrofacetParameters;
using wp::test::Vec3;

template <class Real>
class Microfacets : public ::testing::Test {};
TYPED_TEST_SUITE(Microfacets, wp::test::RealTypes, wp::test::RealTypeNames);

// Both distributions at the roughnesses of the rough materials' tests: nearly
// smooth, moderate, very rough, and anisotropic.
std::vector<MicrofacetParameters> distributions() {
    std::vector<MicrofacetParameters> all;
    for (bool beckmann : {true, false}) {
        for (auto [u, v] : {std::pair{0.05, 0.05}, {0.3, 0.3}, {1.0, 1.0}, {0.05, 0.4}})
            all.push_back({beckmann, u, v});
    }
    return all;
}

// Incident directions: cos theta 0.9, 0.5 and 0.1, at an azimuth between the
// axes of the anisotropic roughness.
const double kCosines[] = {0.9, 0.5, 0.1};
const double kAzimuth = 0.7;

TYPED_TEST(Microfacets, DistributionMatchesTheReference) {
    using R = TypeParam;
    using M = wp::SharedMath<R>;
    for (const MicrofacetParameters& m : distributions()) {
        for (double cos_theta : {1.0, 0.99, 0.9, 0.7, 0.4, 0.1}) {
            for (double phi : {0.0, 0.7, 2.0}) {
                const glm::dvec3 h = wp::test::local_direction(cos_theta, phi);
                const double expected = wp::test::reference_D(m, h);
                if (expected < 1e-30) continue;  // underflows in float
                // Beckmann's exponent, -r2, carries its rounding into D: a relative error of r2
                // roundings; and wp_exp's polynomial is float-accurate by design (2e-10 in double).
                const double r2 = std::pow(h.x / h.z / m.alpha_u, 2) + std::pow(h.y / h.z / m.alpha_v, 2);
                EXPECT_NEAR(M::microfacet_D(wp::test::shared_microfacet<R>(m), Vec3<R>(h)) / expected, 1.0,
                            (wp::test::kRoundingTolerance<R> + 1e-9) * (1.0 + r2))
                    << wp::test::describe(m) << " cos " << cos_theta << " phi " << phi;
            }
        }
        EXPECT_EQ(M::microfacet_D(wp::test::shared_microfacet<R>(m), Vec3<R>(0, 0.6, -0.8)), R(0))
            << "below the surface";
        EXPECT_EQ(M::microfacet_D(wp::test::shared_microfacet<R>(m), Vec3<R>(1, 0, 0)), R(0)) << "in the surface";
    }
}

// The projected areas of the microfacets add up to the surface's:
// the integral of D(h) cos theta_h over the hemisphere is 1.
TYPED_TEST(Microfacets, DistributionIsNormalised) {
    using R = TypeParam;
    using M = wp::SharedMath<R>;
    for (const MicrofacetParameters& m : distributions()) {
        const double total = wp::test::integrate_over_normals(std::sqrt(m.alpha_u * m.alpha_v), [&](glm::dvec3 h) {
            return double(M::microfacet_D(wp::test::shared_microfacet<R>(m), Vec3<R>(h))) * h.z;
        });
        EXPECT_NEAR(total, 1.0, 2e-5) << wp::test::describe(m);
    }
}

TYPED_TEST(Microfacets, MaskingMatchesTheReference) {
    using R = TypeParam;
    using M = wp::SharedMath<R>;
    const glm::dvec3 h = glm::normalize(glm::dvec3(0.1, -0.05, 1.0));
    for (const MicrofacetParameters& m : distributions()) {
        for (double cos_theta : {1.0, 0.9, 0.5, 0.2, 0.05}) {
            for (double phi : {0.0, 0.7, 1.57, 3.0}) {
                const glm::dvec3 w = wp::test::local_direction(cos_theta, phi);
                EXPECT_NEAR(M::microfacet_G1(wp::test::shared_microfacet<R>(m), Vec3<R>(w), Vec3<R>(h)),
                            wp::test::reference_G1(m, w, h), 1e-6)
                    << wp::test::describe(m) << " cos " << cos_theta << " phi " << phi;
            }
        }
        EXPECT_EQ(M::microfacet_G1(wp::test::shared_microfacet<R>(m), Vec3<R>(0, 0, 1), Vec3<R>(h)), R(1))
            << "normal incidence";
    }
}

// A direction cannot see a microfacet's back, nor one from the other side of
// the surface: G1 is 0 where w.h and w.z differ in sign.
TYPED_TEST(Microfacets, MaskingHidesBackFacingMicrofacets) {
    using R = TypeParam;
    using M = wp::SharedMath<R>;
    const glm::dvec3 w = glm::normalize(glm::dvec3(0.9, 0.0, 0.2)), below = glm::dvec3(w.x, w.y, -w.z);
    const glm::dvec3 facing_away = glm::normalize(glm::dvec3(-0.8, 0.0, 0.3));  // w.h < 0 < w.z
    const glm::dvec3 facing = glm::normalize(glm::dvec3(0.8, 0.0, 0.6));        // below.h > 0 > below.z
    for (const MicrofacetParameters& m : distributions()) {
        EXPECT_EQ(M::microfacet_G1(wp::test::shared_microfacet<R>(m), Vec3<R>(w), Vec3<R>(facing_away)), R(0))
            << wp::test::describe(m);
        EXPECT_EQ(M::microfacet_G1(wp::test::shared_microfacet<R>(m), Vec3<R>(below), Vec3<R>(facing)), R(0))
            << wp::test::describe(m);
        EXPECT_GT(M::microfacet_G1(wp::test::shared_microfacet<R>(m), Vec3<R>(w), Vec3<R>(facing)), R(0))
            << wp::test::describe(m);
        // From below, a microfacet's back is what a direction sees (a refraction's masking).
        EXPECT_GT(M::microfacet_G1(wp::test::shared_microfacet<R>(m), Vec3<R>(below), Vec3<R>(facing_away)), R(0))
            << wp::test::describe(m);
    }
}

// The visible normals' density integrates to 1 over the normals: Smith's G1
// is exactly the normalisation of max(0, wo.h) D(h) / wo.z (Heitz 2014, eq. 19),
// so a wrong G1 or a missing factor shows here.
TYPED_TEST(Microfacets, VisibleNormalDensityIntegratesToOne) {
    using R = TypeParam;
    using M = wp::SharedMath<R>;
    for (const MicrofacetParameters& m : distributions()) {
        for (double cos_theta : kCosines) {
            const glm::dvec3 wo = wp::test::local_direction(cos_theta, kAzimuth);
            const double total = wp::test::integrate_over_normals(std::sqrt(m.alpha_u * m.alpha_v), [&](glm::dvec3 h) {
                return double(M::microfacet_pdf_visible(wp::test::shared_microfacet<R>(m), Vec3<R>(wo), Vec3<R>(h)));
            });
            EXPECT_NEAR(total, 1.0, 2e-5) << wp::test::describe(m) << " cos " << cos_theta;
        }
    }
}

// Beckmann's slope sampling solves C(erf x~) = u by Newton's method: the
// slope it returns puts u at the marginal CDF of the visible slopes (written
// here with std::erf), over a grid of angles and u.
TYPED_TEST(Microfacets, BeckmannVisibleSlopeInvertsItsDistribution) {
    using R = TypeParam;
    using M = wp::SharedMath<R>;
    const double sqrt_pi = std::sqrt(std::numbers::pi);
    double worst = 0.0;
    for (int i = 1; i <= 50; ++i) {
        const double cos_theta = R(i / 50.0), sin_theta = R(std::sqrt(1.0 - cos_theta * cos_theta));
        const double tan_theta = sin_theta / cos_theta, cot_theta = cos_theta / sin_theta;
        const double norm = 1.0 + std::erf(cot_theta) + tan_theta / sqrt_pi * std::exp(-cot_theta * cot_theta);
        for (int j = 1; j < 200; ++j) {
            const double u = j / 200.0;
            const double slope = M::beckmann_visible_slope_x(R(cos_theta), R(sin_theta), R(u));
            ASSERT_LE(slope, cot_theta * (1 + 1e-6)) << "only visible normals";
            const double cdf = (1.0 + std::erf(slope) + tan_theta / sqrt_pi * std::exp(-slope * slope)) / norm;
            worst = std::max(worst, std::fabs(cdf - u));
        }
    }
    EXPECT_LT(worst, 2e-6);
}

}  // namespace microfacet_test
}  // namespace
