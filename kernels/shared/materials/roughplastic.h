/* The rough plastic (Mitsuba 3's `roughplastic`): a diffuse base under a
 * rough dielectric coat of relative index eta = int_ior / ext_ior whose
 * microfacets (shared/materials/microfacet.h, isotropic Beckmann or GGX)
 * reflect as roughconductor.h's do, with the dielectric's Fresnel:
 *   f(wo, wi) = specular_reflectance F(wo.h) D(h) G(wo, wi, h) / (4 wo.z wi.z)
 *             + d' t(wo.z) t(wi.z) / (pi eta^2),
 * h the half vector, d' = d / (1 - R_int) (or d / (1 - d R_int) with
 * `nonlinear`), 0 unless both directions are above the shading normal. Here
 * t(mu) is the fraction of light arriving at cos theta mu that the rough
 * coat transmits (single scattering: rough_interface_transmittance), and
 * R_int the coat's reflectance from inside to diffuse light
 * (roughplastic_internal_reflectance): the internal bounces summed as in
 * plastic.h, with the rough coat's quantities in place of the smooth one's.
 *
 * As Mitsuba, each material precomputes t at the 64 cosines
 * max(1e-6, k / 63) and interpolates linearly between them, and R_int once:
 * the host fills, through SharedMath<double>, WP_ROUGHPLASTIC_TABLE_SIZE
 * entries rough_interface_transmittance(m, eta, roughplastic_table_cosine(k))
 * of a table in device memory (the material's RoughPlasticParams holds where
 * they start) and calls roughplastic_params, which computes R_int. Each is a
 * function of the distribution, alpha and eta only.
 *
 * A sample picks the specular lobe (a normal visible from wo, as
 * roughconductor.h's) with probability
 *   P_s = (1 - t(wo.z)) w / ((1 - t(wo.z)) w + t(wo.z) (1 - w)),
 * w the specular sampling weight (plastic.h), else a cosine-distributed
 * direction; its pdf is the mixture of both lobes' densities, and its weight
 * f cos / pdf. Conventions: shared/materials/bsdf.h. */
#ifndef WP_SHARED_MATERIALS_ROUGHPLASTIC_H
#define WP_SHARED_MATERIALS_ROUGHPLASTIC_H

#include "shared/fresnel.h"
#include "shared/materials/bsdf.h"
#include "shared/materials/microfacet.h"
#include "shared/materials/plastic.h"
#include "shared/prelude.h"
#include "shared/sampling.h"

/* Mitsuba's MI_ROUGH_TRANSMITTANCE_RES: the entries of a material's table of t. */
#define WP_ROUGHPLASTIC_TABLE_SIZE 64

typedef struct {
    Microfacet m; /* isotropic: alpha_u = alpha_v */
    vec3 diffuse_reflectance, specular_reflectance;
    real eta;                       /* int_ior / ext_ior */
    real inv_eta_2;                 /* 1 / eta^2 */
    real specular_sampling_weight;  /* plastic_specular_sampling_weight */
    real internal_reflectance;      /* R_int: roughplastic_internal_reflectance(m, eta) */
    lane_int nonlinear;             /* Mitsuba's `nonlinear` */
    lane_uint transmittance_offset; /* where the material's table of t starts in the table buffer */
} RoughPlasticParams;

/* The cosine of the table's entry k, k = 0 .. WP_ROUGHPLASTIC_TABLE_SIZE - 1:
 * Mitsuba's max(1e-6, linspace(0, 1, 64)). */
WP_FN real roughplastic_table_cosine(int k) { return fmax(REAL(1e-6), (real)(k) / REAL(63.0)); }

/* t at cos theta mu from the material's table: linear between the entries
 * about mu * 63 (Mitsuba's lerp_gather). mu is clamped into [0, 1] (a NaN
 * to 0), so that no lane reads outside the table, wherever its value is
 * then discarded. */
WP_FN real roughplastic_transmittance(WP_GLOBAL const real_element* table, lane_uint offset, real mu) {
    real x = wp_clamp(mu, REAL(0.0), REAL(1.0)) * REAL(63.0); /* WP_ROUGHPLASTIC_TABLE_SIZE - 1 */
    real index = fmin(floor(x), REAL(62.0));
    lane_uint i = offset + TO_LANE_UINT(index);
    real t = x - index;
    return gather(table, i) * (REAL(1.0) - t) + gather(table, i + 1u) * t;
}

