/* The rough dielectric (Mitsuba 3's `roughdielectric`): Walter et al. 2007,
 * "Microfacet Models for Refraction through Rough Surfaces", an interface of
 * index `ior` (inside over outside, as glass.h's) made of smooth dielectric
 * microfacets (shared/materials/microfacet.h). With eta the relative index
 * across it from wo's side (`entering`: ior, else 1 / ior) and h the
 * microfacet normal that takes wo to wi (turned to wo's side):
 *   reflection (wi on wo's side), h = (wo + wi) / |wo + wi| (eq. 13):
 *     f = F(wo.h) D(h) G(wo, wi, h) / (4 |wo.z| |wi.z|)               (eq. 20)
 *   refraction, h = -(wo + eta wi) / |wo + eta wi| (eq. 16):
 *     f = (1 - F) D G eta^2 |wo.h| |wi.h| / (|wo.z| |wi.z| (wo.h + eta wi.h)^2)
 *                                                                    (eq. 21)
 *     times 1 / eta^2 for radiance (`transport`, as glass.h's: the solid
 *     angle's compression, which flux does not undergo; Mitsuba's
 *     "missing term");
 * F the dielectric Fresnel reflectance (shared/fresnel.h), G the separable
 * Smith form. A sample draws h from the normals visible from wo, then
 * reflects with probability F(wo.h) (the BsdfRandom's `lobe`) and refracts
 * otherwise, as Mitsuba does. `frame` is the microfacets' frame, z along
 * the shading normal ns on wo's side (microfacet_frame about
 * roughdielectric_frame).
 * Conventions: shared/materials/bsdf.h. */
#ifndef WP_SHARED_MATERIALS_ROUGHDIELECTRIC_H
#define WP_SHARED_MATERIALS_ROUGHDIELECTRIC_H

#include "shared/fresnel.h"
#include "shared/materials/bsdf.h"
#include "shared/materials/microfacet.h"
#include "shared/prelude.h"
#include "shared/sampling.h"

/* The relative index across the interface from wo's side. */
WP_FN real roughdielectric_eta(real ior, lane_int entering) { return entering ? ior : REAL(1.0) / ior; }

/* The local frame without dp/du (microfacet_frame's isotropic one), z along
 * ns (on wo's side): the tangents of the outward shading normal's
 * frame_from_normal, so that they keep their direction on the surface
 * whichever side a path arrives from, turned half about the tangent for a
 * path from inside (as Mitsuba mirrors a direction from inside into its one
 * shading frame). */
WP_FN Frame roughdielectric_frame(vec3 ns, lane_int entering) {
    Frame frame = frame_from_normal(v3_select(entering, ns, v3_neg(ns)));
    frame.bitangent = v3_select(entering, frame.bitangent, v3_neg(frame.bitangent));
    frame.normal = ns;
    return frame;
}

/* The microfacet normal that takes local wo to local wi, by reflection
 * (wi.z > 0) or refraction (wi.z < 0), turned up (to wo's side). */
WP_FN vec3 roughdielectric_half_vector(vec3 wo, vec3 wi, real eta) {
    vec3 h = v3_normalize(v3_add_scaled(wo, wi.z > REAL(0.0) ? REAL(1.0) : eta, wi));
    return v3_scale(h, copysign(REAL(1.0), h.z));
}

/* d(h) / d(wi) of a refraction through h: eta^2 |wi.h| / (wo.h + eta wi.h)^2
 * (Walter et al. 2007, eq. 17, with wo's side's index 1). */
WP_FN real refraction_jacobian(vec3 wo, vec3 wi, vec3 h, real eta) {
    real denominator = v3_dot(wo, h) + eta * v3_dot(wi, h);
    return eta * eta * fabs(v3_dot(wi, h)) / (denominator * denominator);
}

/* Whether local wo and wi see h from the sides they are on (G1's test), so
 * that h is a microfacet normal that can take one to the other. */
WP_FN lane_int roughdielectric_pair_is_consistent(vec3 wo, vec3 wi, vec3 h) {
    return wo.z > REAL(0.0) && v3_dot(wo, h) > REAL(0.0) && v3_dot(wi, h) * wi.z > REAL(0.0);
}

/* f for local wo, wi. */
WP_FN real roughdielectric_eval_local(Microfacet m, real eta, vec3 wo, vec3 wi, uint transport) {
    vec3 h = roughdielectric_half_vector(wo, wi, eta);
    real fresnel = fresnel_dielectric(v3_dot(wo, h), eta);
    real microfacets = microfacet_D(m, h) * microfacet_G(m, wo, wi, h) / fabs(wo.z * wi.z);
    real reflection = fresnel * microfacets / REAL(4.0);
    real refraction = (REAL(1.0) - fresnel) * microfacets * fabs(v3_dot(wo, h)) * refraction_jacobian(wo, wi, h, eta) /
                      (transport == WP_TRANSPORT_RADIANCE ? eta * eta : REAL(1.0));
    real f = wi.z > REAL(0.0) ? reflection : refraction;
    return roughdielectric_pair_is_consistent(wo, wi, h) && isfinite(f) ? f : REAL(0.0);
}

