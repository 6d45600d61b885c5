/* SPPM's photons (docs/architecture.md, "Photon mapping"): how one leaves a
 * light, and what its scattering adds to the BSDF sample that camera paths
 * take too. The light, its point and the random numbers are the caller's
 * (the kernels read them per lane, the reference from its scene). */
#ifndef WP_SHARED_PHOTONS_H
#define WP_SHARED_PHOTONS_H

#include "shared/lights.h"
#include "shared/materials/bsdf.h"
#include "shared/offset.h"
#include "shared/prelude.h"
#include "shared/sampling.h"

typedef struct {
    vec3 origin;    /* offset off the light, on the side it leaves */
    vec3 direction; /* unit */
    vec3 flux;      /* what it carries: the light's power over the photon's density */
} EmittedPhoton;

/* A photon leaving the point `at` (error bound `point_error`, offset.h) of
 * a light of area `area`, chosen with probability `selection_pmf`, whose
 * material emits radiance `emission` from its front (the side at.normal
 * points to) or, `two_sided`, from both sides: u_side picks the side (each
 * with probability 1/2), then (u, v) a cosine-distributed direction about
 * that side's normal. The photon's flux is the emitted radiance over the
 * density of all those choices, L cos / (pmf / area * cos / pi) =
 * L pi area / pmf, twice that for a side chosen among two. */
WP_FN EmittedPhoton emit_photon(AreaPoint at, real point_error, real area, real selection_pmf, vec3 emission,
                                lane_int two_sided, real u_side, real u, real v) {
    lane_int back = two_sided && u_side >= REAL(0.5);
    vec3 side = v3_select(back, v3_neg(at.normal), at.normal);
    real sides = two_sided ? (real)REAL(2.0) : (real)REAL(1.0);
    EmittedPhoton photon;
    photon.direction = frame_to_world(frame_from_normal(side), sample_cosine_hemisphere(u, v));
    photon.origin = offset_ray_origin(at.point, side, point_error);
    photon.flux = v3_scale(emission, WP_PI * area * sides / selection_pmf);
    return photon;
}

/* A BSDF sample (shared/materials/) taken by a photon, which arrived back
 * along `wo` at a vertex of normals nf and ns: with shading normals its
 * weight takes the adjoint correction (shading_normal_adjoint). The
 * materials were sampled with WP_TRANSPORT_IMPORTANCE (refraction does not
 * compress flux). */
WP_FN BsdfSample photon_bsdf_sample(BsdfSample s, vec3 wo, vec3 nf, vec3 ns, int shading_normals) {
    real correction = shading_normals ? shading_normal_adjoint(wo, s.direction, nf, ns) : (real)REAL(1.0);
    s.weight = v3_scale(s.weight, correction);
    return s;
}

/* Whether a photon that hits a surface after `depth` scattering events goes
 * on: a deeper one could add to no visible point under max_depth
 * (photon_depth_counts, shared/sppm.h, with a visible point at depth 0). */
WP_FN lane_int photon_may_scatter(lane_uint depth, uint max_depth) { return depth + 2u <= max_depth; }

#endif