/* The node and weight i (0 .. n - 1) of n-point Gauss-Legendre quadrature on
 * [-1, 1]: Newton's method on the Legendre polynomial P_n (its three-term
 * recurrence), from the estimate cos(pi (i + 3/4) / (n + 1/2)) (Abramowitz
 * and Stegun 22.16.6), converged to the precision's rounding by 8 steps for
 * n <= 128. The weight is 2 / ((1 - x^2) P_n'(x)^2). */
typedef struct {
    real x, weight;
} QuadratureNode;

WP_FN QuadratureNode gauss_legendre_node(int n, int i) {
    real x = cos_sin_turns(((real)(i) + REAL(0.75)) / (REAL(2.0) * (real)(n) + REAL(1.0))).cos_value;
    real derivative = REAL(1.0);
    for (int step = 0; step < 8; ++step) {
        real p_previous = REAL(1.0), p = x;
        for (int j = 2; j <= n; ++j) {
            real p_next = ((REAL(2.0) * (real)(j)-REAL(1.0)) * x * p - ((real)(j)-REAL(1.0)) * p_previous) / (real)(j);
            p_previous = p;
            p = p_next;
        }
        derivative = (real)(n) * (x * p - p_previous) / (x * x - REAL(1.0));
        x = x - p / derivative;
    }
    QuadratureNode node;
    node.x = x;
    node.weight = REAL(2.0) / ((REAL(1.0) - x * x) * derivative * derivative);
    return node;
}

/* The quadrature's points per axis: Mitsuba's 32 where light enters the
 * denser side (eta > 1), 128 from the denser side (total internal
 * reflection puts a kink in the integrand); with several lanes, 128 where
 * any lane needs it. */
WP_FN int rough_interface_resolution(real eta) { return lanes_any(eta <= REAL(1.0)) ? 128 : 32; }

/* The fraction of light arriving at cos theta mu (> 0) that a rough
 * dielectric interface of relative index eta transmits (`transmit` 1) or
 * reflects (0), counting single scattering only: the integral over the
 * normals h visible from wi of (1 - F(wi.h)) G1(wt, h), or F(wi.h) G1(wr, h),
 * wt and wr the refraction and the reflection of wi about h (0 where they
 * leave on the wrong side). As Mitsuba's eval_transmittance and
 * eval_reflectance: Gauss-Legendre on n x n points (n <= 128) in the unit
 * square of random numbers that microfacet_sample_visible maps to the
 * visible normals, which carries their density. The host's: n^2 visible
 * normals per call. The integrand has kinks (where wt or wr crosses the
 * horizon, and at the critical angle), so the rule converges slowly: over
 * the tests' distributions (Beckmann and GGX, alpha 0.05 to 1, eta 1.49) t
 * by 32 points is within 3e-4 relative of t by 128 for GGX and within 7e-5
 * for Beckmann, and Mitsuba's own table (the same rule through its own map of
 * the visible normals) within 3.3e-4 of it for GGX (1.8e-3 for Beckmann,
 * whose G1 differs: microfacet.h). */
WP_FN real rough_interface_scattering(Microfacet m, real eta, real mu, int transmit, int n) {
    real nodes[128], weights[128];
    for (int i = 0; i < n; ++i) {
        QuadratureNode node = gauss_legendre_node(n, i);
        nodes[i] = REAL(0.5) * node.x + REAL(0.5);
        weights[i] = REAL(0.5) * node.weight;
    }
    vec3 wi = make_vec3(safe_sqrt(REAL(1.0) - mu * mu), REAL(0.0), mu);
    real sum = REAL(0.0);
    for (int i = 0; i < n; ++i) {
        for (int j = 0; j < n; ++j) {
            vec3 h = microfacet_sample_visible(m, wi, nodes[i], nodes[j]);
            real fresnel = fresnel_dielectric(v3_dot(wi, h), eta);
            vec3 wt = wi; /* overwritten where refract_direction runs */
            lane_int refracts = refract_direction(v3_neg(wi), h, eta, &wt);
            vec3 wr = reflect_direction(v3_neg(wi), h);
            real transmitted =
                refracts && wt.z < REAL(0.0) ? (REAL(1.0) - fresnel) * microfacet_G1(m, wt, h) : REAL(0.0);
            real reflected = wr.z > REAL(0.0) ? fresnel * microfacet_G1(m, wr, h) : REAL(0.0);
            sum += (transmit ? transmitted : reflected) * (weights[i] * weights[j]);
        }
    }
    return sum;
}

