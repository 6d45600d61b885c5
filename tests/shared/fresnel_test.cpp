// Dielectric and conductor Fresnel, reflection and refraction
// (kernels/shared/fresnel.h).
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <limits>

#include "core/shared_math.h"
#include "support/directions.h"
#include "support/real_types.h"

namespace {

using wp::test::kRoundingTolerance;

template <class Real>
class Fresnel : public ::testing::Test {};
TYPED_TEST_SUITE(Fresnel, wp::test::RealTypes, wp::test::RealTypeNames);

using wp::test::Vec3;

const double kIors[] = {1.0 / 2.4, 1.0 / 1.5, 1.0 / 1.33, 1.1, 1.33, 1.5, 2.4};

// Textbook unpolarised Fresnel with both indices, independent of the code
// under test: n1 on the incident side, n2 beyond, cos_i >= 0, below TIR.
double textbook_fresnel(double cos_i, double n1, double n2) {
    double sin_t = n1 / n2 * std::sqrt(1.0 - cos_i * cos_i);
    double cos_t = std::sqrt(1.0 - sin_t * sin_t);
    double rs = (n1 * cos_i - n2 * cos_t) / (n1 * cos_i + n2 * cos_t);
    double rp = (n2 * cos_i - n1 * cos_t) / (n2 * cos_i + n1 * cos_t);
    return 0.5 * (rs * rs + rp * rp);
}

TYPED_TEST(Fresnel, NormalIncidenceIsSquaredIndexRatio) {
    using R = TypeParam;
    for (double eta : kIors) {
        double expected = std::pow((eta - 1.0) / (eta + 1.0), 2.0);
        EXPECT_NEAR(wp::SharedMath<R>::fresnel_dielectric(R(1), R(eta)), expected, kRoundingTolerance<R>)
            << "eta " << eta;
    }
}

TYPED_TEST(Fresnel, MatchesTextbookFormAtAllAnglesBelowCriticalAngle) {
    using R = TypeParam;
    for (double eta : kIors) {
        double sin_critical = eta < 1.0 ? eta : 1.0;
        for (double cos_i = 1.0; cos_i > 0.0; cos_i -= 1.0 / 64.0) {
            if (std::sqrt(1.0 - cos_i * cos_i) >= sin_critical * (1.0 - 1e-3)) continue;
            EXPECT_NEAR(wp::SharedMath<R>::fresnel_dielectric(R(cos_i), R(eta)), textbook_fresnel(cos_i, 1.0, eta),
                        kRoundingTolerance<R> / std::max(cos_i, 1e-2))
                << "eta " << eta << " cos_i " << cos_i;
        }
    }
}

TYPED_TEST(Fresnel, IndexMatchedInterfaceReflectsNothing) {
    using R = TypeParam;
    for (double cos_i = 1.0; cos_i > 0.0; cos_i -= 0.125) {
        EXPECT_EQ(wp::SharedMath<R>::fresnel_dielectric(R(cos_i), R(1)), R(0));
    }
}

TYPED_TEST(Fresnel, TotalInternalReflectionBeyondCriticalAngle) {
    using R = TypeParam;
    for (double n : {1.33, 1.5, 2.4}) {
        double eta = 1.0 / n;  // leaving the denser medium
        double cos_critical = std::sqrt(1.0 - eta * eta);
        for (double cos_i = cos_critical * 0.999; cos_i >= 0.0; cos_i -= cos_critical / 16.0) {
            EXPECT_EQ(wp::SharedMath<R>::fresnel_dielectric(R(cos_i), R(eta)), R(1)) << "n " << n << " cos_i " << cos_i;
        }
        EXPECT_LT(wp::SharedMath<R>::fresnel_dielectric(R(cos_critical * 1.01), R(eta)), R(1));
    }
}

// Reciprocity: light crossing the interface either way reflects the same
// fraction, F(cos_i, eta) == F(cos_t, 1/eta) with Snell's cos_t.
TYPED_TEST(Fresnel, SymmetricUnderSwappingMedia) {
    using R = TypeParam;
    for (double eta : kIors) {
        for (double cos_i = 1.0; cos_i > 0.05; cos_i -= 1.0 / 32.0) {
            double sin_t = std::sqrt(1.0 - cos_i * cos_i) / eta;
            if (sin_t >= 1.0) continue;
            double cos_t = std::sqrt(1.0 - sin_t * sin_t);
            if (cos_t < 0.05) continue;
            EXPECT_NEAR(wp::SharedMath<R>::fresnel_dielectric(R(cos_i), R(eta)),
                        wp::SharedMath<R>::fresnel_dielectric(R(cos_t), R(1.0 / eta)), 20 * kRoundingTolerance<R>)
                << "eta " << eta << " cos_i " << cos_i;
        }
    }
}

TYPED_TEST(Fresnel, NegativeCosineSwapsTheMedia) {
    using R = TypeParam;
    for (double eta : kIors) {
        for (double cos_i = 1.0; cos_i > 0.0; cos_i -= 0.125) {
            EXPECT_EQ(wp::SharedMath<R>::fresnel_dielectric(R(-cos_i), R(eta)),
                      wp::SharedMath<R>::fresnel_dielectric(R(cos_i), R(1) / R(eta)));
        }
    }
}

template <class Real>
Vec3<Real> spread_direction(int i, int count) {
    return Vec3<Real>(wp::test::spread_direction(i, count));
}

TYPED_TEST(Fresnel, ReflectionMirrorsTheNormalComponent) {
    using R = TypeParam;
    using M = wp::SharedMath<R>;
    Vec3<R> n = glm::normalize(Vec3<R>(R(0.3), R(-0.5), R(0.8)));
    for (int i = 0; i < 200; ++i) {
        Vec3<R> d = spread_direction<R>(i, 200);
        Vec3<R> r = M::reflect_direction(d, n);
        EXPECT_NEAR(glm::dot(r, n), -glm::dot(d, n), kRoundingTolerance<R>);
        EXPECT_NEAR(glm::length(glm::cross(r - d, n)), 0.0, kRoundingTolerance<R>);  // changes only along n
        EXPECT_NEAR(glm::length(r), 1.0, kRoundingTolerance<R>);
    }
}

TYPED_TEST(Fresnel, RefractionObeysSnellOrReportsTotalInternalReflection) {
    using R = TypeParam;
    using M = wp::SharedMath<R>;
    Vec3<R> n = glm::normalize(Vec3<R>(R(-0.2), R(0.9), R(0.4)));
    for (double eta : kIors) {
        for (int i = 0; i < 200; ++i) {
            Vec3<R> d = spread_direction<R>(i, 200);
            if (glm::dot(d, n) >= R(0)) d = M::reflect_direction(d, n);  // incident side: dot(d, n) < 0
            double sin_i = glm::length(glm::dvec3(glm::cross(d, n)));
            Vec3<R> t;
            bool transmitted = M::refract_direction(d, n, R(eta), &t);
            // Away from the critical angle (where rounding may go either way):
            if (sin_i / eta < 1.0 - 1e-4) {
                EXPECT_TRUE(transmitted) << "eta " << eta << " sin_i " << sin_i;
            }
            if (sin_i / eta > 1.0 + 1e-4) {
                EXPECT_FALSE(transmitted) << "eta " << eta << " sin_i " << sin_i;
            }
            if (!transmitted) continue;
            EXPECT_NEAR(glm::length(t), 1.0, kRoundingTolerance<R>);
            EXPECT_LT(glm::dot(t, n), R(0));  // crosses the surface
            EXPECT_NEAR(eta * glm::length(glm::cross(t, n)), sin_i,
                        4 * kRoundingTolerance<R> * eta);                            // n1 sin_i = n2 sin_t
            EXPECT_NEAR(glm::dot(t, glm::cross(d, n)), 0.0, kRoundingTolerance<R>);  // plane of incidence
        }
    }
}

// The conductor's reflectance from the complex amplitudes, written
// independently of the code under test: with the complex index
// n = eta + i k and n cos_t = sqrt(n^2 - sin_i^2),
// r_s = (cos_i - n cos_t) / (cos_i + n cos_t),
// r_p = (n^2 cos_i - n cos_t) / (n^2 cos_i + n cos_t), R = (|r_s|^2 + |r_p|^2) / 2.
double textbook_conductor_fresnel(double cos_i, double eta, double k) {
    const std::complex<double> n(eta, k);
    const std::complex<double> n_cos_t = std::sqrt(n * n - (1.0 - cos_i * cos_i));
    const std::complex<double> r_s = (cos_i - n_cos_t) / (cos_i + n_cos_t);
    const std::complex<double> r_p = (n * n * cos_i - n_cos_t) / (n * n * cos_i + n_cos_t);
    return 0.5 * (std::norm(r_s) + std::norm(r_p));
}

// Complex indices of real metals (Mitsuba 3's RGB Au and Cu, green) and of
// made-up ones.
const std::pair<double, double> kComplexIors[] = {{0.2, 3.0}, {0.143, 3.983}, {0.924, 2.453}, {1.5, 0.5}, {3.0, 0.2}};

TYPED_TEST(Fresnel, ConductorAtNormalIncidenceIsTheTextbookRatio) {
    using R = TypeParam;
    for (auto [eta, k] : kComplexIors) {
        const double expected = ((eta - 1) * (eta - 1) + k * k) / ((eta + 1) * (eta + 1) + k * k);
        EXPECT_NEAR(wp::SharedMath<R>::fresnel_conductor_channel(R(1), R(eta), R(k)), expected, kRoundingTolerance<R>)
            << "eta " << eta << " k " << k;
    }
}

TYPED_TEST(Fresnel, ConductorMatchesTheComplexAmplitudesAtAllAngles) {
    using R = TypeParam;
    for (auto [eta, k] : kComplexIors) {
        for (double cos_i = 1.0; cos_i >= 0.0; cos_i -= 1.0 / 64.0) {
            EXPECT_NEAR(wp::SharedMath<R>::fresnel_conductor_channel(R(cos_i), R(eta), R(k)),
                        textbook_conductor_fresnel(cos_i, eta, k), 4 * kRoundingTolerance<R>)
                << "eta " << eta << " k " << k << " cos_i " << cos_i;
        }
    }
}

// Without absorption the conductor is a dielectric: the same reflectance,
// total internal reflection included (eta < 1).
TYPED_TEST(Fresnel, ConductorWithoutAbsorptionIsTheDielectric) {
    using R = TypeParam;
    for (double eta : kIors) {
        for (double cos_i = 1.0; cos_i > 0.0; cos_i -= 1.0 / 64.0) {
            EXPECT_NEAR(wp::SharedMath<R>::fresnel_conductor_channel(R(cos_i), R(eta), R(0)),
                        wp::SharedMath<R>::fresnel_dielectric(R(cos_i), R(eta)),
                        20 * kRoundingTolerance<R> / std::max(cos_i, 1e-2))
                << "eta " << eta << " cos_i " << cos_i;
        }
    }
}

TYPED_TEST(Fresnel, ConductorReflectsEverythingAtGrazingIncidence) {
    using R = TypeParam;
    for (auto [eta, k] : kComplexIors) {
        EXPECT_NEAR(wp::SharedMath<R>::fresnel_conductor_channel(R(0), R(eta), R(k)), 1.0, kRoundingTolerance<R>);
        EXPECT_GT(wp::SharedMath<R>::fresnel_conductor_channel(R(0.01), R(eta), R(k)),
                  wp::SharedMath<R>::fresnel_conductor_channel(R(0.5), R(eta), R(k)));
    }
}

// eta = 0, k = 1 (Mitsuba's material "none") is a perfect mirror: exactly 1.
TYPED_TEST(Fresnel, ConductorOfIndexIIsAPerfectMirror) {
    using R = TypeParam;
    for (double cos_i = 1.0; cos_i >= 0.0; cos_i -= 1.0 / 128.0) {
        EXPECT_EQ(wp::SharedMath<R>::fresnel_conductor_channel(R(cos_i), R(0), R(1)), R(1)) << cos_i;
    }
}

// Each colour channel gets its own eta and k.
TYPED_TEST(Fresnel, ConductorTakesEachChannelsIndex) {
    using R = TypeParam;
    using M = wp::SharedMath<R>;
    const Vec3<R> eta(R(0.2), R(0.924), R(1.5)), k(R(3.0), R(2.453), R(0.5));
    const Vec3<R> reflectance = M::fresnel_conductor(R(0.6), eta, k);
    for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(reflectance[c], textbook_conductor_fresnel(0.6, eta[c], k[c]), 4 * kRoundingTolerance<R>) << c;
    }
}

}  // namespace
