// Each light shape's density (kernels/shared/lights.h, triangle.h) as a
// function of any point on the light, float and double: integrated over the
// directions from a reference point, by directions drawn uniformly over the
// sphere and traced to the light with the shared intersection tests, it is 1
// (every sample the light's sampler makes lands on it), or for one triangle
// of a mesh light its share of the mesh's area. This checks the densities
// independently of the samplers (whose own returned densities
// sampling_test.cpp checks). Means are accepted within kSigmaTolerance = 4.5
// standard errors of the estimate (false failure 6.8e-6 per check); fixed
// seeds.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <functional>
#include <numbers>

#include "core/shared_math.h"
#include "support/real_types.h"
#include "support/statistics.h"

namespace {

using wp::test::kSigmaTolerance;
using wp::test::Vec3;

template <class Real>
class LightPdfs : public ::testing::Test {};
TYPED_TEST_SUITE(LightPdfs, wp::test::RealTypes, wp::test::RealTypeNames);

// Where a ray from the reference point meets the light, and the light's
// density there; 0 where it misses.
template <class Real>
using DensityAlong = std::function<double(const Vec3<Real>& direction)>;

// The integral of the density over the sphere of directions, as the mean of
// 4 pi density(direction) over uniform directions.
template <class Real>
void expect_integral(const DensityAlong<Real>& density, double expected, const char* label) {
    wp::test::RunningMean integral;
    for (std::uint32_t i = 0; i < 400000; ++i) {
        double z = 1.0 - 2.0 * wp::SharedMath<double>::rng_uniform(3u, i, 0u, 0u, 0u);
        double phi = 2.0 * std::numbers::pi * wp::SharedMath<double>::rng_uniform(3u, i, 0u, 0u, 1u);
        double r = std::sqrt(std::max(0.0, 1.0 - z * z));
        integral.add(4.0 * std::numbers::pi * density(Vec3<Real>(glm::dvec3(r * std::cos(phi), r * std::sin(phi), z))));
    }
    EXPECT_NEAR(integral.mean(), expected, kSigmaTolerance * integral.standard_error())
        << label << ": standard error " << integral.standard_error();
    EXPECT_GT(integral.standard_error(), 0.0) << label << ": the light was never hit";
}

TYPED_TEST(LightPdfs, QuadDensityIntegratesToOne) {
    using R = TypeParam;
    using M = wp::SharedMath<R>;
    const Vec3<R> corner(-0.6, 0.8, -0.9), edge1(1.4, 0.3, 0), edge2(0.2, 0, 1.1), reference(0.1, -0.2, 0.05);
    expect_integral<R>(
        [&](const Vec3<R>& d) {
            R t = M::intersect_quad(corner, edge1, edge2, reference, d, M::real_max);
            if (t == M::real_max) return 0.0;
            Vec3<R> point = reference + t * d;
            return double(M::quad_light_pdf(edge1, edge2, reference, point, M::quad_normal(edge1, edge2)));
        },
        1.0, "quad");
}

// From outside (cone sampling) and from inside (area sampling).
TYPED_TEST(LightPdfs, SphereDensityIntegratesToOne) {
    using R = TypeParam;
    using M = wp::SharedMath<R>;
    const Vec3<R> center(0.3, 1.2, -0.4);
    const R radius = R(0.7);
    for (Vec3<R> reference : {Vec3<R>(0, 0, 0), Vec3<R>(0.5, 1.0, -0.2)}) {
        expect_integral<R>(
            [&](const Vec3<R>& d) {
                R t = M::intersect_sphere(center, radius, reference, d, M::real_max);
                if (t == M::real_max) return 0.0;
                Vec3<R> point = reference + t * d;
                return double(M::sphere_light_pdf(center, radius, reference, point, M::sphere_normal(center, point)));
            },
            1.0, M::sphere_cone_applies(center, radius, reference) ? "sphere from outside" : "sphere from inside");
    }
}

// A triangle of a mesh light whose area is 2.5 times the triangle's holds
// 1 / 2.5 of the light's samples.
TYPED_TEST(LightPdfs, MeshDensityIsTheTrianglesShareOfTheMesh) {
    using R = TypeParam;
    using M = wp::SharedMath<R>;
    const Vec3<R> p0(-0.8, 0.9, -1.0), p1(0.9, 1.1, -0.7), p2(0.1, 0.6, 0.9), reference(0.05, -0.1, 0);
    const double area = 0.5 * glm::length(glm::cross(glm::dvec3(p1 - p0), glm::dvec3(p2 - p0)));
    const R mesh_area = R(2.5 * area);
    expect_integral<R>(
        [&](const Vec3<R>& d) {
            R t = M::intersect_triangle(p0, p1, p2, reference, d, M::real_max);
            if (t == M::real_max) return 0.0;
            Vec3<R> point = reference + t * d;
            return double(M::mesh_light_pdf(mesh_area, reference, point, M::triangle_normal(p0, p1, p2)));
        },
        1.0 / 2.5, "one triangle of a mesh light");
}

}  // namespace
