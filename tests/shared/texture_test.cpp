// Textures and uvs (kernels/shared/texture.h) against values computed by
// hand and printed by Mitsuba 3.9.1 (scalar_rgb) for the same inputs: its
// bitmap plugin with data=TensorXf of the 3 x 2 image below, raw, each
// filter_type and wrap_mode, eval at the uvs below; its checkerboard; and
// si.uv of rays hitting a unit sphere.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <vector>

#include "core/shared_math.h"
#include "support/real_types.h"

namespace {
namespace texture_test {

template <class Real>
class Textures : public ::testing::Test {};
TYPED_TEST_SUITE(Textures, wp::test::RealTypes, wp::test::RealTypeNames);

// Texel (x, y) of the 3 x 2 image holds 10 x + y in red: every texel differs,
// so each value below names the texels and weights it came from.
template <class Real>
std::vector<Real> coded_texels() {
    std::vector<Real> texels;
    for (int y = 0; y < 2; ++y)
        for (int x = 0; x < 3; ++x) texels.insert(texels.end(), {Real(10 * x + y), Real(0), Real(0)});
    return texels;
}

template <class Real>
typename wp::SharedMath<Real>::Texture bitmap(std::uint32_t filter, std::uint32_t wrap) {
    typename wp::SharedMath<Real>::Texture t{};
    t.type = WP_TEXTURE_BITMAP, t.filter = filter, t.wrap = wrap;
    t.width = 3u, t.height = 2u, t.first_texel = 0u;
    t.to_uv[0] = t.to_uv[4] = Real(1);  // the identity
    return t;
}

struct Case {
    double u, v;
};
const Case kCases[] = {{0.1, 0.1},  {0.1, 0.9}, {0.5, 0.5}, {1.0 / 6.0, 0.25}, {0.2, 0.3},
                       {-0.1, 0.1}, {1.1, 0.1}, {1.4, 1.6}, {-0.4, -0.3},      {0.99, 0.1}};

// Mitsuba's values at kCases, per filter and wrap mode. By hand, e.g.
// bilinear repeat at (0.1, 0.1): x = 0.1 * 3 - 0.5 = -0.2 between texels -1
// (repeat: 2) and 0 with weight 0.8 on 0; y = -0.3 between -1 (1) and 0
// with 0.7 on 0: 0.2 0.3 21 + 0.8 0.3 1 + 0.2 0.7 20 + 0.8 0.7 0 = 4.3.
struct Expected {
    std::uint32_t filter, wrap;
    double values[10];
};
const Expected kExpected[] = {
    {WP_FILTER_NEAREST, WP_WRAP_REPEAT, {0, 1, 11, 0, 0, 20, 0, 11, 11, 20}},
    {WP_FILTER_NEAREST, WP_WRAP_MIRROR, {0, 1, 11, 0, 0, 0, 20, 10, 10, 20}},
    {WP_FILTER_NEAREST, WP_WRAP_CLAMP, {0, 1, 11, 0, 0, 0, 20, 21, 0, 20}},
    {WP_FILTER_BILINEAR, WP_WRAP_REPEAT, {4.3, 4.7, 10.5, 0, 1.1, 16.3, 4.3, 7.7, 13.9, 10.9}},
    {WP_FILTER_BILINEAR, WP_WRAP_MIRROR, {0, 1, 10.5, 0, 1.1, 0, 20, 13.3, 7.1, 20}},
    {WP_FILTER_BILINEAR, WP_WRAP_CLAMP, {0, 1, 10.5, 0, 1.1, 0, 20, 21, 0, 20}},
};

TYPED_TEST(Textures, BitmapFiltersAndWrapsAsMitsuba) {
    using R = TypeParam;
    using M = wp::SharedMath<R>;
    const std::vector<R> texels = coded_texels<R>();
    for (const Expected& e : kExpected) {
        for (int i = 0; i < 10; ++i) {
            const typename M::TextureUV uv{R(kCases[i].u), R(kCases[i].v)};
            const auto value = M::texture_value(bitmap<R>(e.filter, e.wrap), texels.data(), uv);
            // Mitsuba printed 4 digits; the values are exact to rounding
            EXPECT_NEAR(value.x, e.values[i], 5e-5 * 21)
                << "filter " << e.filter << " wrap " << e.wrap << " uv " << kCases[i].u << ", " << kCases[i].v;
            EXPECT_EQ(value.y, R(0));
        }
    }
}

TYPED_TEST(Textures, MirrorReflectsAtEachEdgeAndRepeatsEveryTwoWidths) {
    using M = wp::SharedMath<TypeParam>;
    const int expected[] = {2, 1, 0, 0, 1, 2, 2, 1, 0, 0, 1, 2, 2};  // x = -3 .. 9 over 3 texels
    for (int x = -3; x <= 9; ++x) EXPECT_EQ(M::wrap_texel(x, 3, WP_WRAP_MIRROR), expected[x + 3]) << x;
    EXPECT_EQ(M::wrap_texel(-1, 3, WP_WRAP_REPEAT), 2);
    EXPECT_EQ(M::wrap_texel(-4, 3, WP_WRAP_REPEAT), 2);
    EXPECT_EQ(M::wrap_texel(-4, 3, WP_WRAP_CLAMP), 0);
    EXPECT_EQ(M::wrap_texel(7, 3, WP_WRAP_CLAMP), 2);
}

// floor_mod divides in real where that is exact and in integers beyond
// 2^24; either way it must be the true remainder: next to every multiple of
// the size (where a rounded quotient is one too many), at the 2^24 edge and
// across the whole range floor_to_int returns.
TYPED_TEST(Textures, FloorModIsTheExactRemainderEverywhere) {
    using M = wp::SharedMath<TypeParam>;
    const auto expected = [](long long x, long long size) { return int(((x % size) + size) % size); };
    std::vector<long long> xs = {
        0,         1,         -1, (1 << 24) - 1, 1 << 24, (1 << 24) + 1, -(1 << 24) + 1, -(1 << 24), -(1 << 24) - 1,
        (1 << 30), -(1 << 30)};
    unsigned long long state = 12345;  // a fixed LCG (Knuth's MMIX constants) spreads x over +-2^30
    for (int i = 0; i < 4000; ++i) {
        state = state * 6364136223846793005ull + 1442695040888963407ull;
        xs.push_back(static_cast<long long>(state >> 33) % (1ll << 31) - (1ll << 30));
    }
    for (int size : {1, 2, 3, 7, 255, 256, 1000, 4097, 16384}) {
        std::vector<long long> near = xs;
        for (long long k : {1ll, 3ll, 1000ll, 4000000ll, 16000000ll, 100000000ll})
            for (long long d : {-1ll, 0ll, 1ll})
                for (long long sign : {-1ll, 1ll})
                    if (std::llabs(k * size) <= (1ll << 30)) near.push_back(sign * k * size + d);
        for (long long x : near)
            ASSERT_EQ(M::floor_mod(int(x), size), expected(x, size)) << "x " << x << " size " << size;
    }
}

TYPED_TEST(Textures, HugeAndNonFiniteUvsStayInsideTheImage) {
    using R = TypeParam;
    using M = wp::SharedMath<R>;
    const std::vector<R> texels = coded_texels<R>();
    const R huge[] = {R(1e30), R(-1e30), R(NAN), R(INFINITY)};
    for (std::uint32_t wrap : {WP_WRAP_REPEAT, WP_WRAP_MIRROR, WP_WRAP_CLAMP})
        for (R u : huge) {
            const auto value = M::texture_value(bitmap<R>(WP_FILTER_NEAREST, wrap), texels.data(), {u, R(0.1)});
            EXPECT_TRUE(value.x >= 0 && value.x <= 21) << "wrap " << wrap << " u " << u;
        }
}

TYPED_TEST(Textures, CheckerboardAsMitsubaWithToUv) {
    using R = TypeParam;
    using M = wp::SharedMath<R>;
    typename M::Texture t = bitmap<R>(WP_FILTER_BILINEAR, WP_WRAP_REPEAT);
    t.type = WP_TEXTURE_CHECKERBOARD;
    t.width = t.height = 1u;  // as the host lays a checkerboard out: the bitmap lookup beside it reads one texel
    t.color0 = {R(1), R(1), R(1)};
    t.color1 = {R(0), R(0), R(0)};
    const R texel[3] = {0, 0, 0};
    // Mitsuba: color0 where frac(u) > 1/2 and frac(v) > 1/2 agree (1/2 itself is low)
    const Case cases[] = {{0.1, 0.1}, {0.6, 0.1}, {0.1, 0.6}, {0.6, 0.6}, {1.1, 0.1}, {-0.1, 0.1}, {0.5, 0.1}};
    const double expected[] = {1, 0, 0, 1, 1, 0, 1};
    for (int i = 0; i < 7; ++i)
        EXPECT_EQ(M::texture_value(t, texel, {R(cases[i].u), R(cases[i].v)}).x, R(expected[i])) << i;
    // to_uv doubles u: 0.3 becomes 0.6
    t.to_uv[0] = R(2);
    EXPECT_EQ(M::texture_value(t, texel, {R(0.3), R(0.1)}).x, R(0));
    t.to_uv[2] = R(0.5);  // and shifts it by 1/2: 1.1
    EXPECT_EQ(M::texture_value(t, texel, {R(0.3), R(0.1)}).x, R(1));
}

// A material's colour parameter: the constant where the material names no
// texture for it, else the texture's value at the hit (whatever the constant).
TYPED_TEST(Textures, ColourParameterIsTheConstantOrTheTexturesValueAtTheUv) {
    using R = TypeParam;
    using M = wp::SharedMath<R>;
    const typename M::Texture t = bitmap<R>(WP_FILTER_NEAREST, WP_WRAP_REPEAT);
    const std::vector<R> texels = coded_texels<R>();
    const typename M::vec3 constant(R(0.25), R(0.5), R(0.75));
    const typename M::TextureUV uv{R(0.5), R(0.75)};  // texel (1, 1): red 11
    const typename M::vec3 untextured = M::colour_parameter(constant, WP_NO_TEXTURE, t, texels.data(), uv);
    EXPECT_EQ(untextured.x, R(0.25));
    EXPECT_EQ(untextured.y, R(0.5));
    EXPECT_EQ(untextured.z, R(0.75));
    for (std::uint32_t index : {0u, 3u}) {  // any texture index: the caller passes its entry as t
        const typename M::vec3 textured = M::colour_parameter(constant, index, t, texels.data(), uv);
        EXPECT_EQ(textured.x, R(11)) << index;
        EXPECT_EQ(textured.y, R(0)) << index;
        EXPECT_EQ(textured.z, R(0)) << index;
    }
}

// A scalar parameter (a roughness): the constant without a texture, else the
// texture read as Mitsuba 3.9.1's eval_1 reads it: a bitmap's luminance
// (0.212671 R + 0.715160 G + 0.072169 B, the values it printed for red and blue
// texels), a checkerboard's channel mean (it printed 1/3 for rgb (1, 0, 0)).
TYPED_TEST(Textures, ScalarParameterIsALuminanceOfABitmapAndAChannelMeanOfACheckerboard) {
    using R = TypeParam;
    using M = wp::SharedMath<R>;
    typename M::Texture t = bitmap<R>(WP_FILTER_NEAREST, WP_WRAP_REPEAT);
    std::vector<R> texels = coded_texels<R>();
    texels[3 * 4 + 1] = R(0.5), texels[3 * 4 + 2] = R(0.25);  // texel (1, 1): (11, 0.5, 0.25)
    const typename M::TextureUV uv{R(0.5), R(0.75)};
    EXPECT_EQ(M::scalar_parameter(R(0.3), WP_NO_TEXTURE, t, texels.data(), uv), R(0.3));
    EXPECT_NEAR(M::scalar_parameter(R(0.3), 0u, t, texels.data(), uv), 0.212671 * 11 + 0.715160 * 0.5 + 0.072169 * 0.25,
                1e-5);
    t.type = WP_TEXTURE_CHECKERBOARD;
    t.color0 = {R(0.3), R(0.6), R(0.9)};  // at (0.1, 0.1); color1 at (0.1, 0.6)
    t.color1 = {R(0), R(0), R(0.3)};
    EXPECT_NEAR(M::scalar_parameter(R(0.3), 0u, t, texels.data(), {R(0.1), R(0.1)}), 0.6, 1e-6);
    EXPECT_NEAR(M::scalar_parameter(R(0.3), 0u, t, texels.data(), {R(0.1), R(0.6)}), 0.1, 1e-6);
}

TYPED_TEST(Textures, SphereUvAsMitsuba) {
    using R = TypeParam;
    using M = wp::SharedMath<R>;
    const R s = R(1.0 / std::sqrt(3.0));
    struct SphereCase {
        typename M::vec3 normal;
        double u, v;
    };
    const SphereCase cases[] = {{{1, 0, 0}, 0, 0.5},         {{0, 1, 0}, 0.25, 0.5}, {{-1, 0, 0}, 0.5, 0.5},
                                {{0, -1, 0}, 0.75, 0.5},     {{0, 0, 1}, 0, 0},      {{0, 0, -1}, 0, 1},
                                {{s, s, s}, 0.125, 0.304087}};
    for (const SphereCase& c : cases) {
        const typename M::TextureUV uv = M::sphere_uv(c.normal);
        EXPECT_NEAR(uv.u, c.u, 2e-6) << c.normal.x << " " << c.normal.y << " " << c.normal.z;
        EXPECT_NEAR(uv.v, c.v, 2e-6) << c.normal.x << " " << c.normal.y << " " << c.normal.z;
    }
}

TYPED_TEST(Textures, QuadUvIsTheEdgesCoordinatesOfASheardQuad) {
    using R = TypeParam;
    using M = wp::SharedMath<R>;
    const typename M::vec3 corner{1, 2, 3}, edge1{2, 0, 0}, edge2{1, 0, 3};  // sheared
    const typename M::vec3 p = corner + R(0.25) * edge1 + R(0.75) * edge2;
    const typename M::TextureUV uv = M::quad_uv(corner, edge1, edge2, p);
    EXPECT_NEAR(uv.u, 0.25, wp::test::kRoundingTolerance<R>);
    EXPECT_NEAR(uv.v, 0.75, wp::test::kRoundingTolerance<R>);
}

TYPED_TEST(Textures, TriangleUvInterpolatesTheVertices) {
    using R = TypeParam;
    using M = wp::SharedMath<R>;
    const typename M::TextureUV uv =
        M::triangle_uv({R(0.5), R(0)}, {R(1), R(1)}, {R(0), R(0.5)}, R(0.25), R(0.5));  // b0 = 0.25
    EXPECT_NEAR(uv.u, 0.125 + 0.25, wp::test::kRoundingTolerance<R>);
    EXPECT_NEAR(uv.v, 0.25 + 0.25, wp::test::kRoundingTolerance<R>);
}

}  // namespace texture_test
}  // namespace
