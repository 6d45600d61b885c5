/* The rough conductor (Mitsuba 3's `roughconductor`): a surface of mirror
 * microfacets (shared/materials/microfacet.h), each reflecting with the
 * conductor's Fresnel reflectance for the complex index eta + i k per colour
 * channel (shared/fresnel.h), tinted by `specular_reflectance`:
 *   f(wo, wi) = specular_reflectance F(wo.h) D(h) G(wo, wi, h) / (4 wo.z wi.z),
 * h the half vector of wo and wi (Walter et al. 2007, eq. 20), 0 unless both
 * directions are above the shading normal. Directions are sampled by
 * reflecting wo about a visible normal. `frame` is the microfacets' frame,
 * z along the shading normal ns (microfacet_frame about frame_from_normal(ns)):
 * alpha_u lies along its tangent.
 * Conventions: shared/materials/bsdf.h. */
#ifndef WP_SHARED_MATERIALS_ROUGHCONDUCTOR_H
#define WP_SHARED_MATERIALS_ROUGHCONDUCTOR_H

#include "shared/fresnel.h"
#include "shared/materials/bsdf.h"
#include "shared/materials/microfacet.h"
#include "shared/prelude.h"
#include "shared/sampling.h"

/* f for local directions wo, wi (z along ns). */
WP_FN vec3 roughconductor_eval_local(Microfacet m, vec3 eta, vec3 k, vec3 specular_reflectance, vec3 wo, vec3 wi) {
    vec3 h = v3_normalize(v3_add(wo, wi));
    real microfacets = microfacet_D(m, h) * microfacet_G(m, wo, wi, h) / (REAL(4.0) * wo.z * wi.z);
    vec3 f = v3_scale(v3_mul(specular_reflectance, fresnel_conductor(v3_dot(wo, h), eta, k)), microfacets);
    return v3_select(wo.z > REAL(0.0) && wi.z > REAL(0.0), f, make_vec3(REAL(0.0), REAL(0.0), REAL(0.0)));
}

/* f for the pair wo, wi (without the cosine). */
WP_FN vec3 roughconductor_eval(Microfacet m, vec3 eta, vec3 k, vec3 specular_reflectance, Frame frame, vec3 wo,
                               vec3 wi) {
    return roughconductor_eval_local(m, eta, k, specular_reflectance, frame_to_local(frame, wo),
                                     frame_to_local(frame, wi));
}

/* The density with which roughconductor_sample picks wi for local wo, wi. */
WP_FN real roughconductor_pdf_local(Microfacet m, vec3 wo, vec3 wi) {
    real pdf = microfacet_reflection_pdf(m, wo, v3_normalize(v3_add(wo, wi)));
    return wo.z > REAL(0.0) && wi.z > REAL(0.0) ? pdf : REAL(0.0);
}

/* The density with which roughconductor_sample picks wi. */
WP_FN real roughconductor_pdf(Microfacet m, Frame frame, vec3 wo, vec3 wi) {
    return roughconductor_pdf_local(m, frame_to_local(frame, wo), frame_to_local(frame, wi));
}

/* wo mirrored about a normal drawn from those visible from wo (u, v). Its
 * weight f wi.z / pdf reduces to specular_reflectance F(wo.h) G1(wi, h): D,
 * G1(wo, h) and the cosines cancel (as in Mitsuba 3's roughconductor with
 * visible-normal sampling). Where the reflection leaves below the shading
 * normal (or wo arrives from behind it), f is 0: the sample is invalid, with
 * weight and pdf 0 and the direction ns. */
WP_FN BsdfSample roughconductor_sample(Microfacet m, vec3 eta, vec3 k, vec3 specular_reflectance, vec3 nf, Frame frame,
                                       vec3 wo, real u, real v, int shading_normals) {
    vec3 wo_local = frame_to_local(frame, wo);
    vec3 h = microfacet_sample_visible(m, wo_local, u, v);
    vec3 wi_local = reflect_direction(v3_neg(wo_local), h);
    real pdf = microfacet_reflection_pdf(m, wo_local, h);
    lane_int reflects = wo_local.z > REAL(0.0) && wi_local.z > REAL(0.0) && pdf > REAL(0.0);
    vec3 weight = v3_scale(v3_mul(specular_reflectance, fresnel_conductor(v3_dot(wo_local, h), eta, k)),
                           microfacet_G1(m, wi_local, h));
    return glossy_reflection_sample(frame, wi_local, weight, pdf, reflects, nf, frame.normal, shading_normals);
}

#endif