/* t(mu): the entries of a material's table (roughplastic_table_cosine), by
 * Mitsuba's resolution. */
WP_FN real rough_interface_transmittance(Microfacet m, real eta, real mu) {
    return rough_interface_scattering(m, eta, mu, 1, rough_interface_resolution(eta));
}

/* The quadrature's points per axis for R_int: 64 where Mitsuba takes 128
 * (rough_interface_resolution at 1 / eta < 1). Over the tests' distributions
 * (Beckmann and GGX, alpha 0.05 to 1, eta 1.49) the 64- and 128-point rules
 * give R_int within 3e-4 relative of each other, as far as the 128-point
 * rule here is from Mitsuba's own value (the two sample the visible normals
 * through different maps of the unit square, so their nodes differ), at a
 * quarter of the cost (a Beckmann material's R_int took 1.8 s in double with
 * 128). */
#define WP_ROUGHPLASTIC_INTERNAL_RESOLUTION 64

/* R_int: the coat's reflectance from inside (relative index 1 / eta) to
 * light diffuse below it, 2 int_0^1 R(mu) mu dmu, by Mitsuba's rule: twice
 * the mean of R(mu) mu over the table's 64 cosines (which is not the
 * integral: its endpoints weigh as much as the inner points, so it falls
 * short of it by about 1/64 relative; kept, as it is Mitsuba's model). */
WP_FN real roughplastic_internal_reflectance(Microfacet m, real eta) {
    real sum = REAL(0.0);
    for (int k = 0; k < WP_ROUGHPLASTIC_TABLE_SIZE; ++k) {
        real mu = roughplastic_table_cosine(k);
        sum += rough_interface_scattering(m, REAL(1.0) / eta, mu, 0, WP_ROUGHPLASTIC_INTERNAL_RESOLUTION) * mu;
    }
    return REAL(2.0) * sum / REAL(64.0);
}

/* A material's parameters (the host's, once per material: R_int costs
 * 64 x 64^2 visible normals), its table starting at transmittance_offset.
 * eta = int_ior / ext_ior; colours constant over the surface (where a
 * reflectance is a texture, set the sampling weight from its mean). */
WP_FN RoughPlasticParams roughplastic_params(Microfacet m, vec3 diffuse_reflectance, vec3 specular_reflectance,
                                             real eta, lane_int nonlinear, lane_uint transmittance_offset) {
    RoughPlasticParams p;
    p.m = m;
    p.diffuse_reflectance = diffuse_reflectance;
    p.specular_reflectance = specular_reflectance;
    p.eta = eta;
    p.inv_eta_2 = REAL(1.0) / (eta * eta);
    p.specular_sampling_weight = plastic_specular_sampling_weight(plastic_channel_mean(diffuse_reflectance),
                                                                  plastic_channel_mean(specular_reflectance));
    p.internal_reflectance = roughplastic_internal_reflectance(m, eta);
    p.nonlinear = nonlinear;
    p.transmittance_offset = transmittance_offset;
    return p;
}

/* The probability of the specular lobe for a path arriving at cos theta
 * whose transmittance is t_o. */
WP_FN real roughplastic_specular_probability(real t_o, real specular_sampling_weight) {
    real specular = (REAL(1.0) - t_o) * specular_sampling_weight;
    real diffuse = t_o * (REAL(1.0) - specular_sampling_weight);
    return specular / (specular + diffuse);
}

