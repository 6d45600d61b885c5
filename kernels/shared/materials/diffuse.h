/* The diffuse (Lambertian) material: f = albedo / pi on the shading
 * normal's side. Its directions are sampled from the cosine-weighted
 * hemisphere about ns or, with `uniform_hemisphere` (render.hemisphere
 * "uniform"; the same for every lane), from the uniform one. Conventions:
 * shared/materials/bsdf.h. */
#ifndef WP_SHARED_MATERIALS_DIFFUSE_H
#define WP_SHARED_MATERIALS_DIFFUSE_H

#include "shared/materials/bsdf.h"
#include "shared/prelude.h"
#include "shared/sampling.h"

/* The solid-angle density with which diffuse_sample picks a direction at
 * cosine `cos_theta` from ns: cos / pi, or 1 / (2 pi) on the hemisphere. */
WP_FN real diffuse_pdf_at_cosine(real cos_theta, int uniform_hemisphere) {
    real uniform_pdf = cos_theta >= REAL(0.0) ? uniform_hemisphere_pdf() : REAL(0.0);
    return uniform_hemisphere ? uniform_pdf : cosine_hemisphere_pdf(cos_theta);
}

/* The density of diffuse_sample's direction wi. */
WP_FN real diffuse_pdf(vec3 ns, vec3 wi, int uniform_hemisphere) {
    return diffuse_pdf_at_cosine(v3_dot(wi, ns), uniform_hemisphere);
}

/* f for the direction wi: albedo / pi above ns, 0 below. f does not depend on
 * where the path came from. The material is linear in its albedo, so a path's
 * throughput times the albedo gives the throughput times f (next-event
 * estimation's order of operations). */
WP_FN vec3 diffuse_eval(vec3 albedo, vec3 ns, vec3 wi) {
    return v3_select(v3_dot(wi, ns) > REAL(0.0), v3_scale(albedo, WP_INV_PI),
                     make_vec3(REAL(0.0), REAL(0.0), REAL(0.0)));
}

/* A direction about ns from the random numbers u and v. Its weight is
 * f cos / pdf: the albedo for cosine sampling, albedo * 2 cos for uniform. */
WP_FN BsdfSample diffuse_sample(vec3 albedo, vec3 nf, vec3 ns, real u, real v, int uniform_hemisphere,
                                int shading_normals) {
    /* `local` is an OpenCL keyword */
    vec3 in_frame = uniform_hemisphere ? sample_uniform_hemisphere(u, v) : sample_cosine_hemisphere(u, v);
    BsdfSample s;
    s.weight = uniform_hemisphere ? v3_scale(albedo, REAL(2.0) * in_frame.z) : albedo;
    s.direction = frame_to_world(frame_from_normal(ns), in_frame);
    s.leave_side = nf;
    s.pdf = diffuse_pdf_at_cosine(in_frame.z, uniform_hemisphere);
    s.eta_squared = REAL(1.0);
    s.specular = 0u;
    s.valid = leaves_on_side(s.direction, nf, shading_normals);
    return s;
}

#endif
