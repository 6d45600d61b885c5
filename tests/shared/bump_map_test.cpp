// The bumpmap adapter (kernels/shared/normal_map.h' bump_mapped) and the
// texture gradient it reads (kernels/shared/texture.h' texture_gradient):
// the gradient is the exact uv derivative of a bilinear bitmap's luminance
// through its to_uv (central differences of texture_value agree: along a
// line inside one cell the blend is a quadratic, whose central difference
// is exact but for rounding), zero with the nearest filter; a constant
// height leaves the shading normal exactly as it was, with no terminator
// term; a slope tilts the normal as the raised surface's cross product says;
// the nested diffuse's value times the terminator term is Mitsuba 3.9.1's
// bumpmap's; dp/du and dp/dv of spheres and triangles are the derivatives of
// their uv parameterisation.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <numbers>
#include <vector>

#include "core/shared_math.h"
#include "support/directions.h"
#include "support/real_types.h"

namespace {
namespace bump_map_test {

template <class Real>
class BumpMap : public ::testing::Test {};
TYPED_TEST_SUITE(BumpMap, wp::test::RealTypes, wp::test::RealTypeNames);

template <class Real>
using vec3 = typename wp::SharedMath<Real>::vec3;

constexpr std::uint32_t kWidth = 5, kHeight = 4;

// Fixed pseudo-random RGB texels, kWidth x kHeight.
template <class Real>
std::vector<Real> varied_texels() {
    std::vector<Real> texels;
    std::uint32_t state = 12345u;
    for (std::uint32_t i = 0; i < 3 * kWidth * kHeight; ++i) {
        state = state * 1664525u + 1013904223u;
        texels.push_back(Real((state >> 8) & 0xffffu) / Real(65535));
    }
    return texels;
}

// A bitmap with a to_uv that scales, shears and shifts (u' = 2 u + 0.5 v + 0.1, v' = -0.3 u + 3 v + 0.2).
template <class Real>
typename wp::SharedMath<Real>::Texture bitmap(std::uint32_t filter) {
    typename wp::SharedMath<Real>::Texture t{};
    t.type = WP_TEXTURE_BITMAP, t.filter = filter, t.wrap = WP_WRAP_REPEAT;
    t.width = kWidth, t.height = kHeight, t.first_texel = 0u;
    const Real to_uv[6] = {Real(2), Real(0.5), Real(0.1), Real(-0.3), Real(3), Real(0.2)};
    for (int k = 0; k < 6; ++k) t.to_uv[k] = to_uv[k];
    return t;
}

template <class Real>
Real luminance(const typename wp::SharedMath<Real>::Texture& t, const std::vector<Real>& texels, double u, double v) {
    return wp::SharedMath<Real>::texture_luminance(
        wp::SharedMath<Real>::texture_value(t, texels.data(), {Real(u), Real(v)}));
}

TYPED_TEST(BumpMap, TheGradientIsTheBilinearLuminancesDerivativeThroughToUv) {
    using Real = TypeParam;
    using M = wp::SharedMath<Real>;
    const std::vector<Real> texels = varied_texels<Real>();
    const typename M::Texture t = bitmap<Real>(WP_FILTER_BILINEAR);
    const double h = sizeof(Real) == 8 ? 1e-6 : 1e-3, tolerance = sizeof(Real) == 8 ? 1e-6 : 2e-2;
    int checked = 0;
    for (int i = 0; i < 200; ++i) {
        const double u = -0.7 + 0.0123 * i, v = 1.3 - 0.0071 * i;
        // skip points within reach of a cell's edge (x or y at a texel centre): the blend has a kink there
        const double x = (2 * u + 0.5 * v + 0.1) * kWidth - 0.5, y = (-0.3 * u + 3 * v + 0.2) * kHeight - 0.5;
        const double reach = 15 * h;  // |dx/du| = 2 kWidth, |dy/dv| = 3 kHeight: at most 12 h
        if (std::abs(x - std::round(x)) < reach || std::abs(y - std::round(y)) < reach) continue;
        const typename M::TextureUV g = M::texture_gradient(t, texels.data(), {Real(u), Real(v)});
        const double du = (luminance(t, texels, u + h, v) - luminance(t, texels, u - h, v)) / (2 * h);
        const double dv = (luminance(t, texels, u, v + h) - luminance(t, texels, u, v - h)) / (2 * h);
        EXPECT_NEAR(double(g.u), du, tolerance) << "u " << u << " v " << v;
        EXPECT_NEAR(double(g.v), dv, tolerance) << "u " << u << " v " << v;
        ++checked;
    }
    EXPECT_GT(checked, 100);
}

TYPED_TEST(BumpMap, TheNearestFilterHasNoGradient) {
    using Real = TypeParam;
    using M = wp::SharedMath<Real>;
    const std::vector<Real> texels = varied_texels<Real>();
    const typename M::TextureUV g =
        M::texture_gradient(bitmap<Real>(WP_FILTER_NEAREST), texels.data(), {Real(0.37), Real(0.61)});
    EXPECT_EQ(g.u, Real(0));
    EXPECT_EQ(g.v, Real(0));
}

TYPED_TEST(BumpMap, AConstantHeightLeavesTheShadingNormalExactly) {
    using Real = TypeParam;
    using M = wp::SharedMath<Real>;
    const std::vector<Real> texels(3 * kWidth * kHeight, Real(0.3));
    const typename M::Texture t = bitmap<Real>(WP_FILTER_BILINEAR);
    for (int i = 0; i < 64; ++i) {
        const vec3<Real> ns(wp::test::spread_direction(i, 64)), wo(wp::test::spread_direction(i + 5, 64));
        const vec3<Real> dp_du = vec3<Real>(wp::test::spread_direction(i + 17, 64)) * Real(3);
        const vec3<Real> dp_dv = vec3<Real>(wp::test::spread_direction(i + 40, 64)) * Real(0.5);
        const typename M::TextureUV g = M::texture_gradient(t, texels.data(), {Real(0.01 * i), Real(0.3 - 0.02 * i)});
        ASSERT_EQ(g.u, Real(0));
        ASSERT_EQ(g.v, Real(0));
        for (Real scale : {Real(1), Real(7)}) {
            const typename M::NormalMapped bumped =
                M::bump_mapped(ns, ns, ns, dp_du, dp_dv, scale * g.u, scale * g.v, wo);
            EXPECT_EQ(bumped.normal, ns) << "normal " << i;
            EXPECT_EQ(bumped.terminator_alpha2, Real(0));
            // a back face: the normal turned to wo's side, as given
            const typename M::NormalMapped back = M::bump_mapped(ns, ns, -ns, dp_du, dp_dv, Real(0), Real(0), wo);
            EXPECT_EQ(back.normal, -ns);
        }
    }
}

TYPED_TEST(BumpMap, ASlopeTiltsTheNormalAsTheRaisedSurfaceHas) {
    using Real = TypeParam;
    using M = wp::SharedMath<Real>;
    // a quad in the xy plane, edges (2, 0, 0) and (0, 3, 0), height slope 1 along u:
    // dp/du' = (2, 0, 1), dp/dv' = (0, 3, 0), normal (-3, 0, 6) / |.|, tan^2 theta = 1/4
    const vec3<Real> n(0, 0, 1), wo(0, 0, 1), du(2, 0, 0), dv(0, 3, 0);
    const typename M::NormalMapped bumped = M::bump_mapped(n, n, n, du, dv, Real(1), Real(0), wo);
    const vec3<Real> want = glm::normalize(vec3<Real>(-1, 0, 2));
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(double(bumped.normal[k]), double(want[k]), 1e-6);
    EXPECT_NEAR(double(bumped.terminator_alpha2), 0.25 / 8, 1e-6);
    // the same from the back (the normal mirrored through the surface), and a geometric normal the
    // cross product points away from (dp/du and dp/dv swapped) turns it back
    const typename M::NormalMapped back = M::bump_mapped(n, n, -n, du, dv, Real(1), Real(0), -wo);
    const vec3<Real> mirrored(want.x, want.y, -want.z);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(double(back.normal[k]), double(mirrored[k]), 1e-6);
    const typename M::NormalMapped swapped = M::bump_mapped(n, n, n, dv, du, Real(0), Real(1), wo);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(double(swapped.normal[k]), double(want[k]), 1e-6);
}

// Mitsuba 3.9.1 (scalar_rgb) printed these: its bumpmap (scale 0.3, a raw
// 5 x 4 random bitmap) over a diffuse of reflectance 0.5 on the rectangle
// [-1, 1]^2 (dp/du = (2, 0, 0), dp/dv = (0, 2, 0), normal +z), eval(wo) (f cos) at a
// hit reached from wi, with the gradient (times the scale) its eval_1_grad
// gave there. (Over 200 such random hits and directions, bump_mapped and
// the terminator term with Mitsuba's own gradient agree with its eval to
// 1e-6, relative.)
struct MitsubaBumpEval {
    double g_u, g_v, wi[3], wo[3], f;
};
const MitsubaBumpEval kMitsubaBumpEvals[] = {
    {0.11619072, 0.289537114, {0.944866, -0.154506, 0.288714}, {-0.990431, -0.003092, 0.137976}, 0.029694641},
    {0.305552208, 0.479412174, {-0.687456, 0.404051, 0.603446}, {-0.718866, -0.597866, 0.354665}, 0.0914707109},
    {0.241750002, 0.120715401, {-0.690313, -0.591926, 0.416043}, {0.906343, -0.017886, 0.422164}, 0.0493462384},
    {0.0596957758, -0.12920258, {0.394242, 0.841483, 0.369431}, {0.072723, 0.724601, 0.685321}, 0.115863077},
};

TYPED_TEST(BumpMap, TheNestedDiffuseTimesTheTerminatorTermIsMitsubas) {
    using Real = TypeParam;
    using M = wp::SharedMath<Real>;
    const vec3<Real> n(0, 0, 1), dp_du(2, 0, 0), dp_dv(0, 2, 0);
    for (const MitsubaBumpEval& e : kMitsubaBumpEvals) {
        const vec3<Real> wi(Real(e.wi[0]), Real(e.wi[1]), Real(e.wi[2])),
            wo(Real(e.wo[0]), Real(e.wo[1]), Real(e.wo[2]));
        const typename M::NormalMapped bumped = M::bump_mapped(n, n, n, dp_du, dp_dv, Real(e.g_u), Real(e.g_v), wi);
        ASSERT_TRUE(M::normal_map_shades(wi, bumped.normal));
        const double f_cos = double(M::diffuse_eval(vec3<Real>(Real(0.5)), bumped.normal, wo).x) *
                             double(glm::dot(wo, bumped.normal)) *
                             double(M::normal_map_terminator(bumped.terminator_alpha2, n, wo));
        EXPECT_NEAR(f_cos, e.f, 1e-5 * e.f + 1e-7) << "g " << e.g_u << " " << e.g_v;
    }
}

TYPED_TEST(BumpMap, SphereAndTriangleTangentsAreTheirParameterisationsDerivatives) {
    using Real = TypeParam;
    using M = wp::SharedMath<Real>;
    const double pi = std::numbers::pi, r = 1.7, tolerance = sizeof(Real) == 8 ? 1e-9 : 1e-4;
    for (int i = 0; i < 20; ++i) {
        const double u = 0.05 + 0.045 * i, v = 0.03 + 0.047 * i;  // Mitsuba's: u = phi / 2 pi, v = theta / pi
        const double phi = 2 * pi * u, theta = pi * v;
        const vec3<Real> normal(Real(std::sin(theta) * std::cos(phi)), Real(std::sin(theta) * std::sin(phi)),
                                Real(std::cos(theta)));
        const typename M::SurfaceTangents t = M::sphere_tangents(normal, Real(r));
        const double dp_du[3] = {-2 * pi * r * std::sin(theta) * std::sin(phi),
                                 2 * pi * r * std::sin(theta) * std::cos(phi), 0};
        const double dp_dv[3] = {pi * r * std::cos(theta) * std::cos(phi), pi * r * std::cos(theta) * std::sin(phi),
                                 -pi * r * std::sin(theta)};
        for (int k = 0; k < 3; ++k) {
            EXPECT_NEAR(double(t.dp_du[k]), dp_du[k], tolerance * 10) << i;
            EXPECT_NEAR(double(t.dp_dv[k]), dp_dv[k], tolerance * 10) << i;
        }
    }
    // a triangle: its edges are dp/du du + dp/dv dv over their uv differences
    const vec3<Real> p0(1, 2, 3), p1(Real(2.5), 2, Real(3.5)), p2(1, 4, Real(2.5));
    const Real u0 = Real(0.1), v0 = Real(0.2), u1 = Real(0.7), v1 = Real(0.3), u2 = Real(0.2), v2 = Real(0.9);
    const vec3<Real> du = M::triangle_dp_du(p0, p1, p2, u0, v0, u1, v1, u2, v2);
    const vec3<Real> dv = M::triangle_dp_dv(p0, p1, p2, u0, v0, u1, v1, u2, v2);
    const vec3<Real> e1 = du * (u1 - u0) + dv * (v1 - v0), e2 = du * (u2 - u0) + dv * (v2 - v0);
    for (int k = 0; k < 3; ++k) {
        EXPECT_NEAR(double(e1[k]), double((p1 - p0)[k]), tolerance);
        EXPECT_NEAR(double(e2[k]), double((p2 - p0)[k]), tolerance);
    }
}

}  // namespace bump_map_test
}  // namespace
