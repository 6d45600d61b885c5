// Shading normals of mesh triangles (kernels/shared/triangle.h), float and
// double: the vertex normals interpolated by barycentric coordinates,
// normalised and turned to the geometric normal's side; the geometric normal
// where a triangle has none or they cancel.
#include <gtest/gtest.h>

#include <glm/geometric.hpp>
#include <limits>

#include "core/shared_math.h"
#include "support/real_types.h"

namespace {

template <class Real>
class TriangleShading : public ::testing::Test {};
TYPED_TEST_SUITE(TriangleShading, wp::test::RealTypes, wp::test::RealTypeNames);

using wp::test::Vec3;

template <class Real>
constexpr double kTolerance = 16.0 * std::numeric_limits<Real>::epsilon();

template <class Real>
void expect_near(const glm::vec<3, Real>& got, const glm::vec<3, Real>& expected) {
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(got[i], expected[i], kTolerance<Real>) << "component " << i;
}

// A skewed triangle off the origin with three different unit vertex normals.
template <class Real>
struct Fixture {
    Vec3<Real> p0{1, 2, 3}, p1{4, 2.5, 3}, p2{1.5, 6, 3.25};
    Vec3<Real> n0 = glm::normalize(Vec3<Real>(0.3, 0.1, 1)), n1 = glm::normalize(Vec3<Real>(-0.2, 0.4, 1)),
               n2 = glm::normalize(Vec3<Real>(0.1, -0.5, 1));
    Vec3<Real> geometric = wp::SharedMath<Real>::triangle_normal(p0, p1, p2);

    Vec3<Real> at(Real b1, Real b2) const {
        Vec3<Real> p = p0 + b1 * (p1 - p0) + b2 * (p2 - p0);
        return wp::SharedMath<Real>::triangle_shading_normal(p0, p1, p2, n0, n1, n2, geometric, p);
    }
};

TYPED_TEST(TriangleShading, VertexNormalsAtTheVertices) {
    Fixture<TypeParam> f;
    ASSERT_GT(glm::dot(f.geometric, f.n0), 0);  // the fixture's normals lie on the front
    expect_near(f.at(0, 0), f.n0);
    expect_near(f.at(1, 0), f.n1);
    expect_near(f.at(0, 1), f.n2);
}

TYPED_TEST(TriangleShading, InteriorPointsInterpolateByBarycentrics) {
    using R = TypeParam;
    Fixture<R> f;
    for (auto [b1, b2] : {std::pair<R, R>(0.3, 0.5), {0.1, 0.1}, {0.6, 0.05}, {0.25, 0.75}}) {
        SCOPED_TRACE(testing::Message() << "b1 " << b1 << " b2 " << b2);
        expect_near(f.at(b1, b2), glm::normalize((1 - b1 - b2) * f.n0 + b1 * f.n1 + b2 * f.n2));
    }
}

TYPED_TEST(TriangleShading, NormalsOnTheBackAreTurnedToTheFront) {
    Fixture<TypeParam> f;
    f.n0 = -f.n0, f.n1 = -f.n1, f.n2 = -f.n2;  // a file wound against its normals
    Vec3<TypeParam> expected = glm::normalize(f.n0 * TypeParam(0.2) + f.n1 * TypeParam(0.3) + f.n2 * TypeParam(0.5));
    expect_near(f.at(0.3, 0.5), -expected);
}

TYPED_TEST(TriangleShading, NoNormalsOrCancellingOnesGiveTheGeometricNormal) {
    Fixture<TypeParam> f;
    f.n0 = f.n1 = f.n2 = Vec3<TypeParam>(0);  // a triangle without vertex normals
    EXPECT_EQ(f.at(0.3, 0.5), f.geometric);
    f.n0 = Vec3<TypeParam>(1, 0, 0), f.n1 = Vec3<TypeParam>(-1, 0, 0);  // opposite at the ends of an edge
    EXPECT_EQ(f.at(0.5, 0), f.geometric);
}

// A sliver 1e-4 wide: barycentrics from areas stay accurate where those from
// the Gram matrix of the edges would lose most of their digits.
TYPED_TEST(TriangleShading, SliverTrianglesInterpolateAccurately) {
    using R = TypeParam;
    Fixture<R> f;
    f.p0 = Vec3<R>(0), f.p1 = Vec3<R>(1000, 0, 0), f.p2 = Vec3<R>(500, R(1e-4), 0);
    f.geometric = wp::SharedMath<R>::triangle_normal(f.p0, f.p1, f.p2);
    expect_near(f.at(0.25, 0.5), glm::normalize(R(0.25) * f.n0 + R(0.25) * f.n1 + R(0.5) * f.n2));
}

}  // namespace
