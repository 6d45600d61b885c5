// Spawned-ray origins (kernels/common/offset.h): at every scale from 1e-6 to
// 1e6, a hit point offset to one side of its surface lies strictly on that
// side, and rays leaving into that side do not meet the surface again
// (spheres: outward rays miss, inward rays reach the far side). Hit points
// are computed as the renderer computes them: a camera ray from the origin,
// then sphere_reprojection for spheres, o + t d for quads and planes; the
// geometry sits at distances comparable to its size, as camera-relative
// scenes put it.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "core/shared_math.h"
#include "support/directions.h"
#include "support/real_types.h"

namespace {

template <class Real>
class Offset : public ::testing::Test {};
TYPED_TEST_SUITE(Offset, wp::test::RealTypes, wp::test::RealTypeNames);

using wp::test::Vec3;

const double kScales[] = {1e-6, 1e-3, 1.0, 1e3, 1e6};
constexpr int kHitPoints = 300;

// Directions leaving a surface with normal n, from grazing (cos 1e-3) to
// normal incidence, all around the normal.
template <class Real>
std::vector<Vec3<Real>> leaving_directions(const Vec3<Real>& n) {
    auto frame = wp::SharedMath<double>::frame_from_normal(glm::normalize(glm::dvec3(n)));
    std::vector<Vec3<Real>> out;
    for (double cos_theta : {1e-3, 1e-2, 0.1, 0.5, 0.9, 1.0}) {
        for (int k = 0; k < 6; ++k) {
            double phi = 2.0 * 3.14159265358979 * (k + 0.25) / 6.0, sin_theta = std::sqrt(1.0 - cos_theta * cos_theta);
            glm::dvec3 local(sin_theta * std::cos(phi), sin_theta * std::sin(phi), cos_theta);
            out.push_back(Vec3<Real>(wp::SharedMath<double>::frame_to_world(frame, local)));
        }
    }
    return out;
}

// Exit distance, in double, of a ray starting inside the sphere.
double exit_distance(const glm::dvec3& center, double radius, const glm::dvec3& origin, const glm::dvec3& w) {
    glm::dvec3 f = origin - center;
    double b = -glm::dot(f, w);
    glm::dvec3 closest = f + b * w;
    return b + std::sqrt(radius * radius - glm::dot(closest, closest));
}

TYPED_TEST(Offset, SphereHitPointsLeaveTheSurfaceAtEveryScale) {
    using R = TypeParam;
    using M = wp::SharedMath<R>;
    for (double scale : kScales) {
        SCOPED_TRACE("scale " + std::to_string(scale));
        const Vec3<R> center(glm::dvec3(0.3, -0.2, -2.0) * scale);
        const R radius = R(0.7 * scale);
        const glm::dvec3 center_d(center);
        const double radius_d = radius;
        int hits = 0;
        for (int i = 0; i < kHitPoints; ++i) {
            glm::dvec3 target = center_d + radius_d * wp::test::spread_direction(i, kHitPoints);
            Vec3<R> d(glm::normalize(target));
            R t = M::intersect_sphere(center, radius, Vec3<R>(0), d, M::real_max);
            if (t == M::real_max) continue;
            ++hits;
            Vec3<R> p = M::sphere_reproject(center, radius, t * d);
            Vec3<R> n = M::sphere_normal(center, p);

            Vec3<R> outside = M::offset_ray_origin(p, n);
            ASSERT_GT(glm::length(glm::dvec3(outside) - center_d), radius_d) << "point " << i;
            for (const Vec3<R>& w : leaving_directions<R>(n)) {
                ASSERT_EQ(M::intersect_sphere(center, radius, outside, w, M::real_max), M::real_max)
                    << "point " << i << " outward cos " << glm::dot(w, n);
            }
            Vec3<R> inside = M::offset_ray_origin(p, -n);
            ASSERT_LT(glm::length(glm::dvec3(inside) - center_d), radius_d) << "point " << i;
            for (const Vec3<R>& w : leaving_directions<R>(-n)) {
                double expected = exit_distance(center_d, radius_d, glm::dvec3(inside), glm::dvec3(w));
                double tolerance = 1e-2 * expected + 64.0 * std::numeric_limits<R>::epsilon() * scale;
                ASSERT_NEAR(M::intersect_sphere(center, radius, inside, w, M::real_max), expected, tolerance)
                    << "point " << i << " inward cos " << -glm::dot(w, n);
            }
        }
        EXPECT_GT(hits, kHitPoints / 3);
    }
}

TYPED_TEST(Offset, QuadAndPlaneHitPointsLeaveTheSurfaceOnBothSides) {
    using R = TypeParam;
    using M = wp::SharedMath<R>;
    for (double scale : kScales) {
        SCOPED_TRACE("scale " + std::to_string(scale));
        const Vec3<R> corner(glm::dvec3(-0.6, -0.5, -1.5) * scale);
        const Vec3<R> e1(glm::dvec3(1.2, 0.1, 0.2) * scale), e2(glm::dvec3(0.1, 1.0, -0.4) * scale);
        const Vec3<R> n = M::quad_normal(e1, e2);
        const glm::dvec3 n_d = glm::normalize(glm::cross(glm::dvec3(e1), glm::dvec3(e2)));
        for (int i = 0; i < kHitPoints; ++i) {
            double u = 0.02 + 0.96 * ((i * 0.618034) - std::floor(i * 0.618034));
            double v = 0.02 + 0.96 * (i + 0.5) / kHitPoints;
            Vec3<R> d(glm::normalize(glm::dvec3(corner) + u * glm::dvec3(e1) + v * glm::dvec3(e2)));
            R t = M::intersect_quad(corner, e1, e2, Vec3<R>(0), d, M::real_max);
            ASSERT_NE(t, M::real_max) << "point " << i;
            Vec3<R> p = t * d;
            for (R side : {R(1), R(-1)}) {
                Vec3<R> q = M::offset_ray_origin(p, side * n);
                double signed_distance = glm::dot(glm::dvec3(q) - glm::dvec3(corner), n_d);
                ASSERT_GT(side * signed_distance, 0.0) << "point " << i << " side " << side;
                for (const Vec3<R>& w : leaving_directions<R>(side * n)) {
                    ASSERT_EQ(M::intersect_quad(corner, e1, e2, q, w, M::real_max), M::real_max)
                        << "point " << i << " side " << side << " cos " << glm::dot(w, side * n);
                    ASSERT_EQ(M::intersect_plane(corner, n, q, w, M::real_max), M::real_max)
                        << "point " << i << " side " << side << " cos " << glm::dot(w, side * n);
                }
            }
        }
    }
}

// Scaling a scene by a power of two scales every offset by exactly that
// factor: no absolute epsilon anywhere.
TYPED_TEST(Offset, OffsetScalesWithTheScene) {
    using R = TypeParam;
    using M = wp::SharedMath<R>;
    const Vec3<R> p(R(0.3), R(-1.7), R(2.2));
    const Vec3<R> n = glm::normalize(Vec3<R>(R(0.2), R(0.5), R(-0.8)));
    const Vec3<R> base = M::offset_ray_origin(p, n) - p;
    for (int exponent : {-40, -20, -10, -5, 5, 10, 20, 40}) {
        R factor = std::ldexp(R(1), exponent);
        Vec3<R> scaled = M::offset_ray_origin(p * factor, n) - p * factor;
        EXPECT_EQ(scaled, base * factor) << "2^" << exponent;
    }
}

}  // namespace
