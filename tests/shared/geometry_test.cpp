// Ray-primitive intersection (kernels/shared/geometry.h), float and double.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "core/shared_math.h"
#include "support/real_types.h"

namespace {

template <class Real>
class Geometry : public ::testing::Test {};
TYPED_TEST_SUITE(Geometry, wp::test::RealTypes, wp::test::RealTypeNames);

using wp::test::Vec3;

template <class Real>
constexpr Real kMiss = wp::SharedMath<Real>::real_max;

template <class Real>
constexpr Real kNoLimit = wp::SharedMath<Real>::real_max;

// Relative tolerance of a few roundings.
template <class Real>
constexpr double kRel = 8.0 * std::numeric_limits<Real>::epsilon();

// Unit sphere at the origin.
template <class Real>
Real hit_unit_sphere(Vec3<Real> origin, Vec3<Real> direction, Real t_max = kNoLimit<Real>) {
    return wp::SharedMath<Real>::intersect_sphere(Vec3<Real>(0), Real(1), origin, direction, t_max);
}

TYPED_TEST(Geometry, SphereFromOutsideHitsNearSide) {
    using R = TypeParam;
    EXPECT_EQ(hit_unit_sphere<R>({0, 0, 5}, {0, 0, -1}), R(4));
    // Off-axis: t = 5 - sqrt(1 - 0.6^2) = 4.2.
    EXPECT_NEAR(hit_unit_sphere<R>({R(0.6), 0, 5}, {0, 0, -1}), 4.2, 4.2 * kRel<R>);
}

TYPED_TEST(Geometry, SphereFromInsideHitsExit) {
    using R = TypeParam;
    EXPECT_EQ(hit_unit_sphere<R>({0, 0, R(0.5)}, {0, 0, 1}), R(0.5));
    EXPECT_EQ(hit_unit_sphere<R>({0, 0, R(0.5)}, {0, 0, -1}), R(1.5));
    EXPECT_EQ(hit_unit_sphere<R>({0, 0, 0}, {1, 0, 0}), R(1));
}

TYPED_TEST(Geometry, SphereTangentRayTouchesAndNeighbourMisses) {
    using R = TypeParam;
    // The ray y = 1 touches the unit sphere at (0, 1, 0): discriminant exactly 0.
    EXPECT_EQ(hit_unit_sphere<R>({-5, 1, 0}, {1, 0, 0}), R(5));
    EXPECT_EQ(hit_unit_sphere<R>({-5, R(1.001), 0}, {1, 0, 0}), kMiss<R>);
}

TYPED_TEST(Geometry, SphereBehindOriginMisses) {
    using R = TypeParam;
    EXPECT_EQ(hit_unit_sphere<R>({0, 0, 5}, {0, 0, 1}), kMiss<R>);
    EXPECT_EQ(hit_unit_sphere<R>({3, 0, 0}, {1, 0, 0}), kMiss<R>);
}

TYPED_TEST(Geometry, SphereRespectsTMax) {
    using R = TypeParam;
    EXPECT_EQ(hit_unit_sphere<R>({0, 0, 5}, {0, 0, -1}, R(3.9)), kMiss<R>);
    EXPECT_EQ(hit_unit_sphere<R>({0, 0, 5}, {0, 0, -1}, R(4.1)), R(4));
    // From inside with the exit beyond t_max: nothing.
    EXPECT_EQ(hit_unit_sphere<R>({0, 0, 0}, {0, 0, 1}, R(0.5)), kMiss<R>);
}

TYPED_TEST(Geometry, SmallDistantSphereKeepsPrecision) {
    using R = TypeParam;
    using M = wp::SharedMath<R>;
    // Radius 1e-3 seen from 1e3 away: the textbook discriminant b^2 - c
    // cancels completely in float; the Haines form does not.
    R t = M::intersect_sphere(Vec3<R>(0, 0, 0), R(1e-3), Vec3<R>(0, 0, R(1e3)), Vec3<R>(0, 0, -1), kNoLimit<R>);
    EXPECT_NEAR(t, 1e3 - 1e-3, 1e3 * kRel<R>);
    // Huge sphere (radius 1e5, smallpt-style wall) from near its surface.
    R t_wall =
        M::intersect_sphere(Vec3<R>(0, 0, R(-1e5 - 1)), R(1e5), Vec3<R>(0, 0, 0), Vec3<R>(0, 0, -1), kNoLimit<R>);
    EXPECT_NEAR(t_wall, 1.0, 1e5 * kRel<R>);
}

TYPED_TEST(Geometry, PlaneHitFromEitherSideWithUnnormalisedNormal) {
    using R = TypeParam;
    using M = wp::SharedMath<R>;
    Vec3<R> point(0, 0, -2), normal(0, 0, 2);
    EXPECT_EQ(M::intersect_plane(point, normal, Vec3<R>(0), Vec3<R>(0, 0, -1), kNoLimit<R>), R(2));
    EXPECT_EQ(M::intersect_plane(point, normal, Vec3<R>(0, 0, -5), Vec3<R>(0, 0, 1), kNoLimit<R>), R(3));
    Vec3<R> oblique = glm::normalize(Vec3<R>(1, 0, -1));
    EXPECT_NEAR(M::intersect_plane(point, normal, Vec3<R>(0), oblique, kNoLimit<R>), 2.0 * std::sqrt(2.0),
                3.0 * kRel<R>);
}

TYPED_TEST(Geometry, PlaneParallelRayMisses) {
    using R = TypeParam;
    using M = wp::SharedMath<R>;
    Vec3<R> point(0, 0, -2), normal(0, 0, 1);
    EXPECT_EQ(M::intersect_plane(point, normal, Vec3<R>(0), Vec3<R>(1, 0, 0), kNoLimit<R>), kMiss<R>);
    // Lying inside the plane counts as a miss too.
    EXPECT_EQ(M::intersect_plane(point, normal, Vec3<R>(0, 0, -2), Vec3<R>(0, 1, 0), kNoLimit<R>), kMiss<R>);
}

TYPED_TEST(Geometry, PlaneBehindOrBeyondTMaxMisses) {
    using R = TypeParam;
    using M = wp::SharedMath<R>;
    Vec3<R> point(0, 0, -2), normal(0, 0, 1);
    EXPECT_EQ(M::intersect_plane(point, normal, Vec3<R>(0), Vec3<R>(0, 0, 1), kNoLimit<R>), kMiss<R>);
    EXPECT_EQ(M::intersect_plane(point, normal, Vec3<R>(0), Vec3<R>(0, 0, -1), R(2)), kMiss<R>);
}

// Quad corner (0,0,0), edge1 (2,0,0), edge2 (0,1,0); rays straight down from
// z = 1 land exactly on (x, y, 0), where u = x/2 and v = y are exact.
template <class Real>
Real hit_quad_from_above(Real x, Real y) {
    return wp::SharedMath<Real>::intersect_quad(Vec3<Real>(0), Vec3<Real>(2, 0, 0), Vec3<Real>(0, 1, 0),
                                                Vec3<Real>(x, y, 1), Vec3<Real>(0, 0, -1), kNoLimit<Real>);
}

TYPED_TEST(Geometry, QuadInteriorEdgesAndCornersHit) {
    using R = TypeParam;
    const R inside[][2] = {{1, R(0.5)}, {0, R(0.5)}, {2, R(0.5)}, {1, 0}, {1, 1}, {0, 0}, {2, 0}, {0, 1}, {2, 1}};
    for (const auto& xy : inside) EXPECT_EQ(hit_quad_from_above<R>(xy[0], xy[1]), R(1)) << xy[0] << ", " << xy[1];
}

TYPED_TEST(Geometry, QuadJustOutsideEachEdgeAndCornerMisses) {
    using R = TypeParam;
    const R e = R(1e-3);
    const R outside[][2] = {{-e, R(0.5)}, {2 + e, R(0.5)}, {1, -e},     {1, 1 + e},
                            {-e, -e},     {2 + e, 1 + e},  {2 + e, -e}, {-e, 1 + e}};
    for (const auto& xy : outside) EXPECT_EQ(hit_quad_from_above<R>(xy[0], xy[1]), kMiss<R>) << xy[0] << ", " << xy[1];
}

TYPED_TEST(Geometry, QuadBackSideHitsAndBehindMisses) {
    using R = TypeParam;
    using M = wp::SharedMath<R>;
    Vec3<R> corner(0), e1(2, 0, 0), e2(0, 1, 0);
    EXPECT_EQ(M::intersect_quad(corner, e1, e2, Vec3<R>(1, R(0.5), -1), Vec3<R>(0, 0, 1), kNoLimit<R>), R(1));
    EXPECT_EQ(M::intersect_quad(corner, e1, e2, Vec3<R>(1, R(0.5), 1), Vec3<R>(0, 0, 1), kNoLimit<R>), kMiss<R>);
    EXPECT_EQ(M::intersect_quad(corner, e1, e2, Vec3<R>(1, R(0.5), 1), Vec3<R>(1, 0, 0), kNoLimit<R>), kMiss<R>);
}

TYPED_TEST(Geometry, SkewedParallelogramUsesItsOwnEdges) {
    using R = TypeParam;
    using M = wp::SharedMath<R>;
    // Corner 0, edges (1,0,0) and (1,1,0): the point (x, y) has v = y, u = x - y.
    Vec3<R> corner(0), e1(1, 0, 0), e2(1, 1, 0);
    auto hit = [&](R x, R y) {
        return M::intersect_quad(corner, e1, e2, Vec3<R>(x, y, 1), Vec3<R>(0, 0, -1), kNoLimit<R>);
    };
    EXPECT_EQ(hit(R(1.5), R(0.75)), R(1));       // u = 0.75, v = 0.75
    EXPECT_EQ(hit(R(0.25), R(0.5)), kMiss<R>);   // u = -0.25: inside the bounding box, outside the quad
    EXPECT_EQ(hit(R(1.75), R(0.25)), kMiss<R>);  // u = 1.5
}

TYPED_TEST(Geometry, NormalsAndSphereReprojection) {
    using R = TypeParam;
    using M = wp::SharedMath<R>;
    Vec3<R> n = M::quad_normal(Vec3<R>(2, 0, 0), Vec3<R>(0, 3, 0));
    EXPECT_EQ(n, Vec3<R>(0, 0, 1));
    Vec3<R> center(1, 2, 3);
    Vec3<R> p = M::sphere_reproject(center, R(2), center + Vec3<R>(0, R(2.5), 0));
    EXPECT_NEAR(p.y, 4.0, 4.0 * kRel<R>);
    EXPECT_EQ(M::sphere_normal(center, p), Vec3<R>(0, 1, 0));
}

}  // namespace
