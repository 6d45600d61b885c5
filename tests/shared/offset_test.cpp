// Spawned-ray origins (kernels/shared/offset.h). For spheres, quads and planes
// at scales from 1e-6 to 1e6, far from the origin (up to 1e5 times their
// size) and hit by rays from far away (1e4 times their size), the point
// offset by offset_ray_origin lies strictly on the side it was moved to, and
// rays leaving into that side do not meet the surface again (spheres:
// outward rays miss, inward rays reach the far side). Hit points and their
// error bounds are the renderer's (shared/hit_point.h); that the bounds hold
// and are tight is tests/shared/hit_point_test.cpp's.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "core/shared_math.h"
#include "support/directions.h"
#include "support/real_types.h"
#include "support/shape_placements.h"

namespace {

template <class Real>
class Offset : public ::testing::Test {};
TYPED_TEST_SUITE(Offset, wp::test::RealTypes, wp::test::RealTypeNames);

using wp::test::LongVec;
using wp::test::Placement;
using wp::test::to_long;
using wp::test::Vec3;

constexpr int kHitPoints = 200;

const Placement kOffsetPlacements[] = {
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

TYPED_TEST(Offset, SphereHitPointsLeaveTheSurface) {
    using R = TypeParam;
    using M = wp::SharedMath<R>;
    for (const Placement& placement : kOffsetPlacements) {
        for (double scale : wp::test::kShapeScales) {
            SCOPED_TRACE(std::string(placement.name) + ", scale " + std::to_string(scale));
            const Vec3<R> center((glm::dvec3(0.3, -0.2, -2.0) + placement.shape_position) * scale);
            const R radius = R(0.7 * scale);
            const Vec3<R> origin(placement.ray_origin * scale);
            const LongVec center_l = to_long(center);
            const long double radius_l = radius;
            int hits = 0;
            for (int i = 0; i < kHitPoints; ++i) {
                glm::dvec3 target = glm::dvec3(center) + double(radius) * wp::test::spread_direction(i, kHitPoints);
                Vec3<R> d(glm::normalize(target - glm::dvec3(origin)));
                R t = M::intersect_sphere(center, radius, origin, d, M::real_max);
                if (t == M::real_max) continue;
                ++hits;
                const auto [p, n, error] = M::sphere_hit(center, radius, origin, d, t);

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
                    // From 2 error inside, the root's numerator |f|^2 - r^2 ~ -4 r error
                    // is a difference of numbers of size r^2: relative error up to
                    // ~gamma(3) r / (4 error) ~ 15% with error ~ 5 u r.
                    double tolerance = 0.25 * double(expected) + 64.0 * double(error);
                    ASSERT_NEAR(M::intersect_sphere(center, radius, inside, w, M::real_max), double(expected),
                                tolerance)
                        << "point " << i << " inward cos " << -glm::dot(w, n);
                }
            }
            EXPECT_GT(hits, kHitPoints / 4);
        }
    }
}

// The smallpt construction: walls that are spheres of radius 1e5 whose
// centres lie 1e5 + h away, seen from the origin, for boxes of half-size
// h = 50 and h = 1 (a 2-unit room). In float their points are only known to
// ulp(1e5) ~ 0.008; the offset must follow that, not |p| ~ h. Rays leaving
// into the box (along the outward normal n) miss the wall; rays into the
// wall reach its far side.
TYPED_TEST(Offset, HugeSphereWallsOfTheSmallptBox) {
    using R = TypeParam;
    using M = wp::SharedMath<R>;
    const R radius = R(1e5);
    for (double half_size : {50.0, 1.0}) {
        for (const glm::dvec3 axis : {glm::dvec3(1, 0, 0), glm::dvec3(0, -1, 0), glm::dvec3(0, 0, -1)}) {
            SCOPED_TRACE("half size " + std::to_string(half_size));
            const Vec3<R> center(axis * (1e5 + half_size));
            for (int i = 0; i < kHitPoints; ++i) {
                // Points of the wall within the box (a square of 0.9 the box around the axis).
                glm::dvec3 lateral = wp::test::spread_direction(i, kHitPoints) * 0.9 * half_size;
                lateral -= glm::dot(lateral, axis) * axis;
                Vec3<R> d(glm::normalize(axis * half_size + lateral));
                R t = M::intersect_sphere(center, radius, Vec3<R>(0), d, M::real_max);
                ASSERT_NE(t, M::real_max) << "point " << i;
                const auto [p, n, error] = M::sphere_hit(center, radius, Vec3<R>(0), d, t);
                Vec3<R> box_side = M::offset_ray_origin(p, n, error);
                for (const Vec3<R>& w : leaving_directions<R>(n)) {
                    ASSERT_EQ(M::intersect_sphere(center, radius, box_side, w, M::real_max), M::real_max)
                        << "point " << i << " cos " << glm::dot(w, n);
                }
                Vec3<R> wall_side = M::offset_ray_origin(p, -n, error);
                for (const Vec3<R>& w : leaving_directions<R>(-n)) {
                    R exit = M::intersect_sphere(center, radius, wall_side, w, M::real_max);
                    ASSERT_GT(exit, R(1.5) * radius * glm::dot(w, -n)) << "point " << i << " cos " << glm::dot(w, -n);
                }
            }
        }
    }
}

// A hit point p (normal n, bound error) of a flat surface through `anchor`
// with true unit normal n_l, offset to either side, lies on that side, and
// rays leaving into it miss every surface in `surfaces` (distance functions
// of origin and direction).
template <class Real>
void expect_offsets_leave_flat_surface(
    const Vec3<Real>& p, const Vec3<Real>& n, Real error, const Vec3<Real>& anchor, const LongVec& n_l,
    const std::vector<std::function<Real(const Vec3<Real>&, const Vec3<Real>&)>>& surfaces) {
    for (Real side : {Real(1), Real(-1)}) {
        Vec3<Real> q = wp::SharedMath<Real>::offset_ray_origin(p, side * n, error);
        ASSERT_GT(side * glm::dot(to_long(q) - to_long(anchor), n_l), 0.0L) << "side " << side;
        for (const Vec3<Real>& w : leaving_directions<Real>(side * n)) {
            for (std::size_t k = 0; k < surfaces.size(); ++k) {
                ASSERT_EQ(surfaces[k](q, w), wp::SharedMath<Real>::real_max)
                    << "surface " << k << " side " << side << " cos " << glm::dot(w, side * n);
            }
        }
    }
}

TYPED_TEST(Offset, FlatHitPointsLeaveTheSurfaceOnBothSides) {
    using R = TypeParam;
    using M = wp::SharedMath<R>;
    for (const Placement& placement : kOffsetPlacements) {
        for (double scale : wp::test::kShapeScales) {
            SCOPED_TRACE(std::string(placement.name) + ", scale " + std::to_string(scale));
            const Vec3<R> corner((glm::dvec3(-0.6, -0.5, -1.5) + placement.shape_position) * scale);
            const Vec3<R> e1(glm::dvec3(1.2, 0.1, 0.2) * scale), e2(glm::dvec3(0.1, 1.0, -0.4) * scale);
            const Vec3<R> v1 = corner + e1, v2 = corner + e2;  // the triangle of the quad's first half
            const Vec3<R> origin(placement.ray_origin * scale);
            const LongVec quad_n = glm::normalize(glm::cross(to_long(e1), to_long(e2)));
            const LongVec triangle_n =
                glm::normalize(glm::cross(to_long(v1) - to_long(corner), to_long(v2) - to_long(corner)));
            const Vec3<R> plane_n = M::quad_normal(e1, e2);
            auto quad = [&](const Vec3<R>& o, const Vec3<R>& w) {
                return M::intersect_quad(corner, e1, e2, o, w, M::real_max);
            };
            auto plane = [&](const Vec3<R>& o, const Vec3<R>& w) {
                return M::intersect_plane(corner, plane_n, o, w, M::real_max);
            };
            auto triangle = [&](const Vec3<R>& o, const Vec3<R>& w) {
                return M::intersect_triangle(corner, v1, v2, o, w, M::real_max);
            };
            for (int i = 0; i < kHitPoints; ++i) {
                SCOPED_TRACE("point " + std::to_string(i));
                double u = 0.02 + 0.96 * ((i * 0.618034) - std::floor(i * 0.618034));
                double v = 0.02 + 0.96 * (i + 0.5) / kHitPoints;
                glm::dvec3 target = glm::dvec3(corner) + u * glm::dvec3(e1) + v * glm::dvec3(e2);
                Vec3<R> d(glm::normalize(target - glm::dvec3(origin)));
                R t = quad(origin, d);
                ASSERT_NE(t, M::real_max);
                const auto quad_hit = M::quad_hit(corner, e1, e2, origin, d, t);
                expect_offsets_leave_flat_surface<R>(quad_hit.point, quad_hit.normal, quad_hit.error, corner, quad_n,
                                                     {quad, plane});
                if (u + v > 0.98) continue;  // outside the triangle
                ASSERT_NE(triangle(origin, d), M::real_max);
                const auto triangle_hit = M::triangle_hit(corner, v1, v2, origin, d);
                expect_offsets_leave_flat_surface<R>(triangle_hit.point, triangle_hit.normal, triangle_hit.error,
                                                     corner, triangle_n, {triangle});
                if (::testing::Test::HasFatalFailure()) return;
            }
        }
    }
}

// Scaling a scene by a power of two scales every hit point, error bound and
// offset by exactly that factor: no absolute epsilon anywhere. (Up to 2^20:
// beyond, |edge1 x edge2|^2, of the scale's fourth power, leaves float's
// normal range.)
TYPED_TEST(Offset, OffsetScalesWithTheScene) {
    using R = TypeParam;
    using M = wp::SharedMath<R>;
    using HitPoint = typename M::HitPoint;
    const Vec3<R> corner(R(-0.3), R(-0.2), R(-2.2)), e1(R(0.5), R(0.25), R(0.0)), e2(R(0.0), R(0.5), R(0.25));
    const Vec3<R> origin(R(0.1), R(0.2), R(-0.3)), center(R(-0.55), R(-0.3), R(-4.9));
    // towards a point inside the triangle (and the quad); the sphere lies beyond
    const Vec3<R> d = glm::normalize(corner + R(0.25) * e1 + R(0.25) * e2 - origin);
    // Each shape's hit, and where a shadow ray from the hit to the corner would end, at a scale.
    auto hits_at_scale = [&](R f) {
        R t_quad = M::intersect_quad(corner * f, e1 * f, e2 * f, origin * f, d, M::real_max);
        R t_sphere = M::intersect_sphere(center * f, R(0.8) * f, origin * f, d, M::real_max);
        R t_triangle =
            M::intersect_triangle(corner * f, (corner + e1) * f, (corner + e2) * f, origin * f, d, M::real_max);
        HitPoint quad = M::quad_hit(corner * f, e1 * f, e2 * f, origin * f, d, t_quad);
        std::vector<HitPoint> hits = {quad, M::plane_hit(corner * f, quad.normal, origin * f, d, t_quad),
                                      M::sphere_hit(center * f, R(0.8) * f, origin * f, d, t_sphere),
                                      M::triangle_hit(corner * f, (corner + e1) * f, (corner + e2) * f, origin * f, d)};
        EXPECT_NE(t_triangle, M::real_max);
        EXPECT_NE(t_quad, M::real_max);
        EXPECT_NE(t_sphere, M::real_max);
        R light_error = M::shadow_target_error(quad.point, corner * f, M::quad_magnitude(corner * f, e1 * f, e2 * f));
        hits.push_back(HitPoint{M::offset_ray_origin(corner * f, quad.normal, light_error), quad.normal, light_error});
        return hits;
    };
    const std::vector<HitPoint> base = hits_at_scale(R(1));
    for (const HitPoint& h : base) EXPECT_GT(h.error, R(0));
    for (int exponent : {-20, -10, -5, 5, 10, 20}) {
        R factor = std::ldexp(R(1), exponent);
        const std::vector<HitPoint> scaled = hits_at_scale(factor);
        for (std::size_t i = 0; i < base.size(); ++i) {
            SCOPED_TRACE("2^" + std::to_string(exponent) + ", shape " + std::to_string(i));
            EXPECT_EQ(scaled[i].point, base[i].point * factor);
            EXPECT_EQ(scaled[i].error, base[i].error * factor);
            EXPECT_EQ(M::offset_ray_origin(scaled[i].point, scaled[i].normal, scaled[i].error),
                      M::offset_ray_origin(base[i].point, base[i].normal, base[i].error) * factor);
        }
    }
}

}  // namespace
