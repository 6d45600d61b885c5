/* Microfacet distributions for the rough materials (roughconductor.h and
 * the rough dielectrics): Beckmann and GGX (Trowbridge-Reitz), isotropic or
 * anisotropic, their Smith masking function and the sampling of the normals
 * visible from a direction.
 *
 * Everything here works in the local frame of microfacet_frame, z along the
 * shading normal: alpha_u is the roughness along x, alpha_v along y, and
 * every direction is a unit vector. Conventions and formulas: Walter et al. 2007, "Microfacet
 * Models for Refraction through Rough Surfaces" (D, the half-vector
 * Jacobians); Heitz 2014, "Understanding the Masking-Shadowing Function in
 * Microfacet-Based BRDFs" (Smith's Lambda, section 5); Mitsuba 3's
 * MicrofacetDistribution (Beckmann by default, the separable G).
 *
 * Each lane may hold either distribution (`distribution`); the work of a
 * distribution no lane uses is skipped (shared/prelude.h's lanes_any). */
#ifndef WP_SHARED_MATERIALS_MICROFACET_H
#define WP_SHARED_MATERIALS_MICROFACET_H

#include "shared/prelude.h"
#include "shared/sampling.h"
#include "shared/special_functions.h"

#define WP_MICROFACET_BECKMANN 0u
#define WP_MICROFACET_GGX 1u
/* A material without microfacets: its lanes ask for neither distribution's
 * work, so that a diffuse lane beside a GGX one does not run Beckmann's
 * (whose visible normals take five erfinv). */
#define WP_MICROFACET_NONE 2u

typedef struct {
    lane_uint distribution; /* WP_MICROFACET_BECKMANN, WP_MICROFACET_GGX or WP_MICROFACET_NONE */
    real alpha_u, alpha_v;  /* roughness along the tangent (x) and the bitangent (y); > 0 */
} Microfacet;

/* The local frame of a rough material's microfacets about `isotropic`'s
 * normal (the shading normal on wo's side). Where alpha_u != alpha_v its x
 * (alpha_u's direction) is the surface's dp/du made orthogonal to the
 * normal, as in Mitsuba 3's shading frame (shared/sampling.h' frame_along),
 * or isotropic's tangent where dp/du has no such part (a plane); flipping
 * the normal or the tangent leaves an anisotropic D as it is, so either
 * side sees the same one. Elsewhere (an isotropic D is the same about any
 * tangent) it is `isotropic` itself, the frame the material builds without
 * dp/du (frame_from_normal, roughdielectric_frame). */
WP_FN Frame microfacet_frame(Microfacet m, Frame isotropic, vec3 dp_du) {
    Frame along = frame_along(isotropic.normal, dp_du, isotropic.tangent);
    lane_int anisotropic = m.alpha_u != m.alpha_v;
    along.tangent = v3_select(anisotropic, along.tangent, isotropic.tangent);
    along.bitangent = v3_select(anisotropic, along.bitangent, isotropic.bitangent);
    return along;
}

/* Whether some lane uses `distribution`. */
WP_FN int microfacet_any(Microfacet m, uint distribution) { return lanes_any(m.distribution == distribution); }

/* A direction's alpha^2 tan^2 theta, with alpha the roughness along its
 * azimuth (Heitz 2014, section 5.4): 1 / a^2 in Heitz's notation, the one
 * quantity Smith's Lambda depends on. */
WP_FN real microfacet_alpha2_tan2(Microfacet m, vec3 w) {
    real x = m.alpha_u * w.x, y = m.alpha_v * w.y;
    return (x * x + y * y) / (w.z * w.z);
}

/* The distribution stretched to roughness 1 (Heitz 2014, section 5.4): a
 * direction's image there, where visible normals are sampled. */
WP_FN vec3 microfacet_stretch(Microfacet m, vec3 w) {
    return v3_normalize(make_vec3(m.alpha_u * w.x, m.alpha_v * w.y, w.z));
}

/* Beckmann: D(h) = e^(-(h_x^2 / alpha_u^2 + h_y^2 / alpha_v^2) / h_z^2)
 * / (pi alpha_u alpha_v h_z^4) (Walter et al. 2007, eq. 25, anisotropic). */
WP_FN real beckmann_D(Microfacet m, vec3 h) {
    real x = h.x / m.alpha_u, y = h.y / m.alpha_v, z2 = h.z * h.z;
    return wp_exp(-(x * x + y * y) / z2) / (WP_PI * m.alpha_u * m.alpha_v * z2 * z2);
}

/* GGX: D(h) = 1 / (pi alpha_u alpha_v (h_x^2 / alpha_u^2 + h_y^2 / alpha_v^2
 * + h_z^2)^2) (Walter et al. 2007, eq. 33, anisotropic; h is a unit vector). */
