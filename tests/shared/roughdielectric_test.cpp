// The rough dielectric (kernels/shared/materials/roughdielectric.h), float
// and double: its sampling against its pdf (a chi-square test over the
// sphere), its sample against its eval and pdf, the adjoint relation between
// its radiance and importance BSDFs, and its albedo against an independent
// single-scattering reference.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <optional>
#include <vector>

#include "core/shared_math.h"
#include "support/microfacet_reference.h"
#include "support/real_types.h"
#include "support/sphere_chi_square.h"
#include "support/statistics.h"

namespace {
// A namespace of its own: the sanitizer build compiles test files together (unity).
namespace roughdielectric_test {

using wp::test::MicrofacetParameters;
using wp::test::shared_microfacet;
using wp::test::Vec3;

template <class Real>
class RoughDielectric : public ::testing::Test {};
TYPED_TEST_SUITE(RoughDielectric, wp::test::RealTypes, wp::test::RealTypeNames);

// The outward shading normal (no axis), and directions about it.
const glm::dvec3 kNormal = glm::normalize(glm::dvec3(0.3, -0.5, 0.8));
const wp::test::SphereCells kFrame(kNormal, 1, 1);
glm::dvec3 around_normal(double cos_theta, double phi) { return kFrame.direction(cos_theta, phi); }

const double kIor = 1.5;
const double kAzimuth = 0.7;

std::vector<MicrofacetParameters> sampled_distributions() {
    std::vector<MicrofacetParameters> all;
    for (bool beckmann : {true, false}) {
        for (auto [u, v] : {std::pair{0.01, 0.01}, {0.3, 0.3}, {1.0, 1.0}, {0.05, 0.4}})
            all.push_back({beckmann, u, v});
    }
    return all;
}

// A path arriving from outside (entering: wo above the outward normal, which
// is ns) or from inside (wo below it; ns is then its opposite), at cos theta
// `cos_theta` from the normal on its side.
struct Arrival {
    bool entering;
    double cos_theta;
};
const Arrival kArrivals[] = {{true, 0.7}, {false, 0.4}};  // from inside at 0.4: beyond the smooth critical angle

template <class Real>
Vec3<Real> normal_on_side(bool entering) {
    return Vec3<Real>(entering ? kNormal : -kNormal);
}

// The samples follow roughdielectric_pdf (support/sphere_chi_square.h: 32 x
// 64 cells of equal solid angle over the whole sphere, 1e5 samples each).
// 16 cases (8 distributions x 2 arrivals), each at level
// 1 - (1 - 1e-3)^(1/16) = 6.3e-5 (Sidak): a correct sampler fails this test
// (of one precision) with probability 1e-3; the seeds are fixed.
TYPED_TEST(RoughDielectric, SamplesFollowTheirPdf) {
    using R = TypeParam;
    using M = wp::SharedMath<R>;
    const std::vector<MicrofacetParameters> distributions = sampled_distributions();
    const int cases = static_cast<int>(distributions.size() * std::size(kArrivals));
    const double level = 1.0 - std::pow(1.0 - wp::test::kChiSquareAlpha, 1.0 / cases);
    std::uint64_t seed = 100;
    for (const MicrofacetParameters& m : distributions) {
        for (const Arrival& arrival : kArrivals) {
            const Vec3<R> ns = normal_on_side<R>(arrival.entering);
            const Vec3<R> wo(double(arrival.entering ? 1 : -1) * around_normal(arrival.cos_theta, kAzimuth));
            wp::test::UnitRandom<R> random(seed++);
            auto sample = [&]() -> std::optional<glm::dvec3> {
                typename M::BsdfRandom r;
                r.lobe = random(), r.u = random(), r.v = random();
                auto s = M::roughdielectric_sample(shared_microfacet<R>(m), R(kIor), arrival.entering, ns,
                                                   M::roughdielectric_frame(ns, arrival.entering), wo, r,
                                                   WP_TRANSPORT_RADIANCE, 0);
                if (!s.valid) return std::nullopt;
                return glm::dvec3(s.direction);
            };
            auto pdf = [&](const glm::dvec3& wi) {
                return double(M::roughdielectric_pdf(shared_microfacet<R>(m), R(kIor), arrival.entering,
                                                     M::roughdielectric_frame(ns, arrival.entering), wo, Vec3<R>(wi)));
            };
            const wp::test::SphereChiSquare result = wp::test::sphere_chi_square(sample, pdf, kNormal, 100000);
            const std::string where = wp::test::describe(m) + (arrival.entering ? " entering" : " leaving");
            EXPECT_TRUE(result.failure.empty()) << where << ": " << result.describe();
            EXPECT_GT(result.chi_square.p_value, level) << where << ": " << result.describe();
        }
    }
}

// Every sample's pdf is roughdielectric_pdf's for its direction and its
// weight f |cos| / pdf, for radiance and for importance; a refraction leaves
// on the other side and reports eta^2.
TYPED_TEST(RoughDielectric, SampleAgreesWithEvalAndPdf) {
    using R = TypeParam;
    using M = wp::SharedMath<R>;
    const double tolerance = std::is_same_v<R, float> ? 2e-3 : 1e-8;
    wp::test::UnitRandom<R> random(7);
    for (const MicrofacetParameters& m : sampled_distributions()) {
        // From inside at 0.9 too, within the critical angle, where most paths refract.
        for (const Arrival& arrival : {kArrivals[0], kArrivals[1], Arrival{false, 0.9}}) {
            const double eta = arrival.entering ? kIor : 1.0 / kIor;
            const Vec3<R> ns = normal_on_side<R>(arrival.entering);
            const Vec3<R> wo(double(arrival.entering ? 1 : -1) * around_normal(arrival.cos_theta, kAzimuth));
            int refractions = 0, reflections = 0;
            for (int i = 0; i < 400; ++i) {
                typename M::BsdfRandom r;
                r.lobe = random(), r.u = random(), r.v = random();
                for (std::uint32_t transport : {WP_TRANSPORT_RADIANCE, WP_TRANSPORT_IMPORTANCE}) {
                    auto s =
                        M::roughdielectric_sample(shared_microfacet<R>(m), R(kIor), arrival.entering, ns,
                                                  M::roughdielectric_frame(ns, arrival.entering), wo, r, transport, 0);
                    EXPECT_EQ(s.specular, 0u);
                    if (!s.valid) {
                        EXPECT_EQ(s.pdf, R(0));
                        continue;
                    }
                    const double cos_i = glm::dot(glm::dvec3(s.direction), glm::dvec3(ns));
                    const bool refracted = cos_i < 0;
                    EXPECT_EQ(glm::dvec3(s.leave_side), glm::dvec3(refracted ? -ns : ns));
                    EXPECT_NEAR(s.eta_squared, refracted ? eta * eta : 1.0, wp::test::kRoundingTolerance<R>);
                    if (transport == WP_TRANSPORT_RADIANCE) ++(refracted ? refractions : reflections);
                    const double pdf =
                        M::roughdielectric_pdf(shared_microfacet<R>(m), R(kIor), arrival.entering,
                                               M::roughdielectric_frame(ns, arrival.entering), wo, s.direction);
                    ASSERT_NEAR(s.pdf / pdf, 1.0, tolerance) << wp::test::describe(m) << " sample " << i;
                    const double f = M::roughdielectric_eval(shared_microfacet<R>(m), R(kIor), arrival.entering,
                                                             M::roughdielectric_frame(ns, arrival.entering), wo,
                                                             s.direction, transport)
                                         .x;
                    ASSERT_NEAR(s.weight.x / (f * std::fabs(cos_i) / pdf), 1.0, tolerance)
                        << wp::test::describe(m) << " sample " << i << " refracted " << refracted;
                }
            }
            const bool mostly_total_reflection = !arrival.entering && arrival.cos_theta < 0.7;
            EXPECT_GT(mostly_total_reflection ? reflections : refractions, 100) << wp::test::describe(m);
            EXPECT_GT(reflections, 5) << wp::test::describe(m);
        }
    }
}

// The adjoint relation (Veach's thesis, section 5.2): the BSDF for radiance
// from wo to wi is the BSDF for importance from wi to wo, the path reversed
// (wi arriving from the other side where it refracted): radiance's 1 / eta^2
// is what makes Walter's BTDF, not symmetric by itself, the adjoint of
// itself. Reflections are symmetric either way.
TYPED_TEST(RoughDielectric, RadianceIsTheAdjointOfImportance) {
    using R = TypeParam;
    using M = wp::SharedMath<R>;
    for (const MicrofacetParameters& m : sampled_distributions()) {
        if (m.alpha_u < 0.02) continue;  // too narrow a lobe for a grid of pairs
        for (bool entering : {true, false}) {
            const Vec3<R> ns = normal_on_side<R>(entering);
            for (int i = 0; i < 40; ++i) {
                const glm::dvec3 side = glm::dvec3(ns);
                const Vec3<R> wo(double(entering ? 1 : -1) *
                                 around_normal(0.1 + 0.85 * ((i * 7) % 40) / 40.0, 0.3 * i));
                const double cos_i = (i % 2 ? 1 : -1) * (0.1 + 0.85 * ((i * 11) % 40) / 40.0);
                const Vec3<R> wi(double(entering ? 1 : -1) * around_normal(cos_i, 2.0 + 0.7 * i));
                const bool refracts = glm::dot(glm::dvec3(wi), side) < 0;
                const double forward =
                    M::roughdielectric_eval(shared_microfacet<R>(m), R(kIor), entering,
                                            M::roughdielectric_frame(ns, entering), wo, wi, WP_TRANSPORT_RADIANCE)
                        .x;
                const double backward =
                    M::roughdielectric_eval(
                        shared_microfacet<R>(m), R(kIor), refracts ? !entering : entering,
                        M::roughdielectric_frame(refracts ? -ns : ns, refracts ? !entering : entering), wi, wo,
                        WP_TRANSPORT_IMPORTANCE)
                        .x;
                EXPECT_NEAR(forward, backward, 1e-4 * (1.0 + std::fabs(forward)))
                    << wp::test::describe(m) << " entering " << entering << " pair " << i;
            }
        }
    }
}

// Textbook unpolarised Fresnel for relative index eta (below total internal
// reflection; 1 beyond), independent of the code under test.
double textbook_fresnel(double cos_i, double eta) {
    const double sin2_t = (1.0 - cos_i * cos_i) / (eta * eta);
    if (sin2_t >= 1.0) return 1.0;
    const double cos_t = std::sqrt(1.0 - sin2_t);
    const double rs = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
    const double rp = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
    return 0.5 * (rs * rs + rp * rp);
}

// For importance (no 1 / eta^2), the directional albedo, the integral of
// f |cos| over both hemispheres, is at most 1 and equals the single
// scattering albedo of the distribution, the integral over the normals of
// D(h) G1(wo, h) (wo.h) / wo.z [F G1(wi_r, h) + (1 - F) G1(wi_t, h)] with
// wi_r and wi_t the reflection and the refraction of wo about h, and D, G1
// and F written independently (support/microfacet_reference.h). Both are
// integrated over the normals (dwi = 4 wo.h dh for the reflection,
// dh / Jacobian for the refraction) with the same quadrature.
TYPED_TEST(RoughDielectric, AlbedoIsTheSingleScatteringAlbedo) {
    using R = TypeParam;
    using M = wp::SharedMath<R>;
    for (bool beckmann : {true, false}) {
        for (double alpha : {0.1, 0.5}) {
            const MicrofacetParameters m{beckmann, alpha, alpha};
            for (const Arrival& arrival : kArrivals) {
                const double eta = arrival.entering ? kIor : 1.0 / kIor;
                const glm::dvec3 side = arrival.entering ? kNormal : -kNormal;
                const wp::test::SphereCells frame(side, 1, 1);
                const glm::dvec3 wo_local = wp::test::local_direction(arrival.cos_theta, kAzimuth);
                const glm::dvec3 x = frame.direction(0.0, 0.0), y = frame.direction(0.0, 0.5 * std::numbers::pi);
                auto world = [&](const glm::dvec3& v) { return v.x * x + v.y * y + v.z * side; };
                auto refract = [&](const glm::dvec3& h, glm::dvec3* wi) {  // wo through h; false under TIR
                    const double c = glm::dot(wo_local, h), sin2_t = (1.0 - c * c) / (eta * eta);
                    if (sin2_t >= 1.0) return false;
                    *wi = -wo_local / eta + (c / eta - std::sqrt(1.0 - sin2_t)) * h;
                    return true;
                };
                const double albedo = wp::test::integrate_over_normals(alpha, [&](glm::dvec3 h) {
                    const double wo_h = glm::dot(wo_local, h);
                    if (wo_h <= 0.0) return 0.0;
                    double sum = 0.0;
                    const glm::dvec3 wi_r = 2.0 * wo_h * h - wo_local;
                    if (wi_r.z > 0.0) {
                        sum += M::roughdielectric_eval(shared_microfacet<R>(m), R(kIor), arrival.entering,
                                                       M::roughdielectric_frame(Vec3<R>(side), arrival.entering),
                                                       Vec3<R>(world(wo_local)), Vec3<R>(world(wi_r)),
                                                       WP_TRANSPORT_IMPORTANCE)
                                   .x *
                               wi_r.z * 4.0 * wo_h;
                    }
                    glm::dvec3 wi_t;
                    if (refract(h, &wi_t) && wi_t.z < 0.0) {
                        const double denominator = wo_h + eta * glm::dot(wi_t, h);
                        const double jacobian = eta * eta * std::fabs(glm::dot(wi_t, h)) / (denominator * denominator);
                        sum += M::roughdielectric_eval(shared_microfacet<R>(m), R(kIor), arrival.entering,
                                                       M::roughdielectric_frame(Vec3<R>(side), arrival.entering),
                                                       Vec3<R>(world(wo_local)), Vec3<R>(world(wi_t)),
                                                       WP_TRANSPORT_IMPORTANCE)
                                   .x *
                               -wi_t.z / jacobian;
                    }
                    return sum;
                });
                const double reference = wp::test::integrate_over_normals(alpha, [&](glm::dvec3 h) {
                    const double wo_h = glm::dot(wo_local, h);
                    if (wo_h <= 0.0) return 0.0;
                    const double fresnel = textbook_fresnel(wo_h, eta);
                    const glm::dvec3 wi_r = 2.0 * wo_h * h - wo_local;
                    double scattered = wi_r.z > 0.0 ? fresnel * wp::test::reference_G1(m, wi_r, h) : 0.0;
                    glm::dvec3 wi_t;
                    if (refract(h, &wi_t) && wi_t.z < 0.0)
                        scattered += (1.0 - fresnel) * wp::test::reference_G1(m, wi_t, h);
                    return wp::test::reference_D(m, h) * wp::test::reference_G1(m, wo_local, h) * wo_h / wo_local.z *
                           scattered;
                });
                EXPECT_LE(albedo, 1.0 + 1e-5) << wp::test::describe(m) << " entering " << arrival.entering;
                EXPECT_NEAR(albedo, reference, 1e-5) << wp::test::describe(m) << " entering " << arrival.entering;
            }
        }
    }
}

}  // namespace roughdielectric_test
}  // namespace
