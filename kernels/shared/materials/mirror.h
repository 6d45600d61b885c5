/* The mirror material: perfect specular reflection about the shading normal,
 * tinted by `reflectance`. Its lobe is a delta: f and the density of a given
 * pair of directions are 0 (the sample's pdf is 0, which no strategy but
 * following the reflection can find, so next-event estimation skips mirror
 * vertices and emission seen after one counts in full). Conventions:
 * shared/materials/bsdf.h. */
#ifndef WP_SHARED_MATERIALS_MIRROR_H
#define WP_SHARED_MATERIALS_MIRROR_H

#include "shared/fresnel.h"
#include "shared/materials/bsdf.h"
#include "shared/prelude.h"

WP_FN BsdfSample mirror_sample(vec3 reflectance, vec3 wo, vec3 nf, vec3 ns, int shading_normals) {
    BsdfSample s;
    s.direction = reflect_direction(v3_neg(wo), ns);
    s.weight = reflectance;
    s.leave_side = nf;
    s.pdf = REAL(0.0);
    s.eta_squared = REAL(1.0);
    s.specular = 1u;
    s.valid = leaves_on_side(wo, ns, shading_normals) && leaves_on_side(s.direction, nf, shading_normals);
    return s;
}

#endif
