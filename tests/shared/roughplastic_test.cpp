// The rough plastic (kernels/shared/materials/roughplastic.h), float and
// double: its sampling against its pdf (a chi-square test over the sphere),
// each sample against eval and pdf, reciprocity, the albedo of white rough
// plastics, the host's precomputation (the quadrature of the coat's
// transmittance and internal reflectance), and agreement with Mitsuba 3's own
// eval, pdf and precomputed constants (support/plastic_mitsuba_table.h,
// written by scripts/plastic_reference.py).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <optional>
#include <string>
#include <tuple>
#include <vector>

#include "core/shared_math.h"
#include "support/microfacet_reference.h"
#include "support/plastic_mitsuba_table.h"
#include "support/real_types.h"
#include "support/sphere_chi_square.h"
#include "support/statistics.h"

namespace {
// A namespace of its own: the sanitizer build compiles test files together (unity).
namespace roughplastic_test {

using wp::test::MicrofacetParameters;
using wp::test::Vec3;
namespace table = wp::test::plastic_mitsuba;

template <class Real>
class RoughPlastic : public ::testing::Test {};
TYPED_TEST_SUITE(RoughPlastic, wp::test::RealTypes, wp::test::RealTypeNames);

// A shading normal that is no axis, and directions about it.
const glm::dvec3 kNormal = glm::normalize(glm::dvec3(0.3, -0.5, 0.8));
const wp::test::SphereCells kFrame(kNormal, 1, 1);
glm::dvec3 around_normal(double cos_theta, double phi) { return kFrame.direction(cos_theta, phi); }
const double kAzimuth = 0.7;

// A rough plastic's parameters and its table of t, computed once in double
// as the host computes them (roughplastic_params, rough_interface_transmittance)
// and rounded to the precision under test; the table starts at offset 0.
struct RoughMaterial {
    std::string name;
    MicrofacetParameters m;
    glm::dvec3 diffuse, specular;
    double eta;
    bool nonlinear;
};

struct RoughHost {
    wp::SharedMath<double>::RoughPlasticParams params;
    std::vector<double> table;
};

// The host's precomputation (R_int: 64 x 128^2 visible normals), once per
// distribution, alpha and eta for the whole test program.
const RoughHost& rough_host(const RoughMaterial& r) {
    using D = wp::SharedMath<double>;
    static std::map<std::tuple<bool, double, double>, RoughHost> cache;
    const auto key = std::make_tuple(r.m.beckmann, r.m.alpha_u, r.eta);
    auto found = cache.find(key);
    if (found == cache.end()) {
        RoughHost host;
        const D::Microfacet m = wp::test::shared_microfacet<double>(r.m);
        host.params = D::roughplastic_params(m, D::vec3(0.5), D::vec3(1.0), r.eta, 0, 0u);
        for (int k = 0; k < WP_ROUGHPLASTIC_TABLE_SIZE; ++k)
            host.table.push_back(D::rough_interface_transmittance(m, r.eta, D::roughplastic_table_cosine(k)));
        found = cache.emplace(key, host).first;
    }
    return found->second;
}

// The material in the precision under test, with `table` filled.
template <class Real>
typename wp::SharedMath<Real>::RoughPlasticParams shared_rough(const RoughMaterial& r, std::vector<Real>* table) {
    using M = wp::SharedMath<Real>;
    const RoughHost& host = rough_host(r);
    typename M::RoughPlasticParams p;
    p.m = wp::test::shared_microfacet<Real>(r.m);
    p.diffuse_reflectance = Vec3<Real>(r.diffuse);
    p.specular_reflectance = Vec3<Real>(r.specular);
    p.eta = Real(r.eta);
    p.inv_eta_2 = Real(host.params.inv_eta_2);
    p.specular_sampling_weight = M::plastic_specular_sampling_weight(M::plastic_channel_mean(p.diffuse_reflectance),
                                                                     M::plastic_channel_mean(p.specular_reflectance));
    p.internal_reflectance = Real(host.params.internal_reflectance);
    p.nonlinear = r.nonlinear;
    p.transmittance_offset = 0u;
    table->assign(host.table.begin(), host.table.end());
    return p;
}

std::string describe(const RoughMaterial& r) {
    return r.name + " " + wp::test::describe(r.m) + (r.nonlinear ? " nonlinear" : "");
}

// Both distributions at alpha 0.05, 0.3 and 1, grey and coloured (the latter
// nonlinear), at the default index.
std::vector<RoughMaterial> rough_plastics() {
    std::vector<RoughMaterial> all;
    for (bool beckmann : {true, false}) {
        for (double alpha : {0.05, 0.3, 1.0}) {
            const bool coloured = alpha == 0.3;
            all.push_back({coloured ? "coloured" : "grey",
                           {beckmann, alpha, alpha},
                           coloured ? glm::dvec3(0.8, 0.3, 0.1) : glm::dvec3(0.5),
                           coloured ? glm::dvec3(0.9, 0.7, 0.5) : glm::dvec3(1.0),
                           1.49 / 1.000277,
                           coloured});
        }
    }
    return all;
}

// The samples follow roughplastic_pdf (support/sphere_chi_square.h: 32 x 64
// cells over the sphere, 1e5 samples). 18 cases (2 distributions x alpha
// 0.05, 0.3, 1 x cos theta 0.9, 0.5, 0.1), each at level
// 1 - (1 - 1e-3)^(1/18) = 5.6e-5 (Sidak): a correct sampler fails this test
// (of one precision) with probability 1e-3; the seeds are fixed. (nonlinear
// changes weights only, not where samples go.)
TYPED_TEST(RoughPlastic, SamplesFollowTheirPdf) {
    using R = TypeParam;
    using M = wp::SharedMath<R>;
    const std::vector<RoughMaterial> materials = rough_plastics();
    const double cosines[] = {0.9, 0.5, 0.1};
    const int cases = static_cast<int>(materials.size() * std::size(cosines));
    const double level = 1.0 - std::pow(1.0 - wp::test::kChiSquareAlpha, 1.0 / cases);
    std::uint64_t seed = 400;
    for (const RoughMaterial& material : materials) {
        std::vector<R> table;
        const auto p = shared_rough<R>(material, &table);
        for (double cos_theta : cosines) {
            const Vec3<R> wo(around_normal(cos_theta, kAzimuth)), ns(kNormal);
            wp::test::UnitRandom<R> random(seed++);
            auto sample = [&]() -> std::optional<glm::dvec3> {
                typename M::BsdfRandom r;
                r.lobe = random(), r.u = random(), r.v = random();
                auto s = M::roughplastic_sample(p, table.data(), ns, ns, wo, r, 0);
                if (!s.valid) return std::nullopt;
                return glm::dvec3(s.direction);
            };
            auto pdf = [&](const glm::dvec3& wi) {
                return double(M::roughplastic_pdf(p, table.data(), ns, wo, Vec3<R>(wi)));
            };
            const wp::test::SphereChiSquare result = wp::test::sphere_chi_square(sample, pdf, kNormal, 100000);
            const std::string where = describe(material) + " cos " + std::to_string(cos_theta);
            EXPECT_TRUE(result.failure.empty()) << where << ": " << result.describe();
            EXPECT_GT(result.chi_square.p_value, level) << where << ": " << result.describe();
        }
    }
}

// Every sample's pdf is roughplastic_pdf's for its direction and its weight
// f cos / pdf with f from roughplastic_eval, within rounding (relative: a
// few roundings times the steepness of D at alpha 0.05, as in
// conductor_test); invalid samples (reflections below ns) have weight and
// pdf 0.
TYPED_TEST(RoughPlastic, SampleAgreesWithEvalAndPdf) {
    using R = TypeParam;
    using M = wp::SharedMath<R>;
    const double tolerance = std::is_same_v<R, float> ? 2e-3 : 1e-8;
    wp::test::UnitRandom<R> random(12);
    for (const RoughMaterial& material : rough_plastics()) {
        std::vector<R> table;
        const auto p = shared_rough<R>(material, &table);
        for (double cos_theta : {0.95, 0.6, 0.3, 0.05}) {
            const Vec3<R> wo(around_normal(cos_theta, kAzimuth)), ns(kNormal);
            const R t_o = M::roughplastic_transmittance(table.data(), 0u, R(cos_theta));
            const R p_s = M::roughplastic_specular_probability(t_o, p.specular_sampling_weight);
            int valid = 0;
            for (int i = 0; i < 400; ++i) {
                typename M::BsdfRandom r;
                r.lobe = random(), r.u = random(), r.v = random();
                auto s = M::roughplastic_sample(p, table.data(), ns, ns, wo, r, 0);
                EXPECT_EQ(s.specular, 0u);
                EXPECT_EQ(s.eta_squared, R(1));
                if (!s.valid) {
                    EXPECT_LT(r.lobe, p_s) << "only a specular reflection leaves below ns";
                    EXPECT_EQ(s.pdf, R(0));
                    EXPECT_EQ(s.weight, Vec3<R>(0));
                    continue;
                }
                ++valid;
                const double cos_i = glm::dot(glm::dvec3(s.direction), kNormal);
                ASSERT_GT(cos_i, 0.0);
                const double pdf = M::roughplastic_pdf(p, table.data(), ns, wo, s.direction);
                ASSERT_NEAR(s.pdf / pdf, 1.0, tolerance) << describe(material) << " sample " << i;
                const Vec3<R> f = M::roughplastic_eval(p, table.data(), ns, wo, s.direction);
                for (int c = 0; c < 3; ++c) {
                    ASSERT_NEAR(s.weight[c] / (f[c] * cos_i / pdf), 1.0, tolerance)
                        << describe(material) << " cos " << cos_theta << " sample " << i << " channel " << c;
                }
            }
            EXPECT_GT(valid, 200) << describe(material) << " cos " << cos_theta;
        }
    }
}

// f(wo, wi) == f(wi, wo): Mitsuba's roughplastic is reciprocal (the
// specular lobe is, and the diffuse lobe is symmetric in t(wo.z) t(wi.z));
// its pdf is not, nor need it be.
TYPED_TEST(RoughPlastic, IsReciprocal) {
    using R = TypeParam;
    using M = wp::SharedMath<R>;
    const Vec3<R> ns(kNormal);
    for (const RoughMaterial& material : rough_plastics()) {
        std::vector<R> table;
        const auto p = shared_rough<R>(material, &table);
        for (int i = 0; i < 50; ++i) {
            const Vec3<R> a(around_normal(0.02 + 0.96 * ((i * 7) % 50) / 50.0, 0.3 * i));
            const Vec3<R> b(around_normal(0.02 + 0.96 * ((i * 13) % 50) / 50.0, 2.0 + 0.7 * i));
            const Vec3<R> ab = M::roughplastic_eval(p, table.data(), ns, a, b);
            const Vec3<R> ba = M::roughplastic_eval(p, table.data(), ns, b, a);
            for (int c = 0; c < 3; ++c) {
                EXPECT_NEAR(ab[c], ba[c], 1e3 * wp::test::kRoundingTolerance<R> * (1.0 + std::fabs(ab[c])))
                    << describe(material) << " pair " << i;
            }
        }
    }
}

// Nothing below the shading normal: f and the pdf are 0 when either
// direction is under it, and a path arriving from below gets no sample.
TYPED_TEST(RoughPlastic, ReflectsNothingBelowTheSurface) {
    using R = TypeParam;
    using M = wp::SharedMath<R>;
    const Vec3<R> ns(kNormal), above(around_normal(0.6, 1.0)), below(around_normal(-0.3, 2.0));
    for (const RoughMaterial& material : rough_plastics()) {
        std::vector<R> table;
        const auto p = shared_rough<R>(material, &table);
        for (auto [wo, wi] : {std::pair{above, below}, {below, above}, {below, below}}) {
            EXPECT_EQ(M::roughplastic_eval(p, table.data(), ns, wo, wi), Vec3<R>(0)) << describe(material);
            EXPECT_EQ(M::roughplastic_pdf(p, table.data(), ns, wo, wi), R(0)) << describe(material);
        }
        for (R lobe : {R(0), R(0.999)}) {
            typename M::BsdfRandom r;
            r.lobe = lobe, r.u = R(0.3), r.v = R(0.6);
            auto s = M::roughplastic_sample(p, table.data(), ns, ns, below, r, 0);
            EXPECT_FALSE(s.valid) << describe(material);
            EXPECT_EQ(s.weight, Vec3<R>(0));
        }
    }
}

// With white reflectances the albedo, the integral of f cos over the
// hemisphere, is at most 1. The specular lobe's part (diffuse 0) is
// integrated over the microfacet normals (support/microfacet_reference.h's
// quadrature, dwi = 4 wo.h dh), the diffuse lobe's (specular 0), which
// depends on wi's cosine only, by the midpoint rule in mu.
TYPED_TEST(RoughPlastic, WhiteAlbedoIsAtMostOne) {
    using R = TypeParam;
    using M = wp::SharedMath<R>;
    for (bool beckmann : {true, false}) {
        for (double alpha : {0.05, 0.3, 1.0}) {
            for (bool nonlinear : {false, true}) {
                const RoughMaterial white{"white",         {beckmann, alpha, alpha}, glm::dvec3(1.0),
                                          glm::dvec3(1.0), 1.49 / 1.000277,          nonlinear};
                RoughMaterial specular_only = white, diffuse_only = white;
                specular_only.diffuse = glm::dvec3(0.0);
                diffuse_only.specular = glm::dvec3(0.0);
                std::vector<R> table;
                const auto specular = shared_rough<R>(specular_only, &table);
                const auto diffuse = shared_rough<R>(diffuse_only, &table);
                for (double cos_theta : {1.0, 0.7, 0.3, 0.05}) {
                    const glm::dvec3 wo_local = wp::test::local_direction(cos_theta, kAzimuth);
                    const Vec3<R> ns(0, 0, 1), wo(wo_local);
                    const double glossy = wp::test::integrate_over_normals(alpha, [&](glm::dvec3 h) {
                        const double wo_h = glm::dot(wo_local, h);
                        const glm::dvec3 wi = 2.0 * wo_h * h - wo_local;
                        if (wo_h <= 0.0 || wi.z <= 0.0) return 0.0;
                        return double(M::roughplastic_eval(specular, table.data(), ns, wo, Vec3<R>(wi)).x) * wi.z *
                               4.0 * wo_h;
                    });
                    const int n = 4000;
                    double base = 0.0;
                    for (int i = 0; i < n; ++i) {
                        const double mu = (i + 0.5) / n;
                        const Vec3<R> wi(wp::test::local_direction(mu, 1.0 + i));
                        base +=
                            M::roughplastic_eval(diffuse, table.data(), ns, wo, wi).x * mu * 2.0 * std::numbers::pi / n;
                    }
                    EXPECT_LE(glossy + base, 1.0)
                        << describe(white) << " cos " << cos_theta << ": specular " << glossy << " diffuse " << base;
                }
            }
        }
    }
}

// Mitsuba's roughplastic material of a case of the table, and that table's
// RoughMaterial.
RoughMaterial mitsuba_material(const table::RoughPlasticCase& c) {
    return {c.name,
            {c.beckmann, c.alpha, c.alpha},
            glm::dvec3(c.diffuse[0], c.diffuse[1], c.diffuse[2]),
            glm::dvec3(c.specular[0], c.specular[1], c.specular[2]),
            c.eta,
            c.nonlinear};
}

// Float's unit in the last place at 1 (2^-23): the unit of the tolerances
// against Mitsuba, whose values are float's.
constexpr double kFloatUlp = std::numeric_limits<float>::epsilon();

// Mitsuba 3.9.1's roughplastic (support/plastic_mitsuba_table.h) at fixed
// pairs of directions: eval (with the cosine) and pdf, given Mitsuba's own
// precomputed table of t and R_int (read back from it by the script), so
// that this checks the formulas alone. GGX within 16 float ulps relative
// (Mitsuba rounds with fused multiply-adds); Beckmann within 0.6%:
// microfacet.h's Smith G1 for Beckmann is the exact one, Mitsuba's Walter's
// rational fit, up to 0.35% apart per G1, and eval has two of them. Where wi
// is below the surface Mitsuba's eval is 0 but its pdf, evaluated for many
// directions at once, is not masked (its roughplastic returns the specular
// lobe's density unmasked; plastic and roughconductor mask theirs): ours is
// 0 there, and only eval is compared.
TYPED_TEST(RoughPlastic, AgreesWithMitsuba) {
    using R = TypeParam;
    using M = wp::SharedMath<R>;
    const Vec3<R> ns(0, 0, 1);
    for (const table::RoughPlasticCase& c : table::kRoughPlastic) {
        std::vector<R> table;
        auto p = shared_rough<R>(mitsuba_material(c), &table);
        table.assign(c.transmittance.begin(), c.transmittance.end());
        p.internal_reflectance = R(c.internal_reflectance);
        const double tolerance = c.beckmann ? 6e-3 : 16 * kFloatUlp;
        for (int k = 0; k < table::kPairs; ++k) {
            const table::RoughPlasticPair& pair = c.pairs[k];
            const Vec3<R> wo(pair.wo[0], pair.wo[1], pair.wo[2]), wi(pair.wi[0], pair.wi[1], pair.wi[2]);
            const std::string where = std::string(c.name) + " pair " + std::to_string(k);
            const Vec3<R> f = M::roughplastic_eval(p, table.data(), ns, wo, wi);
            for (int ch = 0; ch < 3; ++ch) {
                EXPECT_NEAR(double(f[ch]) * std::fmax(double(wi.z), 0.0), pair.eval[ch], tolerance * pair.eval[ch])
                    << where << " channel " << ch;
            }
            const double pdf = M::roughplastic_pdf(p, table.data(), ns, wo, wi);
            if (wi.z <= R(0)) {
                EXPECT_EQ(pdf, 0.0) << where;
                continue;
            }
            EXPECT_NEAR(pdf, pair.pdf, tolerance * pair.pdf) << where;
        }
    }
}

// The host's precomputation (rough_interface_transmittance at the table's
// cosines, roughplastic_internal_reflectance) against Mitsuba's, read back
// from it: the same quadratures through different maps of the visible
// normals (roughplastic.h), t within 5e-4 relative for GGX and R_int within
// 5e-4; for Beckmann, whose G1 differs from Mitsuba's fit, t within 2.5e-3
// and R_int within 1e-3. In double, as the host computes them.
TYPED_TEST(RoughPlastic, PrecomputationAgreesWithMitsuba) {
    if (!std::is_same_v<TypeParam, double>) GTEST_SKIP() << "the host computes in double";
    for (const table::RoughPlasticCase& c : table::kRoughPlastic) {
        const RoughHost& host = rough_host(mitsuba_material(c));
        for (int k = 0; k < table::kTableSize; ++k) {
            EXPECT_NEAR(host.table[k] / c.transmittance[k], 1.0, c.beckmann ? 2.5e-3 : 5e-4)
                << c.name << " entry " << k;
        }
        EXPECT_NEAR(host.params.internal_reflectance / c.internal_reflectance, 1.0, c.beckmann ? 1e-3 : 5e-4) << c.name;
    }
}

}  // namespace roughplastic_test
}  // namespace
