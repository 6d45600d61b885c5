// Spawned-ray origins (kernels/shared/offset.h). For spheres, quads and planes
// at scales from 1e-6 to 1e6, far from the origin (up to 1e5 times their
// size) and hit by rays from far away (1e4 times their size):
//  - the error bound of every computed hit point is larger than the point's
//    true distance from the surface (measured in long double; the largest
//    ratio is printed);
//  - the point offset by offset_ray_origin lies strictly on the side it was
//    moved to, and rays leaving into that side do not meet the surface again
//    (spheres: outward rays miss, inward rays reach the far side).
// Hit points are computed as the renderer computes them: o + t d, then
// sphere_reproject for spheres.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include "core/shared_math.h"
#include "support/directions.h"
#include "support/real_types.h"

namespace {

template <class Real>
class Offset : public ::testing::Test {};
TYPED_TEST_SUITE(Offset, wp::test::RealTypes, wp::test::RealTypeNames);

using wp::test::Vec3;
using LongVec = glm::vec<3, long double>;

const double kScales[] = {1e-6, 1e-3, 1.0, 1e3, 1e6};
constexpr int kHitPoints = 200;

// Where the shape sits and where rays come from, in units of the shape's size.
struct Placement {
    const char* name;
    glm::dvec3 shape_position;  // added to the shape's coordinates
    glm::dvec3 ray_origin;
};
const Placement kPlacements[] = {
    {"near the origin", {0, 0, 0}, {0, 0, 0}},
    {"translated by 1e5", {1e5, -3e4, 2e4}, {1e5, -3e4, 2e4 + 3.0}},
    {"rays from 1e4 away", {0, 0, 0}, {2e3, 5e3, 8e3}},
};

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

// Exit distance, in long double, of a ray starting inside the sphere.
long double exit_distance(const LongVec& center, long double radius, const LongVec& origin, const LongVec& w) {
    LongVec f = origin - center;
    long double b = -glm::dot(f, w);
    LongVec closest = f + b * w;
    return b + std::sqrt(radius * radius - glm::dot(closest, closest));
}

template <class Vector>
LongVec to_long(const Vector& v) {
    return LongVec(v);
}

// The largest (true distance from the surface) / (error bound) seen.
template <class Real>
struct BoundRatio {
    double worst = 0.0;
    void add(long double distance, Real bound) { worst = std::max(worst, double(distance / (long double)bound)); }
    ~BoundRatio() { std::printf("[%s] largest point error / bound: %.3g\n", name, worst); }
    const char* name;
};

TYPED_TEST(Offset, SphereHitPointsLeaveTheSurface) {
    using R = TypeParam;
    using M = wp::SharedMath<R>;
    BoundRatio<R> ratio{0.0, "sphere"};
    for (const Placement& placement : kPlacements) {
        for (double scale : kScales) {
            SCOPED_TRACE(std::string(placement.name) + ", scale " + std::to_string(scale));
            const Vec3<R> center((glm::dvec3(0.3, -0.2, -2.0) + placement.shape_position) * scale);
            const R radius = R(0.7 * scale);
            const Vec3<R> origin(placement.ray_origin * scale);
            const LongVec center_l = to_long(center);
            const long double radius_l = radius;
            const R error = M::shape_point_error(M::sphere_magnitude(center, radius));
            int hits = 0;
            for (int i = 0; i < kHitPoints; ++i) {
                glm::dvec3 target = glm::dvec3(center) + double(radius) * wp::test::spread_direction(i, kHitPoints);
                Vec3<R> d(glm::normalize(target - glm::dvec3(origin)));
                R t = M::intersect_sphere(center, radius, origin, d, M::real_max);
                if (t == M::real_max) continue;
                ++hits;
                Vec3<R> p = M::sphere_reproject(center, radius, origin + t * d);
                Vec3<R> n = M::sphere_normal(center, p);
                ratio.add(std::fabs(glm::length(to_long(p) - center_l) - radius_l), error);

                Vec3<R> outside = M::offset_ray_origin(p, n, error);
                ASSERT_GT(glm::length(to_long(outside) - center_l), radius_l) << "point " << i;
                for (const Vec3<R>& w : leaving_directions<R>(n)) {
                    ASSERT_EQ(M::intersect_sphere(center, radius, outside, w, M::real_max), M::real_max)
                        << "point " << i << " outward cos " << glm::dot(w, n);
                }
                Vec3<R> inside = M::offset_ray_origin(p, -n, error);
                ASSERT_LT(glm::length(to_long(inside) - center_l), radius_l) << "point " << i;
                for (const Vec3<R>& w : leaving_directions<R>(-n)) {
                    long double expected = exit_distance(center_l, radius_l, to_long(inside), to_long(w));
                    double tolerance = 1e-2 * double(expected) + 64.0 * double(error);
                    ASSERT_NEAR(M::intersect_sphere(center, radius, inside, w, M::real_max), double(expected),
                                tolerance)
                        << "point " << i << " inward cos " << -glm::dot(w, n);
                }
            }
            EXPECT_GT(hits, kHitPoints / 4);
        }
    }
    EXPECT_LT(ratio.worst, 1.0);
}

// The smallpt construction: a wall that is a sphere of radius 1e5 whose
// centre lies 1e5 + 50 away, seen from the origin. In float its points are
// only known to ulp(1e5) ~ 0.008; the offset must follow that, not |p| ~ 50.
TYPED_TEST(Offset, HugeSphereWallsOfTheSmallptBox) {
    using R = TypeParam;
    using M = wp::SharedMath<R>;
    BoundRatio<R> ratio{0.0, "smallpt wall"};
    const R radius = R(1e5);
    for (const glm::dvec3 axis : {glm::dvec3(1, 0, 0), glm::dvec3(0, -1, 0), glm::dvec3(0, 0, -1)}) {
        const Vec3<R> center(axis * (1e5 + 50.0));
        const LongVec center_l = to_long(center);
        const R error = M::shape_point_error(M::sphere_magnitude(center, radius));
        for (int i = 0; i < kHitPoints; ++i) {
            // Points of the wall within the box (a 100-unit square around the axis).
            glm::dvec3 lateral = wp::test::spread_direction(i, kHitPoints) * 45.0;
            lateral -= glm::dot(lateral, axis) * axis;
            Vec3<R> d(glm::normalize(axis * 50.0 + lateral));
            R t = M::intersect_sphere(center, radius, Vec3<R>(0), d, M::real_max);
            ASSERT_NE(t, M::real_max) << "point " << i;
            Vec3<R> p = M::sphere_reproject(center, radius, t * d);
            Vec3<R> n = M::sphere_normal(center, p);
            ratio.add(std::fabs(glm::length(to_long(p) - center_l) - (long double)radius), error);
            Vec3<R> inside = M::offset_ray_origin(p, -n, error);  // the box side
            for (const Vec3<R>& w : leaving_directions<R>(-n)) {
                R exit = M::intersect_sphere(center, radius, inside, w, M::real_max);
                ASSERT_GT(exit, R(1.5) * radius * glm::dot(w, -n)) << "point " << i << " cos " << glm::dot(w, -n);
            }
        }
    }
    EXPECT_LT(ratio.worst, 1.0);
}

TYPED_TEST(Offset, QuadAndPlaneHitPointsLeaveTheSurfaceOnBothSides) {
    using R = TypeParam;
    using M = wp::SharedMath<R>;
    BoundRatio<R> ratio{0.0, "quad and plane"};
    for (const Placement& placement : kPlacements) {
        for (double scale : kScales) {
            SCOPED_TRACE(std::string(placement.name) + ", scale " + std::to_string(scale));
            const Vec3<R> corner((glm::dvec3(-0.6, -0.5, -1.5) + placement.shape_position) * scale);
            const Vec3<R> e1(glm::dvec3(1.2, 0.1, 0.2) * scale), e2(glm::dvec3(0.1, 1.0, -0.4) * scale);
            const Vec3<R> origin(placement.ray_origin * scale);
            const Vec3<R> n = M::quad_normal(e1, e2);
            const LongVec n_l = glm::normalize(glm::cross(to_long(e1), to_long(e2)));
            const R magnitude = M::quad_magnitude(corner, e1, e2);
            for (int i = 0; i < kHitPoints; ++i) {
                double u = 0.02 + 0.96 * ((i * 0.618034) - std::floor(i * 0.618034));
                double v = 0.02 + 0.96 * (i + 0.5) / kHitPoints;
                glm::dvec3 target = glm::dvec3(corner) + u * glm::dvec3(e1) + v * glm::dvec3(e2);
                Vec3<R> d(glm::normalize(target - glm::dvec3(origin)));
                R t = M::intersect_quad(corner, e1, e2, origin, d, M::real_max);
                ASSERT_NE(t, M::real_max) << "point " << i;
                Vec3<R> p = origin + t * d;
                R error = M::ray_point_error(origin, t, magnitude);
                ratio.add(std::fabs(glm::dot(to_long(p) - to_long(corner), n_l)), error);
                for (R side : {R(1), R(-1)}) {
                    Vec3<R> q = M::offset_ray_origin(p, side * n, error);
                    long double signed_distance = glm::dot(to_long(q) - to_long(corner), n_l);
                    ASSERT_GT(side * signed_distance, 0.0L) << "point " << i << " side " << side;
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
    EXPECT_LT(ratio.worst, 1.0);
}

// Scaling a scene by a power of two scales every offset by exactly that
// factor: no absolute epsilon anywhere.
TYPED_TEST(Offset, OffsetScalesWithTheScene) {
    using R = TypeParam;
    using M = wp::SharedMath<R>;
    const Vec3<R> origin(R(0.1), R(0.2), R(-0.3));
    const Vec3<R> corner(R(0.3), R(-1.7), R(2.2)), edge(R(0.5), R(0.25), R(0.0));
    const Vec3<R> n = glm::normalize(Vec3<R>(R(0.2), R(0.5), R(-0.8)));
    const R t = R(2.75);
    auto offset_at_scale = [&](R factor) {
        R error = M::ray_point_error(origin * factor, t * factor,
                                     M::quad_magnitude(corner * factor, edge * factor, edge * factor));
        return M::offset_ray_origin(corner * factor, n, error) - corner * factor;
    };
    const Vec3<R> base = offset_at_scale(R(1));
    EXPECT_GT(glm::length(base), R(0));
    for (int exponent : {-40, -20, -10, -5, 5, 10, 20, 40}) {
        R factor = std::ldexp(R(1), exponent);
        EXPECT_EQ(offset_at_scale(factor), base * factor) << "2^" << exponent;
    }
}

}  // namespace
