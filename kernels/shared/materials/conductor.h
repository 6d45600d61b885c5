/* The smooth conductor (Mitsuba 3's `conductor`): mirror reflection about the
 * shading normal, weighted by the conductor's exact Fresnel reflectance for
 * its complex index eta + i k per colour channel (shared/fresnel.h) and by
 * `specular_reflectance`. A perfect mirror (Mitsuba's material "none") is
 * eta = 0, k = 1, whose reflectance is exactly 1. Its lobe is a delta, as the
 * mirror's (shared/materials/mirror.h, of which it is the general case).
 * Conventions: shared/materials/bsdf.h. */
#ifndef WP_SHARED_MATERIALS_CONDUCTOR_H
#define WP_SHARED_MATERIALS_CONDUCTOR_H

#include "shared/fresnel.h"
#include "shared/materials/bsdf.h"
#include "shared/materials/mirror.h"
#include "shared/prelude.h"

WP_FN BsdfSample conductor_sample(vec3 eta, vec3 k, vec3 specular_reflectance, vec3 wo, vec3 nf, vec3 ns,
                                  int shading_normals) {
    vec3 reflectance = v3_mul(specular_reflectance, fresnel_conductor(v3_dot(wo, ns), eta, k));
    return mirror_sample(reflectance, wo, nf, ns, shading_normals);
}

#endif