WP_FN real ggx_D(Microfacet m, vec3 h) {
    real x = h.x / m.alpha_u, y = h.y / m.alpha_v;
    real s = x * x + y * y + h.z * h.z;
    return REAL(1.0) / (WP_PI * m.alpha_u * m.alpha_v * s * s);
}

/* The density of microfacet normals h per unit projected area, 0 below the
 * surface (and where it underflows, so no NaN escapes). */
WP_FN real microfacet_D(Microfacet m, vec3 h) {
    real beckmann = REAL(0.0), ggx = REAL(0.0);
    if (microfacet_any(m, WP_MICROFACET_BECKMANN)) beckmann = beckmann_D(m, h);
    if (microfacet_any(m, WP_MICROFACET_GGX)) ggx = ggx_D(m, h);
    real d = m.distribution == WP_MICROFACET_BECKMANN ? beckmann : ggx;
    return h.z > REAL(0.0) && isfinite(d) ? d : REAL(0.0);
}

/* Smith's G1 = 1 / (1 + Lambda) for Beckmann, with
 * Lambda = (erf(a) - 1) / 2 + e^(-a^2) / (2 a sqrt(pi)), a = 1 / sqrt(alpha2_tan2)
 * (Heitz 2014, section 5.1; exact, where Mitsuba 3 uses Walter's rational
 * fit, which differs by up to 0.35%): 1 at normal incidence (a infinite). */
WP_FN real beckmann_smith_g1(real alpha2_tan2) {
    real a = REAL(1.0) / sqrt(alpha2_tan2);
    return REAL(2.0) / (REAL(1.0) + wp_erf(a) + wp_exp(-a * a) / (a * WP_SQRT_PI));
}

/* Smith's G1 for GGX, Lambda = (sqrt(1 + alpha2_tan2) - 1) / 2 (Heitz 2014,
 * section 5.1), written without the cancellation. */
WP_FN real ggx_smith_g1(real alpha2_tan2) { return REAL(2.0) / (REAL(1.0) + sqrt(REAL(1.0) + alpha2_tan2)); }

/* The fraction of microfacets of normal h visible from direction w: Smith's
 * G1, 0 where w sees h's back or h is on the other side of the surface from
 * w (w.h and w.z differ in sign; Walter et al. 2007, eq. 7's chi+). */
WP_FN real microfacet_G1(Microfacet m, vec3 w, vec3 h) {
    real alpha2_tan2 = microfacet_alpha2_tan2(m, w);
    real beckmann = REAL(0.0), ggx = REAL(0.0);
    if (microfacet_any(m, WP_MICROFACET_BECKMANN)) beckmann = beckmann_smith_g1(alpha2_tan2);
    if (microfacet_any(m, WP_MICROFACET_GGX)) ggx = ggx_smith_g1(alpha2_tan2);
    real g1 = m.distribution == WP_MICROFACET_BECKMANN ? beckmann : ggx;
    return v3_dot(w, h) * w.z > REAL(0.0) ? g1 : REAL(0.0);
}

/* Masking and shadowing of the pair wo, wi: the separable Smith form
 * G1(wo) G1(wi), Mitsuba 3's choice (not the height-correlated one), so that
 * images agree with it. */
WP_FN real microfacet_G(Microfacet m, vec3 wo, vec3 wi, vec3 h) {
    return microfacet_G1(m, wo, h) * microfacet_G1(m, wi, h);
}

/* Visible normals of GGX, wo above the surface: Dupuy and Benyoub 2023,
 * "Sampling Visible GGX Normals with Spherical Caps". In the stretched
 * configuration the visible normals are the half vectors between wo and a
 * direction c drawn uniformly from the spherical cap z >= -wo.z (u turns
 * its azimuth, v its height); the normal found is then unstretched. */
WP_FN vec3 ggx_sample_visible(Microfacet m, vec3 wo, real u, real v) {
    vec3 wo_stretched = microfacet_stretch(m, wo);
    real z = (REAL(1.0) - v) * (REAL(1.0) + wo_stretched.z) - wo_stretched.z;
    vec3 h_stretched = v3_add(polar_vec3(safe_sqrt(REAL(1.0) - z * z), u, z), wo_stretched);
    return v3_normalize(make_vec3(m.alpha_u * h_stretched.x, m.alpha_v * h_stretched.y, h_stretched.z));
}

/* Newton's iterations for beckmann_visible_slope_x: 4 leave a residual below
 * 1e-9 in the CDF over a grid of angles and u (3, Mitsuba 3's count, leave
 * up to 2e-6). */
#define WP_BECKMANN_NEWTON_STEPS 4

