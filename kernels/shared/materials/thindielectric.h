/* The thin dielectric (Mitsuba 3's `thindielectric`): a slab of index `ior`
 * too thin to shift a ray, such as a window pane. Light reflects off its two
 * faces, and what enters leaves on the far side undeflected. Summing the
 * internal bounces R + T^2 R (1 + R^2 + R^4 + ...) with T = 1 - R gives the
 * slab's reflectance 2 R / (1 + R), R the Fresnel reflectance of one face at
 * wo's angle (the same from either side). u_lobe picks reflection (u_lobe
 * below that reflectance) or transmission straight through; each weighs 1.
 * Both lobes are deltas. Conventions: shared/materials/bsdf.h. */
#ifndef WP_SHARED_MATERIALS_THINDIELECTRIC_H
#define WP_SHARED_MATERIALS_THINDIELECTRIC_H

#include "shared/fresnel.h"
#include "shared/materials/bsdf.h"
#include "shared/prelude.h"

/* The slab's reflectance at incidence cos_theta (>= 0). */
WP_FN real thindielectric_reflectance(real cos_theta, real ior) {
    real face = fresnel_dielectric(cos_theta, ior);
    return REAL(2.0) * face / (REAL(1.0) + face);
}

WP_FN BsdfSample thindielectric_sample(real ior, vec3 wo, vec3 nf, vec3 ns, real u_lobe, int shading_normals) {
    lane_int reflects = u_lobe < thindielectric_reflectance(fabs(v3_dot(wo, ns)), ior);
    BsdfSample s;
    s.direction = v3_select(reflects, reflect_direction(v3_neg(wo), ns), v3_neg(wo));
    s.weight = make_vec3(REAL(1.0), REAL(1.0), REAL(1.0));
    s.leave_side = v3_select(reflects, nf, v3_neg(nf));
    s.pdf = REAL(0.0);
    s.eta_squared = REAL(1.0);
    s.specular = 1u;
    s.valid = leaves_on_side(wo, ns, shading_normals) && leaves_on_side(s.direction, s.leave_side, shading_normals);
    return s;
}

#endif
