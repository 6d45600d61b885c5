// The mask adapter (kernels/shared/materials/mask.h): one uniform number
// picks the pass with probability 1 - opacity and hands the nested material
// a number uniform in [0, 1) again (never 1, at the float just below the
// opacity either); the pass goes on along the ray with weight 1 into the
// far side; the nested sample's density is scaled by the opacity, the
// density with which MIS must weigh it; its samples follow its density
// (a chi-square test). The other checks are exact or on a stratified grid,
// whose error bound is stated where it is used.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>

#include "core/shared_math.h"
#include "support/microfacet_reference.h"
#include "support/real_types.h"
#include "support/sphere_chi_square.h"

namespace {
namespace mask_test {

template <class Real>
class Mask : public ::testing::Test {};
TYPED_TEST_SUITE(Mask, wp::test::RealTypes, wp::test::RealTypeNames);

template <class Real>
using M = wp::SharedMath<Real>;
template <class Real>
using vec3 = typename M<Real>::vec3;

constexpr int kGrid = 1 << 14;  // stratified uniform numbers (i + 0.5) / kGrid

TYPED_TEST(Mask, PassesWithProbabilityOneMinusOpacity) {
    using Real = TypeParam;
    for (double opacity : {0.0, 0.3, 0.5, 0.875, 1.0}) {
        int passes = 0;
        for (int i = 0; i < kGrid; ++i) passes += M<Real>::mask_passes(Real(opacity), Real((i + 0.5) / kGrid)) ? 1 : 0;
        // a grid of kGrid strata estimates a probability to within one stratum
        EXPECT_NEAR(passes / double(kGrid), 1.0 - opacity, 1.0 / kGrid) << "opacity " << opacity;
    }
    EXPECT_FALSE(M<Real>::mask_passes(Real(1), std::nextafter(Real(1), Real(0))));  // opaque: never
    EXPECT_TRUE(M<Real>::mask_passes(Real(0), Real(0)));                            // clear: always
}

TYPED_TEST(Mask, NestedLobeIsUniformAgain) {
    using Real = TypeParam;
    for (double opacity : {0.1, 0.3, 0.7}) {
        double sum = 0.0, sum_squares = 0.0;
        int nested = 0;
        for (int i = 0; i < kGrid; ++i) {
            const Real u = Real((i + 0.5) / kGrid);
            if (M<Real>::mask_passes(Real(opacity), u)) {
                EXPECT_EQ(M<Real>::mask_nested_lobe(Real(opacity), u), u);  // a pass keeps its number
                continue;
            }
            const double lobe = M<Real>::mask_nested_lobe(Real(opacity), u);
            ASSERT_GE(lobe, 0.0);
            ASSERT_LT(lobe, 1.0);
            sum += lobe, sum_squares += lobe * lobe, ++nested;
        }
        // uniform on [0, 1): mean 1/2, second moment 1/3; the rescaled grid's strata are 1 / (opacity kGrid) wide
        const double stratum = 1.0 / (opacity * kGrid);
        EXPECT_NEAR(sum / nested, 0.5, stratum) << "opacity " << opacity;
        EXPECT_NEAR(sum_squares / nested, 1.0 / 3.0, 2.0 * stratum) << "opacity " << opacity;
    }
}

TYPED_TEST(Mask, NestedLobeStaysBelowOneAtTheFloatBelowTheOpacity) {
    using Real = TypeParam;
    // mask.h's bound: u <= opacity - ulp(opacity) gives u / opacity <= 1 - 2^-24 in float; every power-of-two
    // binade and values just above and below its ends
    for (int exponent = -20; exponent <= 0; ++exponent) {
        for (double scale : {1.0, 1.0000001, 1.3, 1.5, 1.999999}) {
            const Real opacity = Real(std::ldexp(scale, exponent));
            if (!(opacity <= Real(1))) continue;
            const Real u = std::nextafter(opacity, Real(0));
            EXPECT_FALSE(M<Real>::mask_passes(opacity, u));
            EXPECT_LT(M<Real>::mask_nested_lobe(opacity, u), Real(1)) << "opacity " << opacity;
        }
    }
}

TYPED_TEST(Mask, OpacityIsClampedToTheUnitInterval) {
    using Real = TypeParam;
    EXPECT_EQ(M<Real>::mask_opacity(Real(-0.25)), Real(0));
    EXPECT_EQ(M<Real>::mask_opacity(Real(1.5)), Real(1));
    EXPECT_EQ(M<Real>::mask_opacity(Real(0.4)), Real(0.4));
}

TYPED_TEST(Mask, ThePassGoesOnAlongTheRayIntoTheFarSide) {
    using Real = TypeParam;
    const vec3<Real> d = M<Real>::v3_normalize(vec3<Real>(Real(0.3), Real(-0.8), Real(0.2)));
    const vec3<Real> nf = vec3<Real>(Real(0), Real(1), Real(0));  // on the arriving side
    const auto nested =
        M<Real>::diffuse_sample(vec3<Real>(Real(0.5), Real(0.5), Real(0.5)), nf, nf, Real(0.2), Real(0.7), 0, 0);
    const auto pass = M<Real>::mask_sample(Real(0.4), 1, nested, d, nf);
    EXPECT_EQ(pass.direction.x, d.x);
    EXPECT_EQ(pass.direction.y, d.y);
    EXPECT_EQ(pass.direction.z, d.z);
    EXPECT_EQ(pass.weight.x, Real(1));
    EXPECT_EQ(pass.weight.y, Real(1));
    EXPECT_EQ(pass.weight.z, Real(1));
    EXPECT_EQ(pass.leave_side.y, Real(-1));  // the next ray starts beyond the surface
    EXPECT_EQ(pass.specular, 1u);            // a delta lobe: the emission it reaches counts in full
    EXPECT_EQ(pass.pdf, Real(0));
    EXPECT_TRUE(pass.valid);
}

// The nested sample keeps its direction and weight (f cos / pdf: the opacity of f and the opacity of choosing it
// cancel), and its density is the opacity times the nested material's at that direction: the density that
// next-event estimation's MIS weighs against (path_vertex.h's vertex_bsdf_value scales the pdf it evaluates alike).
TYPED_TEST(Mask, NestedSampleDensityIsScaledByTheOpacity) {
    using Real = TypeParam;
    const auto nf = vec3<Real>(Real(0), Real(0), Real(1));
    const auto d = M<Real>::v3_normalize(vec3<Real>(Real(0.2), Real(0.1), Real(-1)));
    const Real opacity = Real(0.35);
    for (int i = 0; i < 16; ++i) {
        const Real u = Real((i + 0.5) / 16), v = Real((i * 7 % 16 + 0.5) / 16);
        const auto nested = M<Real>::diffuse_sample(vec3<Real>(Real(0.6), Real(0.5), Real(0.4)), nf, nf, u, v, 0, 0);
        const auto s = M<Real>::mask_sample(opacity, 0, nested, d, nf);
        EXPECT_EQ(s.direction.x, nested.direction.x);
        EXPECT_EQ(s.weight.x, nested.weight.x);
        EXPECT_EQ(s.specular, 0u);
        EXPECT_NEAR(s.pdf, opacity * M<Real>::diffuse_pdf(nf, s.direction, 0),
                    wp::test::kRoundingTolerance<Real> * s.pdf);
    }
}

// The mask's samples follow its density: its passes a delta cell of their
// own, expected to hold 1 - opacity of them, and its nested material's
// directions the cells of the sphere, expected to hold opacity times the
// nested density (support/sphere_chi_square.h: 32 x 64 cells of equal solid
// angle, 1e5 samples, the rejected samples a cell of their own). A diffuse and
// a GGX rough conductor (alpha 0.3) nested, at opacities 0.3 and 0.8 and cos
// theta 0.9 and 0.4: 8 cases, each at level 1 - (1 - 1e-3)^(1/8) = 1.25e-4
// (Sidak): a correct sampler fails this test (of one precision) with
// probability 1e-3; the seeds are fixed.
TYPED_TEST(Mask, SamplesFollowTheirPdf) {
    using R = TypeParam;
    using M = wp::SharedMath<R>;
    const glm::dvec3 normal = glm::normalize(glm::dvec3(0.3, -0.5, 0.8));
    const wp::test::SphereCells frame(normal, 1, 1);
    const wp::test::MicrofacetParameters ggx{false, 0.3, 0.3};
    const double opacities[] = {0.3, 0.8}, cosines[] = {0.9, 0.4};
    const double level = 1.0 - std::pow(1.0 - wp::test::kChiSquareAlpha, 1.0 / 8.0);
    std::uint64_t seed = 700;
    for (bool conductor : {false, true}) {
        for (double opacity : opacities) {
            for (double cos_theta : cosines) {
                const vec3<R> ns(normal), wo(frame.direction(cos_theta, 0.7));
                const vec3<R> d = M::v3_neg(wo);
                wp::test::UnitRandom<R> random(seed++);
                auto sample = [&]() {
                    const R lobe = random(), u = random(), v = random();
                    const auto passes = M::mask_passes(R(opacity), lobe);
                    const auto nested = conductor ? M::roughconductor_sample(wp::test::shared_microfacet<R>(ggx),
                                                                             vec3<R>(0), vec3<R>(1), vec3<R>(1), ns,
                                                                             M::frame_from_normal(ns), wo, u, v, 0)
                                                  : M::diffuse_sample(vec3<R>(0.5), ns, ns, u, v, 0, 0);
                    const auto s = M::mask_sample(R(opacity), passes, nested, d, ns);
                    wp::test::SphereSample result;
                    result.delta = s.valid && s.specular;
                    if (s.valid && !s.specular) result.direction = glm::dvec3(s.direction);
                    return result;
                };
                auto pdf = [&](const glm::dvec3& wi) {
                    const double nested = conductor
                                              ? double(M::roughconductor_pdf(wp::test::shared_microfacet<R>(ggx),
                                                                             M::frame_from_normal(ns), wo, vec3<R>(wi)))
                                              : double(M::diffuse_pdf(ns, vec3<R>(wi), 0));
                    return opacity * nested;
                };
                const std::string where = std::string(conductor ? "roughconductor" : "diffuse") + " opacity " +
                                          std::to_string(opacity) + " cos " + std::to_string(cos_theta);
                const wp::test::SphereChiSquare result =
                    wp::test::sphere_chi_square_with_delta(sample, pdf, 1.0 - opacity, normal, 100000);
                EXPECT_TRUE(result.failure.empty()) << where << ": " << result.describe();
                EXPECT_GT(result.chi_square.p_value, level) << where << ": " << result.describe();
            }
        }
    }
}

}  // namespace mask_test
}  // namespace