/* The slope x~ along the azimuth of a direction at cos_theta, sin_theta from
 * the normal, of the roughness-1 Beckmann normals visible from it, for u in
 * [0, 1): Jakob 2014, "An Improved Visible Normal Sampling Routine for the
 * Beckmann Distribution". A normal of slope x~ (normal (-x~, -y~, 1)) is
 * visible below x~ = cot theta, and the marginal CDF of x~ is, in the
 * variable x = erf(x~),
 *   C(x) = (1 + x + tan theta e^(-x~^2) / sqrt(pi)) / (1 + erf(cot theta)
 *          + tan theta e^(-cot^2 theta) / sqrt(pi)).
 * C(x) = u is solved by Newton's method in x, C being concave and increasing
 * there (C' = (1 - x~ tan theta) / norm, C'' < 0): from the starting point
 * (the exact solution at theta = 90 degrees, mapped onto [-1, erf(cot theta)])
 * the first step lands left of the root and the next ones rise to it. */
WP_FN real beckmann_visible_slope_x(real cos_theta, real sin_theta, real u) {
    real tan_theta = sin_theta / cos_theta;
    real cot_theta = cos_theta / sin_theta; /* infinite at normal incidence: erf 1, e^-inf 0 */
    real x_max = wp_erf(cot_theta);
    real tail_scale = tan_theta / WP_SQRT_PI;
    real target = u * (REAL(1.0) + x_max + tail_scale * wp_exp(-cot_theta * cot_theta));
    real x = x_max - (REAL(1.0) + x_max) * wp_erf(sqrt(-wp_log(u)));
    for (int step = 0; step < WP_BECKMANN_NEWTON_STEPS; ++step) {
        real slope = wp_erfinv(x);
        real value = REAL(1.0) + x + tail_scale * wp_exp(-slope * slope) - target;
        real derivative = REAL(1.0) - slope * tan_theta;
        x = wp_clamp(x - value / derivative, REAL(-1.0), x_max);
    }
    return wp_erfinv(x);
}

/* Visible normals of Beckmann, wo above the surface (Heitz and d'Eon 2014,
 * "Importance Sampling Microfacet-Based BSDFs using the Distribution of
 * Visible Normals", with Jakob's inversion): stretch wo to roughness 1,
 * sample the slope (x~, y~) in wo's azimuth (x~ by
 * beckmann_visible_slope_x from u, y~ independent and Gaussian, erfinv(2 v - 1)),
 * rotate it back to the frame, unstretch it and turn it into a normal. */
WP_FN vec3 beckmann_sample_visible(Microfacet m, vec3 wo, real u, real v) {
    vec3 wo_stretched = microfacet_stretch(m, wo);
    real sin_theta = sqrt(wo_stretched.x * wo_stretched.x + wo_stretched.y * wo_stretched.y);
    lane_int tilted = sin_theta > REAL(0.0);
    real cos_phi = tilted ? wo_stretched.x / sin_theta : REAL(1.0);
    real sin_phi = tilted ? wo_stretched.y / sin_theta : REAL(0.0);
    real slope_x = beckmann_visible_slope_x(wo_stretched.z, sin_theta, u);
    real slope_y = wp_erfinv(REAL(2.0) * v - REAL(1.0));
    real x = (cos_phi * slope_x - sin_phi * slope_y) * m.alpha_u;
    real y = (sin_phi * slope_x + cos_phi * slope_y) * m.alpha_v;
    return v3_normalize(make_vec3(-x, -y, REAL(1.0)));
}

/* A microfacet normal h drawn from the normals visible from wo (wo.z > 0),
 * D_wo(h) = G1(wo, h) max(0, wo.h) D(h) / wo.z, from random numbers u, v in
 * [0, 1). */
WP_INLINED_FN vec3 microfacet_sample_visible(Microfacet m, vec3 wo, real u, real v) {
    vec3 beckmann = wo, ggx = wo;
    if (microfacet_any(m, WP_MICROFACET_BECKMANN)) beckmann = beckmann_sample_visible(m, wo, u, v);
    if (microfacet_any(m, WP_MICROFACET_GGX)) ggx = ggx_sample_visible(m, wo, u, v);
    return v3_select(m.distribution == WP_MICROFACET_BECKMANN, beckmann, ggx);
}

/* The solid-angle density D_wo(h) of microfacet_sample_visible's normal; 0
 * where wo is not above the surface. */
WP_FN real microfacet_pdf_visible(Microfacet m, vec3 wo, vec3 h) {
    real pdf = microfacet_G1(m, wo, h) * fmax(v3_dot(wo, h), REAL(0.0)) * microfacet_D(m, h) / wo.z;
    return wo.z > REAL(0.0) ? pdf : REAL(0.0);
}

/* The solid-angle density of wi = wo mirrored about a visible normal h:
 * D_wo(h) times the Jacobian of the half vector, d(h) / d(wi) = 1 / (4 wo.h)
 * (Walter et al. 2007, eq. 14). */
WP_FN real microfacet_reflection_pdf(Microfacet m, vec3 wo, vec3 h) {
    real wo_h = v3_dot(wo, h);
    return wo_h > REAL(0.0) ? microfacet_pdf_visible(m, wo, h) / (REAL(4.0) * wo_h) : REAL(0.0);
}

#endif
