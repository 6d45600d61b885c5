/* The glass material: a smooth dielectric of index `ior` (outside 1), which
 * reflects with the exact Fresnel probability and refracts otherwise. Both
 * lobes are deltas (see shared/materials/mirror.h): f and the density of a
 * given pair of directions are 0. Conventions: shared/materials/bsdf.h. */
#ifndef WP_SHARED_MATERIALS_GLASS_H
#define WP_SHARED_MATERIALS_GLASS_H

#include "shared/fresnel.h"
#include "shared/materials/bsdf.h"
#include "shared/prelude.h"

/* `entering`: the path arrives from outside (wo on the side of the outward
 * geometric normal). u_lobe picks reflection (u_lobe < Fresnel reflectance)
 * or refraction; total internal reflection always reflects. Each lobe's weight
 * is then 1, except that a refraction compresses radiance by 1/eta^2
 * (`transport` WP_TRANSPORT_RADIANCE) while flux passes unscaled
 * (WP_TRANSPORT_IMPORTANCE). */
WP_FN BsdfSample glass_sample(real ior, lane_int entering, vec3 wo, vec3 nf, vec3 ns, real u_lobe, uint transport,
                              int shading_normals) {
    vec3 d = v3_neg(wo); /* the direction the path arrived along */
    real eta = entering ? ior : REAL(1.0) / ior;
    real reflectance = fresnel_dielectric(-v3_dot(d, ns), eta);
    vec3 refracted = d; /* overwritten where refract_direction runs (one lane: where u_lobe allows it) */
    lane_int refracts = u_lobe >= reflectance && refract_direction(d, ns, eta, &refracted);
    BsdfSample s;
    s.specular = 1u;
    s.pdf = REAL(0.0);
    s.eta_squared = refracts ? eta * eta : REAL(1.0);
    s.direction = v3_select(refracts, refracted, reflect_direction(d, ns));
    s.weight = v3_div(make_vec3(REAL(1.0), REAL(1.0), REAL(1.0)),
                      refracts && transport == WP_TRANSPORT_RADIANCE ? eta * eta : REAL(1.0));
    s.leave_side = v3_select(refracts, v3_neg(nf), nf);
    s.valid = leaves_on_side(wo, ns, shading_normals) && leaves_on_side(s.direction, s.leave_side, shading_normals);
    return s;
}

#endif
