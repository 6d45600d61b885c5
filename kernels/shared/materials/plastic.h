/* The smooth plastic (Mitsuba 3's `plastic`): a diffuse base under a smooth
 * dielectric coat of relative index eta = int_ior / ext_ior. Light either
 * reflects off the coat (a delta lobe: the mirror direction about the shading
 * normal, weighted by the coat's Fresnel reflectance F(wo) and by
 * `specular_reflectance`), or enters it, scatters off the base any number of
 * times, the coat reflecting back the fraction fdr_int of what the base
 * sends up each time, and leaves. Summing those bounces gives the diffuse
 * lobe
 *   f(wo, wi) = d / (1 - fdr_int) (1 - F(wo)) (1 - F(wi)) / (pi eta^2),
 * d the diffuse reflectance, or with `nonlinear` (colours darken and saturate
 * as under varnish) d / (1 - d fdr_int); 0 unless wo and wi are both above
 * the shading normal. The Fresnel terms are the exact dielectric ones at wo's
 * and wi's angles (shared/fresnel.h), as Mitsuba's.
 *
 * A sample picks the delta lobe with probability
 *   P_s = F(wo) w / (F(wo) w + (1 - F(wo)) (1 - w)),
 * w the specular sampling weight (plastic_specular_sampling_weight), else a
 * cosine-distributed direction of the diffuse lobe; plastic_eval and
 * plastic_pdf are the diffuse lobe's, the pdf times 1 - P_s (what next-event
 * estimation and MIS need: the delta lobe has no density to evaluate).
 *
 * The material's constants (PlasticParams) are computed once per material on
 * the host through plastic_params (SharedMath<double>), the same quantities
 * Mitsuba precomputes. Conventions: shared/materials/bsdf.h. */
#ifndef WP_SHARED_MATERIALS_PLASTIC_H
#define WP_SHARED_MATERIALS_PLASTIC_H

#include "shared/fresnel.h"
#include "shared/materials/bsdf.h"
#include "shared/prelude.h"
#include "shared/sampling.h"

typedef struct {
    vec3 diffuse_reflectance, specular_reflectance;
    real eta;                      /* int_ior / ext_ior */
    real inv_eta_2;                /* 1 / eta^2 */
    real fdr_int;                  /* fresnel_diffuse_reflectance(1 / eta): the coat's from inside */
    real specular_sampling_weight; /* plastic_specular_sampling_weight */
    lane_int nonlinear;            /* Mitsuba's `nonlinear` */
} PlasticParams;

/* The fraction of uniformly diffuse light (radiance the same in every
 * direction) that a smooth dielectric interface of relative index eta
 * reflects, 2 int_0^1 F(mu, eta) mu dmu ("Fdr"): Mitsuba 3's
 * fresnel_diffuse_reflectance, by the same fits, so that the plastic agrees
 * with it: Egan and Hilgeman (1973) for eta < 1, d'Eon and Irving (2011), a
 * polynomial in 1 / eta, for eta >= 1. Measured against the integral
 * (tests/shared/plastic_test.cpp), relative: within 1.2e-3 for eta or
 * 1 / eta in [1.2, 2] (8.2e-4 too high at 1 / 1.49, the default plastic's
 * fdr_int), within 6e-3 in [1.05, 2.5]; worse towards 1 (index matched,
 * Fdr -> 0) and beyond 2.5. */
WP_FN real fresnel_diffuse_reflectance(real eta) {
    real inv_eta = REAL(1.0) / eta;
    real egan_hilgeman = REAL(0.0636) * inv_eta + (eta * (eta * REAL(-1.4399) + REAL(0.7099)) + REAL(0.6681));
    real p = REAL(-1.36881);
    p = p * inv_eta + REAL(4.98554);
    p = p * inv_eta - REAL(7.80989);
    p = p * inv_eta + REAL(6.75335);
    p = p * inv_eta - REAL(3.4793);
    p = p * inv_eta + REAL(0.919317);
    return eta < REAL(1.0) ? egan_hilgeman : p;
}

