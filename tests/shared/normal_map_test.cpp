// The normalmap adapter's frame (kernels/shared/normal_map.h): a flat map
// leaves the shading normal, and so the nested BSDF, exactly as it was; a
// texel's colour c is the normal 2 c - 1 in the frame (dp/du made orthogonal
// to ns, ns x that, ns), flipped as Mitsuba 3.9's where the arrival lies
// below it, with Mitsuba's terminator term (values printed by Mitsuba 3.9.1,
// scalar_rgb: its normalmap over a white diffuse, eval at the directions
// below); dp/du of triangles and spheres as Mitsuba's; and whatever normal a
// map gives, no direction the BSDFs sample or the light samples carry leaves
// below the geometric surface (no light leaks).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <numbers>

#include "core/shared_math.h"
#include "support/directions.h"
#include "support/real_types.h"

namespace {
namespace normal_map_test {

template <class Real>
class NormalMap : public ::testing::Test {};
TYPED_TEST_SUITE(NormalMap, wp::test::RealTypes, wp::test::RealTypeNames);

template <class Real>
using vec3 = typename wp::SharedMath<Real>::vec3;

template <class Real>
vec3<Real> spread(int i, int count) {
    return vec3<Real>(wp::test::spread_direction(i, count));
}

template <class Real>
void expect_near(const vec3<Real>& got, const vec3<Real>& want, double tolerance) {
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(double(got[k]), double(want[k]), tolerance) << "component " << k;
}

template <class Real>
vec3<Real> mapped_normal(const vec3<Real>& ns, const vec3<Real>& dp_du, const vec3<Real>& colour,
                         const vec3<Real>& wo) {
    return wp::SharedMath<Real>::normal_mapped(ns, ns, dp_du, colour, wo).normal;
}

TYPED_TEST(NormalMap, AFlatTexelGivesTheShadingNormalAndTheNestedBsdfExactly) {
    using Real = TypeParam;
    using M = wp::SharedMath<Real>;
    typename M::Microfacet rough{WP_MICROFACET_GGX, Real(0.3), Real(0.3)};
    const vec3<Real> flat(Real(0.5), Real(0.5), Real(1));
    for (int i = 0; i < 64; ++i) {
        const vec3<Real> ns = spread<Real>(i, 64), dp_du = spread<Real>(i + 17, 64) * Real(3);
        const vec3<Real> wo = spread<Real>(i + 5, 64), wi = spread<Real>(i + 33, 64);
        const typename M::NormalMapped mapped = M::normal_mapped(ns, ns, dp_du, flat, wo);
        ASSERT_EQ(mapped.normal, ns) << "normal " << i;
        EXPECT_EQ(M::normal_map_terminator(mapped.terminator_alpha2, ns, wi), Real(1));
        const vec3<Real> eta(Real(0.2)), k(Real(3));
        EXPECT_EQ(M::roughconductor_eval(rough, eta, k, vec3<Real>(1), M::frame_from_normal(mapped.normal), wo, wi),
                  M::roughconductor_eval(rough, eta, k, vec3<Real>(1), M::frame_from_normal(ns), wo, wi));
    }
}

TYPED_TEST(NormalMap, AColourIsTheNormalTwiceItMinusOneInTheTangentFrame) {
    using Real = TypeParam;
    using M = wp::SharedMath<Real>;
    const vec3<Real> ns(0, 0, 1), dp_du(2, 0, Real(0.5));  // s = +x after Gram-Schmidt, t = ns x s = +y
    const vec3<Real> up(0, 0, 1);                          // the arrival: above every normal below
    expect_near<Real>(mapped_normal<Real>(ns, dp_du, vec3<Real>(1, Real(0.5), Real(0.75)), up),
                      glm::normalize(vec3<Real>(1, 0, Real(0.5))), 1e-6);
    expect_near<Real>(mapped_normal<Real>(ns, dp_du, vec3<Real>(Real(0.5), 1, Real(0.75)), up),
                      glm::normalize(vec3<Real>(0, 1, Real(0.5))), 1e-6);
    const vec3<Real> tilted = mapped_normal<Real>(ns, dp_du, vec3<Real>(Real(0.75), Real(0.25), 1), up);
    expect_near<Real>(tilted, vec3<Real>(Real(0.5), Real(-0.5), 1) / std::sqrt(Real(1.5)), 1e-6);
    // a tilted shading normal and tangent: the same colour turns with the frame
    const vec3<Real> n2 = glm::normalize(vec3<Real>(0, 1, 1)), along(1, 0, 0);
    expect_near<Real>(mapped_normal<Real>(n2, along, vec3<Real>(Real(0.5), 1, Real(0.75)), n2),
                      glm::normalize(glm::cross(n2, along) + n2 * Real(0.5)), 1e-6);
    // a degenerate colour (2 c - 1 = 0) keeps the normal
    EXPECT_EQ(mapped_normal<Real>(ns, dp_du, vec3<Real>(Real(0.5)), up), ns);
    // an arrival below the perturbed normal flips its tangential part (Mitsuba's flip_invalid_normals)
    const vec3<Real> grazing = glm::normalize(vec3<Real>(-1, 0, Real(0.2)));
    expect_near<Real>(mapped_normal<Real>(ns, dp_du, vec3<Real>(1, Real(0.5), Real(0.75)), grazing),
                      glm::normalize(vec3<Real>(-1, 0, Real(0.5))), 1e-6);
    // on the back (side = -ns) the frame is the front's mirrored: z negated, s and t kept
    expect_near<Real>(M::normal_mapped(ns, -ns, dp_du, vec3<Real>(Real(0.75), Real(0.25), 1), -up).normal,
                      vec3<Real>(Real(0.5), Real(-0.5), -1) / std::sqrt(Real(1.5)), 1e-6);
}

// Mitsuba 3.9.1 (scalar_rgb) printed f cos of its normalmap (a raw bitmap of
// colour (0.75, 0.5, 0.9)) around a white diffuse, at wi = +z, for these wo:
// the cosine about the perturbed normal times the terminator term.
TYPED_TEST(NormalMap, TheNestedBsdfTimesTheTerminatorTermIsMitsubas) {
    using Real = TypeParam;
    using M = wp::SharedMath<Real>;
    const vec3<Real> ns(0, 0, 1), up(0, 0, 1);
    const typename M::NormalMapped m =
        M::normal_mapped(ns, ns, vec3<Real>(1, 0, 0), vec3<Real>(Real(0.75), Real(0.5), Real(0.9)), up);
    struct {
        vec3<Real> wo;
        double mitsuba;
    } cases[] = {{{0, 0, 1}, 0.8479982303243637},
                 {{1, 0, 1}, 0.9627784551300153},
                 {{-1, 0, 1}, 0.2221795948776489},
                 {{0, 1, 1}, 0.5924790133004875}};
    for (const auto& c : cases) {
        const vec3<Real> wo = glm::normalize(c.wo);
        const double f_cos = double(M::diffuse_eval(vec3<Real>(1), m.normal, wo).x) * std::numbers::pi *
                             double(glm::dot(wo, m.normal)) *
                             double(M::normal_map_terminator(m.terminator_alpha2, ns, wo));
        EXPECT_NEAR(f_cos, c.mitsuba, 2e-6) << "wo " << c.wo.x << " " << c.wo.y << " " << c.wo.z;
    }
}

TYPED_TEST(NormalMap, TangentsAreMitsubasDpDu) {
    using Real = TypeParam;
    using M = wp::SharedMath<Real>;
    // p = origin + u a + v b at the vertices' uvs: dp/du is a
    const vec3<Real> origin(1, 2, 3), a(2, 0, 1), b(0, 3, 0);
    auto at = [&](Real u, Real v) { return origin + a * u + b * v; };
    expect_near<Real>(M::triangle_dp_du(at(Real(0.1), Real(0.2)), at(Real(0.9), Real(0.3)), at(Real(0.4), Real(0.8)),
                                        Real(0.1), Real(0.2), Real(0.9), Real(0.3), Real(0.4), Real(0.8)),
                      a, 1e-5);
    // uvs along a line: no dp/du (the frame then takes frame_from_normal's tangent)
    EXPECT_EQ(M::triangle_dp_du(at(0, 0), at(1, 0), at(0, 1), 0, 0, 1, 1, 2, 2), vec3<Real>(0));
    // the sphere's u is the azimuth about +z: dp/du is along (-y, x, 0)
    expect_near<Real>(M::sphere_dp_du(vec3<Real>(1, 0, 0)), vec3<Real>(0, 1, 0), 0);
}

// Whatever normal the map gives (colours over the whole cube, tilted below
// the surface too), a sample that the BSDFs call valid and a light sample
// that next-event estimation says carries light never go below the
// geometric surface, with the two normals' rule on (as the kernels compile
// it with WP_HAS_NORMAL_MAP); an arrival below the perturbed normal (after
// the flip: where the map points into the surface) is not scattered
// (normal_map_shades).
TYPED_TEST(NormalMap, NoDirectionBelowTheGeometricSurfaceIsEverReflected) {
    using Real = TypeParam;
    using M = wp::SharedMath<Real>;
    const vec3<Real> nf(0, 0, 1), dp_du(1, 0, 0);
    typename M::Microfacet rough{WP_MICROFACET_GGX, Real(0.4), Real(0.4)};
    int valid = 0, below_perturbed = 0;
    for (int c = 0; c < 125; ++c) {
        const vec3<Real> colour(Real(c % 5) / 4, Real(c / 5 % 5) / 4, Real(c / 25) / 4);
        for (int i = 0; i < 32; ++i) {
            vec3<Real> wo = spread<Real>(i, 64);  // the upper hemisphere of nf
            const vec3<Real> ns = mapped_normal<Real>(nf, dp_du, colour, wo);
            below_perturbed += !M::normal_map_shades(wo, ns);
            for (int j = 0; j < 16; ++j) {
                const Real u = (Real(j) + Real(0.5)) / 16, v = Real((j * 7 + i) % 16 + 0.5) / 16;
                const typename M::BsdfSample d = M::diffuse_sample(vec3<Real>(1), nf, ns, u, v, 0, 1);
                const typename M::BsdfSample r = M::roughconductor_sample(
                    rough, vec3<Real>(0), vec3<Real>(1), vec3<Real>(1), nf, M::frame_from_normal(ns), wo, u, v, 1);
                for (const auto& s : {d, r}) {
                    valid += s.valid;
                    if (s.valid) {
                        ASSERT_GT(glm::dot(s.direction, nf), Real(0)) << "colour " << c << " wo " << i;
                    }
                }
                const vec3<Real> wi = spread<Real>(j * 2, 64) * Real(-1);  // below nf
                EXPECT_FALSE(M::light_sample_carries(Real(1), wi, nf, ns, 0, 1, 1));
            }
        }
    }
    EXPECT_GT(valid, 125 * 32 * 16 / 2);  // of 2 x 125 x 32 x 16 samples: the rule is not vacuous
    EXPECT_GT(below_perturbed, 0);        // some arrivals lie below a tilted normal
}

}  // namespace normal_map_test
}  // namespace
