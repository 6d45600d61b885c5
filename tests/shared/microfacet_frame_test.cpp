// The frame of an anisotropic rough material's microfacets
// (kernels/shared/materials/microfacet.h' microfacet_frame): its tangent,
// along which alpha_u lies, is the surface's dp/du made orthogonal to the
// shading normal, as Mitsuba 3's shading frame. Checked per shape against
// the uv parameterisation the textures use (shared/texture.h), by stepping
// along the tangent: v stays put and u grows at 1 / |dp/du| -- the sphere's
// azimuth, a quad's edge1, a triangle's uv gradient. An isotropic material
// keeps the frame built from the normal alone, bit for bit; a plane (no
// dp/du) keeps its tangent; and both sides of a surface see one axis.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "core/shared_math.h"
#include "support/directions.h"
#include "support/real_types.h"

namespace {
namespace microfacet_frame_test {

template <class Real>
class MicrofacetFrame : public ::testing::Test {};
TYPED_TEST_SUITE(MicrofacetFrame, wp::test::RealTypes, wp::test::RealTypeNames);

using D = wp::SharedMath<double>;

template <class Real>
typename wp::SharedMath<Real>::Microfacet anisotropic() {
    return {WP_MICROFACET_GGX, Real(0.05), Real(0.4)};
}

// The uv's rate of change per unit length along `tangent` at p, by central
// differences of `uv_at` (a point to its uv) over +-h; a difference in u is
// taken modulo 1 (the sphere's azimuth wraps there).
template <class UvAt>
D::TextureUV uv_rate(UvAt uv_at, const glm::dvec3& p, const glm::dvec3& tangent, double h) {
    const D::TextureUV ahead = uv_at(p + tangent * h), behind = uv_at(p - tangent * h);
    const double du = ahead.u - behind.u;
    return D::make_texture_uv((du - std::round(du)) / (2 * h), (ahead.v - behind.v) / (2 * h));
}

template <class Real>
glm::dvec3 tangent_of(const typename wp::SharedMath<Real>::Frame& frame) {
    return glm::dvec3(frame.tangent);
}

// Tolerances: the float frame's rounding (a few ulps of its unit tangent)
// plus the central differences' h^2 error.
template <class Real>
constexpr double kTangentTolerance = std::is_same_v<Real, float> ? 2e-5 : 1e-7;

// Mitsuba's sphere: u the azimuth about +z over 2 pi, v the polar angle over
// pi (sphere_uv). Along the tangent v is constant and u grows at
// 1 / (2 pi r sin theta), the analytic |dp/du|^-1.
TYPED_TEST(MicrofacetFrame, OnASphereTheTangentIsTheAzimuthsDerivative) {
    using Real = TypeParam;
    using M = wp::SharedMath<Real>;
    const glm::dvec3 center(0.3, -1.2, 2.0);
    const double radius = 1.7;
    int checked = 0;
    for (int i = 0; i < 200; ++i) {
        const glm::dvec3 n = wp::test::spread_direction(i, 200);
        const double sin_theta = std::sqrt(n.x * n.x + n.y * n.y);
        if (sin_theta < 0.05) continue;  // near the poles the azimuth's differences lose their precision
        const typename M::vec3 normal(n);
        const typename M::Frame frame =
            M::microfacet_frame(anisotropic<Real>(), M::frame_from_normal(normal), M::sphere_dp_du(normal));
        const glm::dvec3 t = tangent_of<Real>(frame);
        auto uv_at = [&](const glm::dvec3& q) { return D::sphere_uv(glm::normalize(q - center)); };
        const D::TextureUV rate = uv_rate(uv_at, center + n * radius, t, 1e-4);
        EXPECT_NEAR(rate.v, 0.0, kTangentTolerance<Real>) << "normal " << i;
        EXPECT_NEAR(rate.u * 2 * std::numbers::pi * radius * sin_theta, 1.0, 10 * kTangentTolerance<Real>)
            << "normal " << i;
        EXPECT_NEAR(glm::dot(t, n), 0.0, kTangentTolerance<Real>);
        ++checked;
    }
    EXPECT_GT(checked, 150);
}

// A quad corner + u edge1 + v edge2 (quad_uv, Mitsuba's rectangle): the
// tangent is edge1's direction even where edge2 is not orthogonal to it.
TYPED_TEST(MicrofacetFrame, OnAQuadTheTangentIsEdge1) {
    using Real = TypeParam;
    using M = wp::SharedMath<Real>;
    const glm::dvec3 corner(1, 0.5, -2), edge1(2, 0.5, -1), edge2(0.5, 1.5, 1);
    const glm::dvec3 n = glm::normalize(glm::cross(edge1, edge2));
    const typename M::Frame frame =
        M::microfacet_frame(anisotropic<Real>(), M::frame_from_normal(typename M::vec3(n)), typename M::vec3(edge1));
    const glm::dvec3 t = tangent_of<Real>(frame);
    auto uv_at = [&](const glm::dvec3& q) { return D::quad_uv(corner, edge1, edge2, q); };
    const D::TextureUV rate = uv_rate(uv_at, corner + edge1 * 0.3 + edge2 * 0.6, t, 1e-3);
    // a step along t changes u only where t is edge1's direction: dv/ds = 0 needs t in the plane and along edge1
    EXPECT_NEAR(rate.v, 0.0, kTangentTolerance<Real>);
    EXPECT_NEAR(rate.u * glm::length(edge1), 1.0, kTangentTolerance<Real>);
}

// A mesh triangle with vertex uvs (triangle_dp_du, triangle_uv): along the
// tangent the interpolated v is constant and u grows at 1 / |dp/du|; uvs
// given as they come from a file, sheared and mirrored.
TYPED_TEST(MicrofacetFrame, OnATriangleTheTangentFollowsItsUvGradient) {
    using Real = TypeParam;
    using M = wp::SharedMath<Real>;
    const glm::dvec3 p0(0.2, 0.1, -1), p1(1.7, 0.4, -0.6), p2(0.9, 1.8, -0.2);
    const double uvs[3][2] = {{0.1, 0.9}, {2.0, 0.6}, {-0.4, -0.3}};
    const glm::dvec3 n = glm::normalize(glm::cross(p1 - p0, p2 - p0));
    auto real3 = [](const glm::dvec3& v) { return typename M::vec3(v); };
    const typename M::vec3 dp_du =
        M::triangle_dp_du(real3(p0), real3(p1), real3(p2), Real(uvs[0][0]), Real(uvs[0][1]), Real(uvs[1][0]),
                          Real(uvs[1][1]), Real(uvs[2][0]), Real(uvs[2][1]));
    const typename M::Frame frame = M::microfacet_frame(anisotropic<Real>(), M::frame_from_normal(real3(n)), dp_du);
    const glm::dvec3 t = tangent_of<Real>(frame);
    auto uv_at = [&](const glm::dvec3& q) {
        const D::TriangleBarycentrics b = D::triangle_barycentrics(p0, p1, p2, q);
        return D::triangle_uv(D::make_texture_uv(uvs[0][0], uvs[0][1]), D::make_texture_uv(uvs[1][0], uvs[1][1]),
                              D::make_texture_uv(uvs[2][0], uvs[2][1]), b.b1, b.b2);
    };
    const D::TextureUV rate = uv_rate(uv_at, (p0 + p1 + p2) / 3.0, t, 1e-3);
    EXPECT_NEAR(rate.v, 0.0, 10 * kTangentTolerance<Real>);
    EXPECT_NEAR(rate.u * glm::length(glm::dvec3(dp_du)), 1.0, 10 * kTangentTolerance<Real>);
}

// With a shading normal that is not the surface's (vertex normals), the
// tangent is dp/du less its part along that normal (Gram-Schmidt), as
// Mitsuba's initialize_sh_frame: orthogonal to ns, in the plane of dp/du and
// ns, on dp/du's side; the bitangent completes a right-handed frame.
TYPED_TEST(MicrofacetFrame, TheTangentIsDpDuMadeOrthogonalToTheShadingNormal) {
    using Real = TypeParam;
    using M = wp::SharedMath<Real>;
    for (int i = 0; i < 64; ++i) {
        const glm::dvec3 ns = wp::test::spread_direction(i, 64),
                         dp_du = wp::test::spread_direction((i + 23) % 64, 64) * 2.5;
        if (std::fabs(glm::dot(ns, glm::normalize(dp_du))) > 0.99) continue;
        const typename M::Frame frame = M::microfacet_frame(
            anisotropic<Real>(), M::frame_from_normal(typename M::vec3(ns)), typename M::vec3(dp_du));
        const glm::dvec3 expected = glm::normalize(dp_du - ns * glm::dot(ns, dp_du));
        for (int k = 0; k < 3; ++k) {
            EXPECT_NEAR(double(frame.tangent[k]), expected[k], kTangentTolerance<Real>) << "case " << i;
            EXPECT_NEAR(double(frame.bitangent[k]), glm::cross(ns, expected)[k], kTangentTolerance<Real>);
        }
        EXPECT_EQ(frame.normal, typename M::vec3(ns));
    }
}

// An isotropic material (alpha_u == alpha_v) keeps the frame it builds from
// the normal alone, bit for bit (so scenes without anisotropy render as
// before); an anisotropic one on a plane (dp/du zero) keeps that frame's
// tangent.
TYPED_TEST(MicrofacetFrame, IsotropicMaterialsAndPlanesKeepTheNormalsFrame) {
    using Real = TypeParam;
    using M = wp::SharedMath<Real>;
    const typename M::Microfacet isotropic{WP_MICROFACET_BECKMANN, Real(0.2), Real(0.2)};
    for (int i = 0; i < 64; ++i) {
        const typename M::vec3 ns(wp::test::spread_direction(i, 64));
        const typename M::vec3 dp_du(wp::test::spread_direction((i + 9) % 64, 64));
        const typename M::Frame normal_frame = M::frame_from_normal(ns);
        const typename M::Frame kept = M::microfacet_frame(isotropic, normal_frame, dp_du);
        EXPECT_EQ(kept.tangent, normal_frame.tangent);
        EXPECT_EQ(kept.bitangent, normal_frame.bitangent);
        EXPECT_EQ(kept.normal, normal_frame.normal);
        const typename M::Frame plane = M::microfacet_frame(anisotropic<Real>(), normal_frame, typename M::vec3(0));
        EXPECT_EQ(plane.tangent, normal_frame.tangent) << "case " << i;
    }
}

// A rough dielectric seen from inside has its frame about -ns: its tangent
// lies along the same axis as the outside's, so that alpha_u has one
// direction on the surface for paths from either side.
TYPED_TEST(MicrofacetFrame, BothSidesOfADielectricSeeOneAxis) {
    using Real = TypeParam;
    using M = wp::SharedMath<Real>;
    for (int i = 0; i < 64; ++i) {
        const typename M::vec3 n(wp::test::spread_direction(i, 64)),
            dp_du(wp::test::spread_direction((i + 31) % 64, 64));
        if (std::fabs(double(glm::dot(n, dp_du))) > 0.99) continue;
        const typename M::Frame outside =
            M::microfacet_frame(anisotropic<Real>(), M::roughdielectric_frame(n, 1), dp_du);
        const typename M::Frame inside =
            M::microfacet_frame(anisotropic<Real>(), M::roughdielectric_frame(-n, 0), dp_du);
        EXPECT_NEAR(std::fabs(double(glm::dot(outside.tangent, inside.tangent))), 1.0, kTangentTolerance<Real>);
        EXPECT_EQ(inside.normal, -n);
    }
}

}  // namespace microfacet_frame_test
}  // namespace