/* f for local wo, wi (z along ns). */
WP_FN vec3 roughplastic_eval_local(RoughPlasticParams p, WP_GLOBAL const real_element* table, vec3 wo, vec3 wi) {
    vec3 h = v3_normalize(v3_add(wo, wi));
    real microfacets = fresnel_dielectric(v3_dot(wo, h), p.eta) * microfacet_D(p.m, h) * microfacet_G(p.m, wo, wi, h) /
                       (REAL(4.0) * wo.z * wi.z);
    real t_o = roughplastic_transmittance(table, p.transmittance_offset, wo.z);
    real t_i = roughplastic_transmittance(table, p.transmittance_offset, wi.z);
    vec3 diffuse = plastic_internal_scattering(p.diffuse_reflectance, p.internal_reflectance, p.nonlinear);
    vec3 f =
        v3_add(v3_scale(p.specular_reflectance, microfacets), v3_scale(diffuse, WP_INV_PI * p.inv_eta_2 * t_o * t_i));
    return v3_select(wo.z > REAL(0.0) && wi.z > REAL(0.0), f, make_vec3(REAL(0.0), REAL(0.0), REAL(0.0)));
}

/* f for the pair wo, wi (without the cosine). */
WP_FN vec3 roughplastic_eval(RoughPlasticParams p, WP_GLOBAL const real_element* table, vec3 ns, vec3 wo, vec3 wi) {
    Frame frame = frame_from_normal(ns);
    return roughplastic_eval_local(p, table, frame_to_local(frame, wo), frame_to_local(frame, wi));
}

/* The density with which roughplastic_sample picks local wi: P_s times the
 * visible-normal reflection's, plus 1 - P_s times the cosine density. */
WP_FN real roughplastic_pdf_local(RoughPlasticParams p, WP_GLOBAL const real_element* table, vec3 wo, vec3 wi) {
    real t_o = roughplastic_transmittance(table, p.transmittance_offset, wo.z);
    real specular = roughplastic_specular_probability(t_o, p.specular_sampling_weight);
    real pdf = specular * microfacet_reflection_pdf(p.m, wo, v3_normalize(v3_add(wo, wi))) +
               (REAL(1.0) - specular) * cosine_hemisphere_pdf(wi.z);
    return wo.z > REAL(0.0) && wi.z > REAL(0.0) ? pdf : REAL(0.0);
}

/* The density with which roughplastic_sample picks wi. */
WP_FN real roughplastic_pdf(RoughPlasticParams p, WP_GLOBAL const real_element* table, vec3 ns, vec3 wo, vec3 wi) {
    Frame frame = frame_from_normal(ns);
    return roughplastic_pdf_local(p, table, frame_to_local(frame, wo), frame_to_local(frame, wi));
}

/* The specular lobe where random.lobe < P_s (wo mirrored about a normal
 * visible from it, drawn from (random.u, random.v)), else the diffuse lobe
 * (a cosine-distributed direction from (u, v)); pdf roughplastic_pdf's and
 * weight f cos / pdf, both lobes counted, as Mitsuba. Where the reflection
 * leaves below the shading normal (or wo arrives from behind it) the sample
 * is invalid, with weight and pdf 0 and the direction ns. */
WP_FN BsdfSample roughplastic_sample(RoughPlasticParams p, WP_GLOBAL const real_element* table, vec3 nf, vec3 ns,
                                     vec3 wo, BsdfRandom random, int shading_normals) {
    Frame frame = frame_from_normal(ns);
    vec3 wo_local = frame_to_local(frame, wo);
    real t_o = roughplastic_transmittance(table, p.transmittance_offset, wo_local.z);
    lane_int specular = random.lobe < roughplastic_specular_probability(t_o, p.specular_sampling_weight);
    vec3 h = make_vec3(REAL(0.0), REAL(0.0), REAL(1.0));
    if (lanes_any(specular)) h = microfacet_sample_visible(p.m, wo_local, random.u, random.v);
    vec3 wi_local =
        v3_select(specular, reflect_direction(v3_neg(wo_local), h), sample_cosine_hemisphere(random.u, random.v));
    real pdf = roughplastic_pdf_local(p, table, wo_local, wi_local);
    vec3 f = roughplastic_eval_local(p, table, wo_local, wi_local);
    lane_int reflects = wo_local.z > REAL(0.0) && wi_local.z > REAL(0.0) && pdf > REAL(0.0);
    return glossy_reflection_sample(frame, wi_local, v3_scale(f, wi_local.z / pdf), pdf, reflects, nf, ns,
                                    shading_normals);
}

#endif