/* Mitsuba's steering of samples between the lobes: the mean of the specular
 * reflectance over that of both (means over the colour channels, or over a
 * texture). 1/2 where both are 0 (Mitsuba's 0/0). */
WP_FN real plastic_specular_sampling_weight(real diffuse_mean, real specular_mean) {
    real sum = diffuse_mean + specular_mean;
    return sum > REAL(0.0) ? specular_mean / sum : REAL(0.5);
}

/* The mean of a colour's channels, as Mitsuba's mean() of an RGB value. */
WP_FN real plastic_channel_mean(vec3 c) { return (c.x + c.y + c.z) / REAL(3.0); }

/* A material's parameters: eta = int_ior / ext_ior, the colours constant over
 * the surface. (Where a reflectance is a texture, set the sampling weight
 * from its mean with plastic_specular_sampling_weight.) */
WP_FN PlasticParams plastic_params(vec3 diffuse_reflectance, vec3 specular_reflectance, real eta, lane_int nonlinear) {
    PlasticParams p;
    p.diffuse_reflectance = diffuse_reflectance;
    p.specular_reflectance = specular_reflectance;
    p.eta = eta;
    p.inv_eta_2 = REAL(1.0) / (eta * eta);
    p.fdr_int = fresnel_diffuse_reflectance(REAL(1.0) / eta);
    p.specular_sampling_weight = plastic_specular_sampling_weight(plastic_channel_mean(diffuse_reflectance),
                                                                  plastic_channel_mean(specular_reflectance));
    p.nonlinear = nonlinear;
    return p;
}

/* The diffuse reflectance with the coat's internal bounces summed:
 * d / (1 - fdr), or d / (1 - d fdr) per channel with `nonlinear`. */
WP_FN vec3 plastic_internal_scattering(vec3 d, real fdr, lane_int nonlinear) {
    vec3 reflected = v3_select(nonlinear, v3_scale(d, fdr), make_vec3(fdr, fdr, fdr));
    return make_vec3(d.x / (REAL(1.0) - reflected.x), d.y / (REAL(1.0) - reflected.y), d.z / (REAL(1.0) - reflected.z));
}

/* The probability of the delta lobe for a path arriving with Fresnel
 * reflectance fresnel_o at the coat. */
WP_FN real plastic_specular_probability(real fresnel_o, real specular_sampling_weight) {
    real specular = fresnel_o * specular_sampling_weight;
    real diffuse = (REAL(1.0) - fresnel_o) * (REAL(1.0) - specular_sampling_weight);
    return specular / (specular + diffuse);
}

/* The throughput of a path that takes plastic_sample's diffuse lobe at a
 * vertex it arrives at along wo (SPPM's visible point on the base, which
 * evaluates plastic_eval there): `throughput` over the lobe's probability
 * 1 - P_s; 0 where the base is never chosen (a path from below ns, which
 * plastic_eval gives nothing either). */
WP_FN vec3 plastic_base_throughput(PlasticParams p, vec3 ns, vec3 wo, vec3 throughput) {
    real specular_probability =
        plastic_specular_probability(fresnel_dielectric(v3_dot(wo, ns), p.eta), p.specular_sampling_weight);
    real diffuse_probability = REAL(1.0) - specular_probability;
    return v3_select(diffuse_probability > REAL(0.0), v3_scale(throughput, REAL(1.0) / diffuse_probability),
                     make_vec3(REAL(0.0), REAL(0.0), REAL(0.0)));
}

/* The diffuse lobe's f for cosines cos_o, cos_i (both > 0) and their Fresnel
 * reflectances. */
WP_FN vec3 plastic_diffuse_f(PlasticParams p, real fresnel_o, real fresnel_i) {
    vec3 d = plastic_internal_scattering(p.diffuse_reflectance, p.fdr_int, p.nonlinear);
    return v3_scale(d, WP_INV_PI * p.inv_eta_2 * (REAL(1.0) - fresnel_o) * (REAL(1.0) - fresnel_i));
}

