// Error bounds of ray hit points (kernels/shared/hit_point.h) against the
// errors they bound. For spheres (seen from outside and from inside, and the
// radius-1e5 walls of a unit-sized smallpt box), planes, quads and
// triangles, at scales 1e-6 to 1e6, near the origin, translated by 1e5 their
// size and hit by rays from 1e4 their size away, random rays (fixed seed)
// give hit points whose true distance from the surface is measured in long
// double. For every shape, in float and in double:
//  - no distance exceeds its bound (the bound is a bound);
//  - the largest distance / bound is at least 1/4 (the bound is within 4x
//    of the worst error measured: offsets stay as small as the arithmetic
//    allows, which the sphere's old gamma(16) (|center| + r) was not, by
//    20-40x on the smallpt walls).
// Both hold separately for each placement, so no term of a bound may be
// loose where it dominates.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <random>
#include <string>

#include "core/shared_math.h"
#include "support/real_types.h"
#include "support/shape_placements.h"

namespace {

template <class Real>
class HitPoint : public ::testing::Test {};
TYPED_TEST_SUITE(HitPoint, wp::test::RealTypes, wp::test::RealTypeNames);

using wp::test::LongVec;
using wp::test::Placement;
using wp::test::to_long;
using wp::test::Vec3;

constexpr int kRaysPerScale = 400;
constexpr double kLeastWorstRatio = 0.25;  // bound <= 4x the worst error measured

const Placement kHitPointPlacements[] = {
    {"near the origin", {0, 0, 0}, {0, 0, 2}},
    {"translated by 1e5", {1e5, -3e4, 2e4}, {1e5, -3e4, 2e4 + 2.0}},
    {"rays from 1e4 away", {0, 0, 0}, {2e3, 5e3, 8e3}},
};

// The largest true distance / bound over many hit points.
struct WorstRatio {
    double worst = 0.0;
    int points = 0;
    void add(long double distance, double bound) {
        ASSERT_GT(bound, 0.0);
        ASSERT_LE(double(distance), bound) << "hit point " << points << ": distance " << double(distance);
        worst = std::max(worst, double(distance / bound));
        ++points;
    }
};

// One ray towards a random point of the shape; fills the ratio.
template <class Real>
using AddHit = std::function<void(std::mt19937_64& random, const glm::dvec3& shape_position, double scale,
                                  const Vec3<Real>& origin, WorstRatio& ratio)>;

// Runs add_hit over every placement and scale; checks and prints the worst
// ratio of each placement.
template <class Real>
void check_bound_tightness(const char* shape, const AddHit<Real>& add_hit) {
    std::mt19937_64 random(12345);
    std::uniform_real_distribution<double> jitter(-0.5, 0.5);
    for (const Placement& placement : kHitPointPlacements) {
        WorstRatio ratio;
        for (double scale : wp::test::kShapeScales) {
            SCOPED_TRACE(std::string(shape) + ", " + placement.name + ", scale " + std::to_string(scale));
            for (int i = 0; i < kRaysPerScale; ++i) {
                glm::dvec3 origin = placement.ray_origin + glm::dvec3(jitter(random), jitter(random), jitter(random));
                add_hit(random, placement.shape_position * scale, scale, Vec3<Real>(origin * scale), ratio);
                if (::testing::Test::HasFatalFailure()) return;
            }
        }
        std::printf("[%s, %s] %d hit points, largest distance from the surface / bound: %.3f\n", shape, placement.name,
                    ratio.points, ratio.worst);
        EXPECT_GT(ratio.points, kRaysPerScale) << shape << ", " << placement.name;
        EXPECT_GE(ratio.worst, kLeastWorstRatio) << shape << ", " << placement.name;
    }
}

glm::dvec3 random_direction(std::mt19937_64& random) {
    std::normal_distribution<double> gaussian;
    return glm::normalize(glm::dvec3(gaussian(random), gaussian(random), gaussian(random)));
}

template <class Real>
void add_sphere_hit(const Vec3<Real>& center, Real radius, const Vec3<Real>& origin, const Vec3<Real>& direction,
                    WorstRatio& ratio) {
    using M = wp::SharedMath<Real>;
    Real t = M::intersect_sphere(center, radius, origin, direction, M::real_max);
    if (t == M::real_max) return;
    typename M::HitPoint h = M::sphere_hit(center, radius, origin, direction, t);
    ratio.add(std::fabs(glm::length(to_long(h.point) - to_long(center)) - (long double)radius), double(h.error));
}

TYPED_TEST(HitPoint, SphereBoundIsTight) {
    using R = TypeParam;
    check_bound_tightness<R>("sphere", [](std::mt19937_64& random, const glm::dvec3& position, double scale,
                                          const Vec3<R>& origin, WorstRatio& ratio) {
        const Vec3<R> center(glm::dvec3(0.3, -0.2, -2.0) * scale + position);
        const R radius = R(0.7 * scale);
        glm::dvec3 target = glm::dvec3(center) + double(radius) * random_direction(random);
        add_sphere_hit(center, radius, origin, Vec3<R>(glm::normalize(target - glm::dvec3(origin))), ratio);
    });
}

TYPED_TEST(HitPoint, SphereBoundIsTightFromInside) {
    using R = TypeParam;
    check_bound_tightness<R>("sphere from inside", [](std::mt19937_64& random, const glm::dvec3& position, double scale,
                                                      const Vec3<R>& origin, WorstRatio& ratio) {
        // The sphere holds the ray origins' cube.
        const Vec3<R> center(glm::dvec3(origin) + glm::dvec3(0.3, -0.2, 0.1) * scale);
        const R radius = R(1.5 * scale);
        (void)position;
        add_sphere_hit(center, radius, origin, Vec3<R>(random_direction(random)), ratio);
    });
}

// The smallpt construction at unit scale: a 2-unit box whose walls are
// spheres of radius 1e5, seen from inside the box (placements move the box).
TYPED_TEST(HitPoint, SphereBoundIsTightOnSmallptWalls) {
    using R = TypeParam;
    const glm::dvec3 axes[] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    check_bound_tightness<R>("smallpt wall", [&axes](std::mt19937_64& random, const glm::dvec3& position, double scale,
                                                     const Vec3<R>& origin, WorstRatio& ratio) {
        std::uniform_real_distribution<double> jitter(-0.5, 0.5);
        const glm::dvec3 box_center =
            glm::dvec3(origin) + glm::dvec3(jitter(random), jitter(random), jitter(random)) * scale;
        const glm::dvec3 axis = axes[std::uniform_int_distribution<int>(0, 5)(random)];
        const Vec3<R> center(box_center + axis * (1e5 + 1.0) * scale);
        const R radius = R(1e5 * scale);
        (void)position;
        glm::dvec3 direction = random_direction(random);
        if (glm::dot(direction, axis) < 0.0) direction = -direction;
        add_sphere_hit(center, radius, origin, Vec3<R>(direction), ratio);
    });
}

TYPED_TEST(HitPoint, PlaneBoundIsTight) {
    using R = TypeParam;
    using M = wp::SharedMath<R>;
    check_bound_tightness<R>("plane", [](std::mt19937_64& random, const glm::dvec3& position, double scale,
                                         const Vec3<R>& origin, WorstRatio& ratio) {
        const Vec3<R> anchor(glm::dvec3(-0.6, -0.5, -1.5) * scale + position);
        const Vec3<R> normal(glm::normalize(glm::dvec3(0.2, 0.9, 0.4)));
        // Targets up to 10 sizes from the anchor.
        glm::dvec3 in_plane = random_direction(random) * 10.0 * scale;
        glm::dvec3 target = glm::dvec3(anchor) + in_plane - glm::dot(in_plane, glm::dvec3(normal)) * glm::dvec3(normal);
        Vec3<R> direction(glm::normalize(target - glm::dvec3(origin)));
        R t = M::intersect_plane(anchor, normal, origin, direction, M::real_max);
        if (t == M::real_max) return;
        typename M::HitPoint h = M::plane_hit(anchor, normal, origin, direction, t);
        const LongVec n = glm::normalize(to_long(normal));
        ratio.add(std::fabs(glm::dot(to_long(h.point) - to_long(anchor), n)), double(h.error));
    });
}

TYPED_TEST(HitPoint, QuadBoundIsTight) {
    using R = TypeParam;
    using M = wp::SharedMath<R>;
    check_bound_tightness<R>("quad", [](std::mt19937_64& random, const glm::dvec3& position, double scale,
                                        const Vec3<R>& origin, WorstRatio& ratio) {
        const Vec3<R> corner(glm::dvec3(-0.6, -0.5, -1.5) * scale + position);
        const Vec3<R> e1(glm::dvec3(1.2, 0.1, 0.2) * scale), e2(glm::dvec3(0.1, 1.0, -0.4) * scale);
        std::uniform_real_distribution<double> unit(0.0, 1.0);
        glm::dvec3 target = glm::dvec3(corner) + unit(random) * glm::dvec3(e1) + unit(random) * glm::dvec3(e2);
        Vec3<R> direction(glm::normalize(target - glm::dvec3(origin)));
        R t = M::intersect_quad(corner, e1, e2, origin, direction, M::real_max);
        if (t == M::real_max) return;
        typename M::HitPoint h = M::quad_hit(corner, e1, e2, origin, direction, t);
        const LongVec n = glm::normalize(glm::cross(to_long(e1), to_long(e2)));
        ratio.add(std::fabs(glm::dot(to_long(h.point) - to_long(corner), n)), double(h.error));
    });
}

TYPED_TEST(HitPoint, TriangleBoundIsTight) {
    using R = TypeParam;
    using M = wp::SharedMath<R>;
    check_bound_tightness<R>("triangle", [](std::mt19937_64& random, const glm::dvec3& position, double scale,
                                            const Vec3<R>& origin, WorstRatio& ratio) {
        const Vec3<R> p0(glm::dvec3(-0.6, -0.5, -1.5) * scale + position);
        const Vec3<R> p1(glm::dvec3(0.7, -0.3, -1.2) * scale + position);
        const Vec3<R> p2(glm::dvec3(-0.2, 0.6, -2.1) * scale + position);
        std::uniform_real_distribution<double> unit(0.0, 1.0);
        double root = std::sqrt(unit(random)), b1 = 1.0 - root, b2 = unit(random) * root;
        glm::dvec3 target = (1.0 - b1 - b2) * glm::dvec3(p0) + b1 * glm::dvec3(p1) + b2 * glm::dvec3(p2);
        Vec3<R> direction(glm::normalize(target - glm::dvec3(origin)));
        R t = M::intersect_triangle(p0, p1, p2, origin, direction, M::real_max);
        if (t == M::real_max) return;
        typename M::HitPoint h = M::triangle_hit(p0, p1, p2, origin, direction);
        const LongVec n = glm::normalize(glm::cross(to_long(p1) - to_long(p0), to_long(p2) - to_long(p0)));
        ratio.add(std::fabs(glm::dot(to_long(h.point) - to_long(p0), n)), double(h.error));
    });
}

}  // namespace
