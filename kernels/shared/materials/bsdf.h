/* What every material's functions share (shared/materials/diffuse.h,
 * mirror.h, glass.h): the sample they return, how lanes choose between
 * kinds, and the two normals' rule.
 *
 * Conventions, the same for a path from the camera and for one from a light
 * (a photon): directions are unit vectors pointing away from the surface; `wo`
 * points back along the path (to where it came from) and a sample's
 * `direction` is where it goes next. `nf` is the geometric normal and `ns` the
 * shading normal, both turned to wo's side by the geometric test (the side the
 * path arrived on). Nothing here knows which end of the path is the camera
 * except where `transport` says what the path carries. */
#ifndef WP_SHARED_MATERIALS_BSDF_H
#define WP_SHARED_MATERIALS_BSDF_H

#include "shared/prelude.h"
#include "shared/sampling.h"

/* What a path carries, where a material's weight depends on it (pbrt-v4's
 * TransportMode): radiance (a path from the camera) or importance and flux (a
 * path from a light). Refraction compresses radiance by 1/eta^2, not flux. */
#define WP_TRANSPORT_RADIANCE 0u
#define WP_TRANSPORT_IMPORTANCE 1u

typedef struct {
    vec3 direction;   /* where the path goes next (unit) */
    vec3 weight;      /* f * cos / pdf: the path's throughput factor */
    vec3 leave_side;  /* the geometric normal on the side `direction` leaves into: where the next ray starts */
    real pdf;         /* solid-angle density of `direction`; 0 for a specular (delta) lobe */
    real eta_squared; /* eta^2 of a refraction, else 1 (roulette_outcome's eta_scale) */
    lane_uint specular;
    lane_int valid; /* the sample is consistent with both normals (leaves_on_side): else the path ends */
} BsdfSample;

/* The random numbers one BSDF sample takes: glass's choice of lobe and
 * the diffuse direction (u, v). A camera path draws them from DIM_BSDF_*, a
 * photon from DIM_PHOTON_BSDF_* (shared/rng.h). */
typedef struct {
    real lobe, u, v;
} BsdfRandom;

/* No sample: a lane whose material has no kind compiled in keeps this. */
WP_FN BsdfSample no_bsdf_sample(void) {
    BsdfSample s;
    s.direction = s.weight = s.leave_side = make_vec3(REAL(0.0), REAL(0.0), REAL(0.0));
    s.pdf = REAL(0.0);
    s.eta_squared = REAL(1.0);
    s.specular = 0u;
    s.valid = 0;
    return s;
}

WP_FN BsdfSample select_bsdf_sample(lane_int choose_a, BsdfSample a, BsdfSample b) {
    BsdfSample s;
    s.direction = v3_select(choose_a, a.direction, b.direction);
    s.weight = v3_select(choose_a, a.weight, b.weight);
    s.leave_side = v3_select(choose_a, a.leave_side, b.leave_side);
    s.pdf = choose_a ? a.pdf : b.pdf;
    s.eta_squared = choose_a ? a.eta_squared : b.eta_squared;
    s.specular = choose_a ? a.specular : b.specular;
    s.valid = choose_a ? a.valid : b.valid;
    return s;
}

/* A surface point's two normals turned to the side a path arrives on, and
 * whether that is the front (the side the geometric normal points to). The
 * geometric normal alone decides the side: the shading normal is turned with
 * it (shared/triangle.h keeps it on the geometric normal's side). */
typedef struct {
    lane_int front;
    vec3 nf, ns;
} FacingNormals;

/* For a path arriving along `direction` at a point of geometric normal
 * `normal` and shading normal `shading`. */
WP_FN FacingNormals normals_facing(vec3 direction, vec3 normal, vec3 shading) {
    FacingNormals f;
    f.front = v3_dot(direction, normal) < REAL(0.0);
    f.nf = v3_select(f.front, normal, v3_neg(normal));
    f.ns = v3_select(f.front, shading, v3_neg(shading));
    return f;
}

/* Whether `direction` leaves on the side `normal` points to. Shading normals
 * bend directions but only the geometric normal says where a ray really goes:
 * a direction sampled or reflected about ns that points into the surface as
 * nf sees it, or a path arriving from behind ns at a specular surface, ends
 * the path (as in Mitsuba 3 and pbrt-v4's treatment of the two normals):
 * continuing would leak light through the surface or shade from the wrong
 * side. Without shading normals (`shading_normals` 0, the same for every
 * lane) ns is nf and every such test passes. */
WP_FN lane_int leaves_on_side(vec3 direction, vec3 normal, int shading_normals) {
    return !shading_normals || v3_dot(direction, normal) > REAL(0.0);
}

/* Veach's correction for shading normals on a path that carries importance
 * or flux (a photon; thesis section 5.3.2): such a path's throughput at a
 * vertex where the shading normal ns differs from the geometric normal nf
 * takes |wo.ns| |wi.nf| / (|wo.nf| |wi.ns|) besides the BSDF sample's
 * weight, where wo points back along the path and wi is where it goes next;
 * otherwise light paths and camera paths would estimate different
 * equations, and a photon map would disagree with path tracing wherever
 * shading normals lean. 0 where a direction grazes the geometric surface. */
WP_FN real shading_normal_adjoint(vec3 wo, vec3 wi, vec3 nf, vec3 ns) {
    real numerator = fabs(v3_dot(wo, ns)) * fabs(v3_dot(wi, nf));
    real denominator = fabs(v3_dot(wo, nf)) * fabs(v3_dot(wi, ns));
    return denominator > REAL(0.0) ? numerator / denominator : REAL(0.0);
}

/* A glossy reflection sampled in the shading frame (roughconductor,
 * roughplastic): wi_local with its weight (f cos / pdf) and pdf, where
 * `reflects` says that wo and wi are above the surface and the density is
 * positive; else no direction, and the path ends. */
WP_FN BsdfSample glossy_reflection_sample(Frame frame, vec3 wi_local, vec3 weight, real pdf, lane_int reflects, vec3 nf,
                                          vec3 ns, int shading_normals) {
    BsdfSample s;
    s.direction = v3_select(reflects, frame_to_world(frame, wi_local), ns);
    s.weight = v3_select(reflects, weight, make_vec3(REAL(0.0), REAL(0.0), REAL(0.0)));
    s.leave_side = nf;
    s.pdf = reflects ? pdf : REAL(0.0);
    s.eta_squared = REAL(1.0);
    s.specular = 0u;
    s.valid = reflects && leaves_on_side(s.direction, nf, shading_normals);
    return s;
}

#endif
