// The thin dielectric (kernels/shared/materials/thindielectric.h), float and
// double: the split between mirror reflection and straight transmission
// follows the slab's reflectance, summed here bounce by bounce.
#include <gtest/gtest.h>

#include <cmath>

#include "core/shared_math.h"
#include "support/real_types.h"

namespace {
// A namespace of its own: the sanitizer build compiles test files together (unity).
namespace thindielectric_test {

using wp::test::kRoundingTolerance;
using wp::test::Vec3;

template <class Real>
class ThinDielectric : public ::testing::Test {};
TYPED_TEST_SUITE(ThinDielectric, wp::test::RealTypes, wp::test::RealTypeNames);

// The slab's reflectance as the sum of its bounces, R + T R T + T R^3 T + ...
// (1000 terms), with R one face's textbook Fresnel reflectance.
double slab_reflectance(double cos_i, double ior) {
    const double sin_t = std::sqrt(1.0 - cos_i * cos_i) / ior, cos_t = std::sqrt(1.0 - sin_t * sin_t);
    const double rs = (cos_i - ior * cos_t) / (cos_i + ior * cos_t), rp = (ior * cos_i - cos_t) / (ior * cos_i + cos_t);
    const double r = 0.5 * (rs * rs + rp * rp), t = 1.0 - r;
    double sum = r, bounce = t * r * t;
    for (int k = 0; k < 1000; ++k, bounce *= r * r) sum += bounce;
    return sum;
}

// Over a grid of u_lobe the reflected fraction is the slab's reflectance
// within one step, from either side; a reflection mirrors wo about ns, a
// transmission goes on along -wo to the other side; every weight is 1.
TYPED_TEST(ThinDielectric, ReflectsTheSlabsReflectanceAndTransmitsTheRest) {
    using R = TypeParam;
    using M = wp::SharedMath<R>;
    const glm::dvec3 n = glm::normalize(glm::dvec3(0.3, -0.5, 0.8));
    const double ior = 1.5;
    for (double side : {1.0, -1.0}) {
        for (double cos_i : {1.0, 0.7, 0.3, 0.05}) {
            const glm::dvec3 t = glm::normalize(glm::cross(n, glm::dvec3(1, 0, 0)));
            const glm::dvec3 wo = side * (cos_i * n + std::sqrt(1.0 - cos_i * cos_i) * t);
            const Vec3<R> normal(side * n);
            const int steps = 1000;
            int reflected = 0;
            for (int k = 0; k < steps; ++k) {
                auto s = M::thindielectric_sample(R(ior), Vec3<R>(wo), normal, normal, R((k + 0.5) / steps), 1);
                ASSERT_TRUE(s.valid);
                EXPECT_EQ(s.weight, Vec3<R>(1));
                EXPECT_EQ(s.pdf, R(0));
                EXPECT_EQ(s.specular, 1u);
                EXPECT_EQ(s.eta_squared, R(1));
                const glm::dvec3 wi(s.direction);
                if (glm::dot(wi, side * n) > 0) {
                    ++reflected;
                    EXPECT_NEAR(glm::length(wi + wo - 2.0 * cos_i * side * n), 0.0, kRoundingTolerance<R>);
                    EXPECT_EQ(s.leave_side, normal);
                } else {
                    EXPECT_NEAR(glm::length(wi + wo), 0.0, kRoundingTolerance<R>);
                    EXPECT_EQ(s.leave_side, -normal);
                }
            }
            EXPECT_NEAR(reflected / double(steps), slab_reflectance(cos_i, ior), 1.0 / steps)
                << "side " << side << " cos " << cos_i;
        }
    }
}

}  // namespace thindielectric_test
}  // namespace
