/* Mitsuba 3's `normalmap` BSDF adapter: a texture, read raw, whose colour c
 * holds a shading normal n = 2 c - 1 in the tangent frame of the surface
 * (s, t, ns): ns the shading normal, s its surface's dp/du made orthogonal
 * to ns (Gram-Schmidt), t = ns x s, as Mitsuba's SurfaceInteraction
 * initialize_sh_frame builds it. The nested material is then evaluated and
 * sampled about the perturbed normal, which the kernels and the reference
 * put where the shading normal was (device/surface.h' vertex_at,
 * reference/path_tracer.h), times a shadow terminator term, as Mitsuba
 * 3.9's; the two normals' rule (leaves_on_side,
 * shared/materials/bsdf.h) still keeps every direction on the geometric
 * normal's side, so the perturbation cannot leak light through the
 * surface. dp/du per shape as Mitsuba's (shared/surface_tangents.h).
 * Mitsuba 3's `bumpmap` adapter (bump_mapped) shares the flip and the
 * terminator term; its normal is that of the surface raised along the
 * shading normal by a height texture, from dp/du and dp/dv. */
#ifndef WP_SHARED_NORMAL_MAP_H
#define WP_SHARED_NORMAL_MAP_H

#include "shared/prelude.h"
#include "shared/sampling.h"
#include "shared/surface_tangents.h"

/* A normal map's or bump map's shading normal at a hit, and the alpha^2 of
 * its shadow terminator term (0 where it has none). */
typedef struct {
    vec3 normal;
    real terminator_alpha2;
} NormalMapped;

/* What a normal map and a bump map share (Mitsuba 3.9's
 * src/bsdfs/normalmap_helpers.h, with a twosided outside): the perturbed
 * normal is tangential + z `side` in the unperturbed frame, where `side` is
 * the unperturbed shading normal turned to wo's side of the geometric
 * normal (a back face sees the front's frame mirrored: z negated, the
 * tangential part kept). Where wo lies below it (Mitsuba's
 * flip_invalid_normals, after Schuessler et al. 2017) its tangential part
 * is negated. A `flat` perturbation gives `side` exactly, a degenerate one
 * (zero length) `side` too. The terminator's alpha^2 is min(tan^2
 * theta_n / 8, 1) (`tan2`: tan^2 theta_n), Mitsuba's use_shadowing_function
 * (normal_map_terminator). */
WP_FN NormalMapped perturbed_normal(vec3 side, vec3 tangential, real z, real tan2, lane_int flat, vec3 wo) {
    vec3 up = v3_scale(side, z);
    vec3 perturbed = v3_add(tangential, up);
    lane_int flip = v3_dot(wo, side) * v3_dot(wo, perturbed) <= REAL(0.0);
    perturbed = v3_select(flip, v3_sub(up, tangential), perturbed);
    real length = v3_length(perturbed);
    lane_int keeps_side = flat || !(length > REAL(0.0));
    NormalMapped m;
    m.normal = v3_select(keeps_side, side, v3_scale(perturbed, REAL(1.0) / (keeps_side ? REAL(1.0) : length)));
    m.terminator_alpha2 = keeps_side ? REAL(0.0) : fmin(REAL(0.125) * tan2, REAL(1.0));
    return m;
}

/* The shading normal a normal map's texel `colour` gives a hit reached from
 * wo (pointing away from the surface): n = 2 c - 1 in the frame (s, t,
 * side), where (s, t, ns) is frame_along(ns, dp_du) about the unperturbed
 * shading normal ns (frame_from_normal's tangent where dp_du is zero or
 * along ns), and `side` is ns turned to wo's side of the geometric normal
 * (perturbed_normal does the rest). A flat texel (n = (0, 0, z), z > 0)
 * gives `side` exactly. */
WP_FN NormalMapped normal_mapped(vec3 ns, vec3 side, vec3 dp_du, vec3 colour, vec3 wo) {
    vec3 n =
        make_vec3(REAL(2.0) * colour.x - REAL(1.0), REAL(2.0) * colour.y - REAL(1.0), REAL(2.0) * colour.z - REAL(1.0));
    Frame frame = frame_along(ns, dp_du, frame_from_normal(ns).tangent);
    vec3 tangential = v3_add(v3_scale(frame.tangent, n.x), v3_scale(frame.bitangent, n.y));
    real tan2 = (n.x * n.x + n.y * n.y) / (n.z * n.z);
    return perturbed_normal(side, tangential, n.z, tan2, n.x == REAL(0.0) && n.y == REAL(0.0) && n.z > REAL(0.0), wo);
}

/* The shading normal Mitsuba 3.9's bumpmap gives a hit reached from wo
 * whose height texture has the uv gradient (g_u, g_v) there (already times
 * the map's scale; texture_gradient): the surface's dp/du and dp/dv, each
 * moved along the unperturbed shading normal ns to the height's slope
 * (dp/du + ns (g_u - ns . dp/du)), span the bumped surface, whose normal
 * (their cross product) is turned to the geometric normal `geometric`'s
 * side; perturbed_normal then mirrors it to wo's side (`side`), flips it
 * where wo lies below it and gives its terminator term. A zero gradient (a
 * constant height) gives `side` exactly. */
WP_FN NormalMapped bump_mapped(vec3 geometric, vec3 ns, vec3 side, vec3 dp_du, vec3 dp_dv, real g_u, real g_v,
                               vec3 wo) {
    vec3 du = v3_add(dp_du, v3_scale(ns, g_u - v3_dot(ns, dp_du)));
    vec3 dv = v3_add(dp_dv, v3_scale(ns, g_v - v3_dot(ns, dp_dv)));
    vec3 n = v3_cross(du, dv);
    n = v3_select(v3_dot(geometric, n) < REAL(0.0), v3_neg(n), n);
    real z = v3_dot(n, ns);
    vec3 tangential = v3_sub(n, v3_scale(ns, z));
    real tan2 = v3_dot(tangential, tangential) / (z * z);
    return perturbed_normal(side, tangential, z, tan2, g_u == REAL(0.0) && g_v == REAL(0.0), wo);
}

/* Estevez, Lecocq and Stein's shadowing of a bumped surface's terminator
 * (Ray Tracing Gems, 2019), as Mitsuba's normalmap multiplies the nested
 * BSDF's value and sample weight by it: 2 / (1 + sqrt(1 + alpha^2 tan^2
 * theta)), theta the angle of the outgoing direction w from the unperturbed
 * shading normal ns; exactly 1 where alpha^2 is 0 (no normal map, or a flat
 * texel). */
WP_FN real normal_map_terminator(real alpha2, vec3 ns, vec3 w) {
    real c = v3_dot(w, ns);
    real tan2 = fmax(REAL(1.0) - c * c, REAL(0.0)) / (c * c);
    real shadowing = REAL(2.0) / (REAL(1.0) + sqrt(REAL(1.0) + alpha2 * tan2));
    return alpha2 > REAL(0.0) ? shadowing : REAL(1.0);
}

/* Whether a path arriving from wo (pointing away from the surface) at a
 * normal-mapped point with perturbed shading normal ns is scattered at all:
 * Mitsuba's nested BSDF sees wo in the perturbed frame and is black where
 * it lies below it (after the flip above, only where the map's normal
 * points into the surface). */
WP_FN lane_int normal_map_shades(vec3 wo, vec3 ns) { return v3_dot(wo, ns) > REAL(0.0); }

#endif
