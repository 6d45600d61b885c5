// The materials (kernels/shared/materials/), float and double: each one's
// sample against its own evaluate and pdf, and those against closed forms.
//
// Integrals over the sphere are deterministic midpoint quadratures in a frame
// whose pole is the shading normal (equal-area cells in cos(theta) and phi,
// so the hemisphere's edge is a cell boundary); their error is below 1e-5.
// Monte Carlo means use the project RNG with fixed seeds and are accepted
// within kSigmaTolerance = 4.5 standard errors (false failure 6.8e-6 per
// check).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <numbers>

#include "core/shared_math.h"
#include "support/directions.h"
#include "support/real_types.h"
#include "support/statistics.h"

namespace {

using wp::test::kRoundingTolerance;
using wp::test::kSigmaTolerance;
using wp::test::Vec3;

template <class Real>
class Materials : public ::testing::Test {};
TYPED_TEST_SUITE(Materials, wp::test::RealTypes, wp::test::RealTypeNames);

// A shading normal that is no axis, and a right-handed basis around it built
// here (not with the shared frame_from_normal).
const glm::dvec3 kNormal = glm::normalize(glm::dvec3(0.3, -0.5, 0.8));

struct Basis {
    glm::dvec3 t, b, n;
    glm::dvec3 at(double cos_theta, double phi) const {
        double sin_theta = std::sqrt(std::max(0.0, 1.0 - cos_theta * cos_theta));
        return sin_theta * std::cos(phi) * t + sin_theta * std::sin(phi) * b + cos_theta * n;
    }
};

Basis basis_around(const glm::dvec3& n) {
    glm::dvec3 t = glm::normalize(glm::cross(std::fabs(n.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0), n));
    return {t, glm::cross(n, t), n};
}

// The integral of f(direction) over the sphere.
template <class F>
double integrate_over_sphere(const F& f) {
    const int rings = 2000, sectors = 64;
    const Basis basis = basis_around(kNormal);
    double sum = 0.0;
    for (int i = 0; i < rings; ++i) {
        double cos_theta = -1.0 + (i + 0.5) * 2.0 / rings;
        for (int j = 0; j < sectors; ++j) sum += f(basis.at(cos_theta, (j + 0.5) * 2.0 * std::numbers::pi / sectors));
    }
    return sum * (2.0 / rings) * (2.0 * std::numbers::pi / sectors);
}

template <class Real>
double random_number(std::uint32_t sample, std::uint32_t dimension) {
    return wp::SharedMath<Real>::rng_uniform(5u, 0u, sample, 0u, dimension);
}

const glm::dvec3 kAlbedo(0.8, 0.5, 0.2);

// The geometric normal alone says which side a path arrives on; the shading
// normal turns with it, even where it leans so far that the path meets it from
// its own front.
TYPED_TEST(Materials, NormalsTurnToTheArrivingPathByTheGeometricNormal) {
    using R = TypeParam;
    using M = wp::SharedMath<R>;
    const Vec3<R> normal(0, 0, 1), shading(Vec3<R>(glm::normalize(glm::dvec3(0.9, 0, 0.2))));
    const Vec3<R> from_above(Vec3<R>(glm::normalize(glm::dvec3(1, 0, -0.1))));  // meets shading from behind
    auto above = M::normals_facing(from_above, normal, shading);
    EXPECT_TRUE(above.front);
    EXPECT_EQ(above.nf, normal);
    EXPECT_EQ(above.ns, shading);
    const Vec3<R> from_below(Vec3<R>(glm::normalize(glm::dvec3(-1, 0, 0.1))));  // meets shading from its front
    auto below = M::normals_facing(from_below, normal, shading);
    EXPECT_FALSE(below.front);
    EXPECT_EQ(below.nf, -normal);
    EXPECT_EQ(below.ns, -shading);
}

TYPED_TEST(Materials, DiffusePdfIntegratesToOne) {
    using R = TypeParam;
    using M = wp::SharedMath<R>;
    for (int uniform : {0, 1}) {
        double total = integrate_over_sphere(
            [&](const glm::dvec3& w) { return double(M::diffuse_pdf(Vec3<R>(kNormal), Vec3<R>(w), uniform)); });
        EXPECT_NEAR(total, 1.0, 1e-5) << "uniform " << uniform;
    }
}

// Energy conservation, exact for a Lambertian surface: the integral of
// f cos over the directions above it is the albedo.
TYPED_TEST(Materials, DiffuseReflectsItsAlbedo) {
    using R = TypeParam;
    using M = wp::SharedMath<R>;
    for (int c = 0; c < 3; ++c) {
        double total = integrate_over_sphere([&](const glm::dvec3& w) {
            double cos_theta = std::max(0.0, glm::dot(w, kNormal));
            return double(M::diffuse_eval(Vec3<R>(kAlbedo), Vec3<R>(kNormal), Vec3<R>(w))[c]) * cos_theta;
        });
        EXPECT_NEAR(total, kAlbedo[c], 1e-5) << "channel " << c;
    }
}

// Every sample is a unit direction above ns whose pdf is diffuse_pdf's and
// whose weight is f cos / pdf, for both hemisphere strategies; nf is tilted
// against ns, so the samples that leave below nf are the invalid ones when
// shading normals are on.
TYPED_TEST(Materials, DiffuseSampleAgreesWithEvaluateAndPdf) {
    using R = TypeParam;
    using M = wp::SharedMath<R>;
    const glm::dvec3 nf = glm::normalize(kNormal + glm::dvec3(0.4, 0.2, 0.0));
    for (int uniform : {0, 1}) {
        int below_nf = 0;
        for (std::uint32_t i = 0; i < 20000; ++i) {
            auto s = M::diffuse_sample(Vec3<R>(kAlbedo), Vec3<R>(nf), Vec3<R>(kNormal), random_number<R>(i, 0),
                                       random_number<R>(i, 1), uniform, 1);
            glm::dvec3 w(s.direction);
            double cos_theta = glm::dot(w, kNormal);
            ASSERT_NEAR(glm::length(w), 1.0, kRoundingTolerance<R>);
            ASSERT_GE(cos_theta, -kRoundingTolerance<R>);
            double pdf = M::diffuse_pdf(Vec3<R>(kNormal), s.direction, uniform);
            // The sample's cosine is its frame's z, the pdf's a dot product: equal to a few roundings of 1.
            ASSERT_NEAR(s.pdf, pdf, kRoundingTolerance<R>) << "uniform " << uniform << " sample " << i;
            if (cos_theta > 1e-3) {
                glm::dvec3 expected = glm::dvec3(M::diffuse_eval(Vec3<R>(kAlbedo), Vec3<R>(kNormal), s.direction)) *
                                      cos_theta / double(s.pdf);
                ASSERT_NEAR(glm::length(glm::dvec3(s.weight) - expected), 0.0, 1e3 * kRoundingTolerance<R>)
                    << "uniform " << uniform << " sample " << i;
            }
            EXPECT_EQ(s.specular, 0u);
            EXPECT_EQ(s.leave_side, Vec3<R>(nf));
            bool leaves_above_nf = glm::dot(w, nf) > 0;
            below_nf += !leaves_above_nf;
            if (std::fabs(glm::dot(w, nf)) > 1e-5) {
                ASSERT_EQ(bool(s.valid), leaves_above_nf) << "sample " << i;
            }
            auto without = M::diffuse_sample(Vec3<R>(kAlbedo), Vec3<R>(nf), Vec3<R>(kNormal), random_number<R>(i, 0),
                                             random_number<R>(i, 1), uniform, 0);
            ASSERT_TRUE(without.valid);
        }
        EXPECT_GT(below_nf, 100) << "the tilt should send some samples below nf";
    }
}

// The samples follow their pdf: the mean of g / pdf over samples estimates
// the integral of g over the hemisphere above ns, for g = (w . a)^2 (w . ns),
// whose integral is pi (|a|^2 + (a . ns)^2) / 4 (g / pdf stays bounded for
// both strategies); and the mean weight is the albedo (for cosine sampling
// every weight is).
TYPED_TEST(Materials, DiffuseSamplesFollowTheirPdf) {
    using R = TypeParam;
    using M = wp::SharedMath<R>;
    const glm::dvec3 a(0.7, -0.2, 0.4);
    for (int uniform : {0, 1}) {
        wp::test::RunningMean integral, weight;
        for (std::uint32_t i = 0; i < 200000; ++i) {
            auto s = M::diffuse_sample(Vec3<R>(kAlbedo), Vec3<R>(kNormal), Vec3<R>(kNormal), random_number<R>(i, 0),
                                       random_number<R>(i, 1), uniform, 0);
            glm::dvec3 w(s.direction);
            integral.add(glm::dot(w, a) * glm::dot(w, a) * glm::dot(w, kNormal) / s.pdf);
            weight.add(s.weight.x);
        }
        double expected = std::numbers::pi * (glm::dot(a, a) + glm::dot(a, kNormal) * glm::dot(a, kNormal)) / 4.0;
        EXPECT_NEAR(integral.mean(), expected, kSigmaTolerance * integral.standard_error()) << "uniform " << uniform;
        EXPECT_NEAR(weight.mean(), kAlbedo.x, kSigmaTolerance * weight.standard_error() + 1e-6) << uniform;
    }
}

TYPED_TEST(Materials, MirrorReflectsAboutTheShadingNormal) {
    using R = TypeParam;
    using M = wp::SharedMath<R>;
    const glm::dvec3 tint(0.9, 0.6, 0.3);
    for (int i = 0; i < 200; ++i) {
        glm::dvec3 wo = wp::test::spread_direction(i, 200);
        if (glm::dot(wo, kNormal) < 0) wo = -wo;
        auto s = M::mirror_sample(Vec3<R>(tint), Vec3<R>(wo), Vec3<R>(kNormal), Vec3<R>(kNormal), 1);
        glm::dvec3 wi(s.direction);
        EXPECT_NEAR(glm::dot(wi, kNormal), glm::dot(wo, kNormal), kRoundingTolerance<R>) << i;  // equal angles
        EXPECT_NEAR(glm::length(wi + wo - 2.0 * glm::dot(wo, kNormal) * kNormal), 0.0, kRoundingTolerance<R>) << i;
        EXPECT_EQ(glm::dvec3(s.weight), glm::dvec3(Vec3<R>(tint)));
        EXPECT_EQ(s.pdf, R(0));
        EXPECT_EQ(s.specular, 1u);
        EXPECT_TRUE(s.valid);
    }
}

// With shading normals, a reflection about ns that leaves below nf, or a
// path that arrives from behind ns, ends the path; without, neither is tested.
TYPED_TEST(Materials, MirrorSampleInconsistentWithTheGeometricNormalIsInvalid) {
    using R = TypeParam;
    using M = wp::SharedMath<R>;
    const Vec3<R> nf(0, 0, 1), ns(Vec3<R>(glm::normalize(glm::dvec3(0.5, 0, 1))));
    const Vec3<R> grazing(Vec3<R>(glm::normalize(glm::dvec3(-1, 0, 0.8))));  // in front of ns, reflects below nf
    const Vec3<R> steep(Vec3<R>(glm::normalize(glm::dvec3(0.2, 0, 1))));
    const Vec3<R> behind_ns(Vec3<R>(glm::normalize(glm::dvec3(-1, 0, 0.3))));  // above nf, behind ns
    ASSERT_GT(glm::dot(grazing, ns), R(0));
    ASSERT_LT(glm::dot(grazing, ns) * R(2) * ns.z - grazing.z, R(0));
    ASSERT_GT(behind_ns.z, R(0));
    ASSERT_LT(glm::dot(behind_ns, ns), R(0));
    EXPECT_TRUE(M::mirror_sample(Vec3<R>(1), steep, nf, ns, 1).valid);
    EXPECT_FALSE(M::mirror_sample(Vec3<R>(1), grazing, nf, ns, 1).valid);
    EXPECT_FALSE(M::mirror_sample(Vec3<R>(1), behind_ns, nf, ns, 1).valid);
    EXPECT_TRUE(M::mirror_sample(Vec3<R>(1), grazing, nf, ns, 0).valid);
    EXPECT_TRUE(M::mirror_sample(Vec3<R>(1), behind_ns, nf, ns, 0).valid);
}

// u_lobe below the Fresnel reflectance reflects, at or above it refracts:
// over a grid of u_lobe the reflected fraction is Fresnel's within one step.
// A refraction obeys Snell's law into the other side (entering: eta = ior,
// leaving: 1 / ior); its weight is 1/eta^2 for radiance and 1 for flux, and
// it reports eta^2; a reflection weighs 1 either way.
TYPED_TEST(Materials, GlassSplitsByFresnelAndRefractsBySnell) {
    using R = TypeParam;
    using M = wp::SharedMath<R>;
    const double ior = 1.5;
    const glm::dvec3 n(0, 0, 1);  // the outward normal
    for (bool entering : {true, false}) {
        double eta = entering ? ior : 1.0 / ior;
        for (double cos_i : {1.0, 0.8, 0.5, 0.2}) {
            glm::dvec3 wo(std::sqrt(1.0 - cos_i * cos_i), 0.0, cos_i);  // on the side of nf = n, ns = n
            double fresnel = M::fresnel_dielectric(R(cos_i), R(eta));
            const int steps = 1000;
            int reflected = 0;
            for (int k = 0; k < steps; ++k) {
                for (std::uint32_t transport : {WP_TRANSPORT_RADIANCE, WP_TRANSPORT_IMPORTANCE}) {
                    auto s = M::glass_sample(R(ior), entering, Vec3<R>(wo), Vec3<R>(n), Vec3<R>(n),
                                             R((k + 0.5) / steps), transport, 1);
                    glm::dvec3 wi(s.direction);
                    ASSERT_TRUE(s.valid);
                    EXPECT_EQ(s.pdf, R(0));
                    EXPECT_EQ(s.specular, 1u);
                    bool reflects = glm::dot(wi, n) > 0;
                    if (reflects) {
                        EXPECT_NEAR(glm::length(wi - glm::dvec3(-wo.x, 0, wo.z)), 0.0, kRoundingTolerance<R>);
                        EXPECT_EQ(glm::dvec3(s.leave_side), n);
                        EXPECT_EQ(glm::dvec3(s.weight), glm::dvec3(1.0));
                        EXPECT_EQ(s.eta_squared, R(1));
                    } else {
                        double sin_t = std::hypot(wi.x, wi.y);
                        EXPECT_NEAR(sin_t * eta, wo.x, 4 * kRoundingTolerance<R>);  // Snell: eta sin_t = sin_i
                        EXPECT_LT(wi.x * wo.x, 1e-12);                              // in the plane, on the other side
                        EXPECT_EQ(glm::dvec3(s.leave_side), -n);
                        EXPECT_NEAR(s.eta_squared, eta * eta, kRoundingTolerance<R>);
                        double expected = transport == WP_TRANSPORT_RADIANCE ? 1.0 / (eta * eta) : 1.0;
                        EXPECT_NEAR(s.weight.x, expected, kRoundingTolerance<R>);
                    }
                    if (transport == WP_TRANSPORT_RADIANCE) reflected += reflects;
                }
            }
            EXPECT_NEAR(reflected / double(steps), fresnel, 1.0 / steps) << "entering " << entering << " cos " << cos_i;
        }
    }
}

// Paths are reversible through glass: a refraction traced back from the
// other side (a photon arriving along the refracted ray) refracts into the
// direction the first path came from.
TYPED_TEST(Materials, GlassRefractionIsReversible) {
    using R = TypeParam;
    using M = wp::SharedMath<R>;
    const Vec3<R> n(0, 0, 1);
    for (int i = 0; i < 100; ++i) {
        glm::dvec3 wo = wp::test::spread_direction(i, 200);  // the upper half: outside
        auto in = M::glass_sample(R(1.5), true, Vec3<R>(wo), n, n, R(0.999), WP_TRANSPORT_RADIANCE, 1);
        if (glm::dvec3(in.leave_side).z > 0) continue;  // reflected (grazing: Fresnel above 0.999)
        // Inside, the normals face the arriving path: -n.
        auto out = M::glass_sample(R(1.5), false, in.direction, -n, -n, R(0.999), WP_TRANSPORT_RADIANCE, 1);
        ASSERT_GT(glm::dvec3(out.leave_side).z, 0.0) << "refracts back out";
        EXPECT_NEAR(glm::length(glm::dvec3(out.direction) - wo), 0.0, 16 * kRoundingTolerance<R>) << i;
        EXPECT_NEAR(double(in.weight.x) * double(out.weight.x), 1.0, kRoundingTolerance<R>) << "1/eta^2 then eta^2";
    }
}

// Beyond the critical angle from inside, every u_lobe reflects.
TYPED_TEST(Materials, GlassReflectsTotallyBeyondTheCriticalAngle) {
    using R = TypeParam;
    using M = wp::SharedMath<R>;
    const Vec3<R> n(0, 0, -1);                                            // inside, facing the path
    const Vec3<R> wo(Vec3<R>(glm::normalize(glm::dvec3(0.9, 0, -0.3))));  // sin 0.95 > 1/1.5
    for (double u : {0.0, 0.5, 0.999}) {
        auto s = M::glass_sample(R(1.5), false, wo, n, n, R(u), WP_TRANSPORT_RADIANCE, 1);
        EXPECT_EQ(glm::dvec3(s.leave_side), glm::dvec3(n)) << u;
        EXPECT_EQ(s.eta_squared, R(1)) << u;
    }
}

}  // namespace