/* f for the pair wo, wi (without the cosine), the same in each channel. */
WP_FN vec3 roughdielectric_eval(Microfacet m, real ior, lane_int entering, Frame frame, vec3 wo, vec3 wi,
                                uint transport) {
    real f = roughdielectric_eval_local(m, roughdielectric_eta(ior, entering), frame_to_local(frame, wo),
                                        frame_to_local(frame, wi), transport);
    return make_vec3(f, f, f);
}

/* The density with which roughdielectric_sample picks local wi: the visible
 * normal's density, times the probability of the lobe (F or 1 - F), times
 * the Jacobian of the lobe's half vector. */
WP_FN real roughdielectric_pdf_local(Microfacet m, real eta, vec3 wo, vec3 wi) {
    vec3 h = roughdielectric_half_vector(wo, wi, eta);
    real fresnel = fresnel_dielectric(v3_dot(wo, h), eta);
    real reflection = fresnel * microfacet_reflection_pdf(m, wo, h);
    real refraction = (REAL(1.0) - fresnel) * microfacet_pdf_visible(m, wo, h) * refraction_jacobian(wo, wi, h, eta);
    real pdf = wi.z > REAL(0.0) ? reflection : refraction;
    return roughdielectric_pair_is_consistent(wo, wi, h) && isfinite(pdf) ? pdf : REAL(0.0);
}

/* The density with which roughdielectric_sample picks wi. */
WP_FN real roughdielectric_pdf(Microfacet m, real ior, lane_int entering, Frame frame, vec3 wo, vec3 wi) {
    return roughdielectric_pdf_local(m, roughdielectric_eta(ior, entering), frame_to_local(frame, wo),
                                     frame_to_local(frame, wi));
}

/* A visible normal h from (random.u, random.v); reflection about it where
 * random.lobe < F(wo.h) (always under total internal reflection), else
 * refraction through it. The weight f |wi.z| / pdf reduces to G1(wi, h),
 * times 1 / eta^2 for refracted radiance. A direction that leaves on the
 * wrong side of the surface for its lobe is invalid, with weight and pdf 0
 * and the direction ns. */
WP_FN BsdfSample roughdielectric_sample(Microfacet m, real ior, lane_int entering, vec3 nf, Frame frame, vec3 wo,
                                        BsdfRandom random, uint transport, int shading_normals) {
    real eta = roughdielectric_eta(ior, entering);
    vec3 wo_local = frame_to_local(frame, wo);
    vec3 h = microfacet_sample_visible(m, wo_local, random.u, random.v);
    real fresnel = fresnel_dielectric(v3_dot(wo_local, h), eta);
    vec3 refracted = wo_local; /* overwritten where refract_direction runs */
    lane_int refracts = random.lobe >= fresnel && refract_direction(v3_neg(wo_local), h, eta, &refracted);
    vec3 wi_local = v3_select(refracts, refracted, reflect_direction(v3_neg(wo_local), h));
    real reflection_pdf = fresnel * microfacet_reflection_pdf(m, wo_local, h);
    real refraction_pdf = (REAL(1.0) - fresnel) * microfacet_pdf_visible(m, wo_local, h) *
                          refraction_jacobian(wo_local, wi_local, h, eta);
    real pdf = refracts ? refraction_pdf : reflection_pdf;
    lane_int scatters = roughdielectric_pair_is_consistent(wo_local, wi_local, h) &&
                        (wi_local.z < REAL(0.0)) == refracts && pdf > REAL(0.0);
    real weight =
        microfacet_G1(m, wi_local, h) / (refracts && transport == WP_TRANSPORT_RADIANCE ? eta * eta : REAL(1.0));
    BsdfSample s;
    s.direction = v3_select(scatters, frame_to_world(frame, wi_local), frame.normal);
    s.weight = make_vec3(scatters ? weight : REAL(0.0), scatters ? weight : REAL(0.0), scatters ? weight : REAL(0.0));
    s.leave_side = v3_select(refracts, v3_neg(nf), nf);
    s.pdf = scatters ? pdf : REAL(0.0);
    s.eta_squared = refracts ? eta * eta : REAL(1.0);
    s.specular = 0u;
    s.valid = scatters && leaves_on_side(s.direction, s.leave_side, shading_normals);
    return s;
}

#endif