/* f of the diffuse lobe for the pair wo, wi (without the cosine); the delta
 * lobe is not in it. */
WP_FN vec3 plastic_eval(PlasticParams p, vec3 ns, vec3 wo, vec3 wi) {
    real cos_o = v3_dot(wo, ns), cos_i = v3_dot(wi, ns);
    vec3 f = plastic_diffuse_f(p, fresnel_dielectric(cos_o, p.eta), fresnel_dielectric(cos_i, p.eta));
    return v3_select(cos_o > REAL(0.0) && cos_i > REAL(0.0), f, make_vec3(REAL(0.0), REAL(0.0), REAL(0.0)));
}

/* The density with which plastic_sample picks wi by its diffuse lobe: the
 * cosine density times the lobe's probability 1 - P_s. */
WP_FN real plastic_pdf(PlasticParams p, vec3 ns, vec3 wo, vec3 wi) {
    real cos_o = v3_dot(wo, ns), cos_i = v3_dot(wi, ns);
    real diffuse =
        REAL(1.0) - plastic_specular_probability(fresnel_dielectric(cos_o, p.eta), p.specular_sampling_weight);
    real pdf = cosine_hemisphere_pdf(cos_i) * diffuse;
    return cos_o > REAL(0.0) && cos_i > REAL(0.0) ? pdf : REAL(0.0);
}

/* The delta lobe where random.lobe < P_s: wo mirrored about ns, weight
 * specular_reflectance F(wo) / P_s, pdf 0, `specular` 1; else the diffuse
 * lobe: a cosine-distributed direction from (random.u, random.v), weight
 * f cos / pdf = d' (1 - F(wo)) (1 - F(wi)) / (eta^2 (1 - P_s)) (d' the
 * diffuse reflectance with the internal bounces), pdf plastic_pdf's. A path
 * arriving from below ns gets no sample (invalid, weight 0). */
WP_FN BsdfSample plastic_sample(PlasticParams p, vec3 nf, vec3 ns, vec3 wo, BsdfRandom random, int shading_normals) {
    real cos_o = v3_dot(wo, ns);
    real fresnel_o = fresnel_dielectric(cos_o, p.eta);
    real specular_probability = plastic_specular_probability(fresnel_o, p.specular_sampling_weight);
    real diffuse_probability = REAL(1.0) - specular_probability;
    lane_int specular = random.lobe < specular_probability;
    vec3 diffuse_local = sample_cosine_hemisphere(random.u, random.v);
    real fresnel_i = fresnel_dielectric(diffuse_local.z, p.eta);
    vec3 diffuse_weight =
        v3_scale(plastic_internal_scattering(p.diffuse_reflectance, p.fdr_int, p.nonlinear),
                 p.inv_eta_2 * (REAL(1.0) - fresnel_o) * (REAL(1.0) - fresnel_i) / diffuse_probability);
    vec3 specular_weight = v3_scale(p.specular_reflectance, fresnel_o / specular_probability);
    lane_int arrives = cos_o > REAL(0.0);
    BsdfSample s;
    s.direction =
        v3_select(specular, reflect_direction(v3_neg(wo), ns), frame_to_world(frame_from_normal(ns), diffuse_local));
    s.weight = v3_select(arrives, v3_select(specular, specular_weight, diffuse_weight),
                         make_vec3(REAL(0.0), REAL(0.0), REAL(0.0)));
    s.leave_side = nf;
    s.pdf = arrives && !specular ? cosine_hemisphere_pdf(diffuse_local.z) * diffuse_probability : REAL(0.0);
    s.eta_squared = REAL(1.0);
    s.specular = specular ? 1u : 0u;
    s.valid = arrives && leaves_on_side(s.direction, nf, shading_normals);
    return s;
}

#endif
