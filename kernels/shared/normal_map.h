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
 * surface. dp/du per shape as Mitsuba's: a sphere's azimuthal tangent, a
 * quad's edge1 (Mitsuba's rectangle's +x), a triangle's from its vertex
 * uvs. */
#ifndef WP_SHARED_NORMAL_MAP_H
#define WP_SHARED_NORMAL_MAP_H

#include "shared/prelude.h"
#include "shared/sampling.h"

/* dp/du of Mitsuba's sphere at unit normal `normal` (u the azimuth about
 * +z in turns): along (-y, x, 0); zero at the poles. */
WP_FN vec3 sphere_dp_du(vec3 normal) { return make_vec3(-normal.y, normal.x, REAL(0.0)); }

/* dp/du of the triangle p0 p1 p2 with vertex uvs (u0, v0), (u1, v1), (u2,
 * v2): the solution of dp = dp/du du + dp/dv dv along its two edges from
 * p0; zero where the uvs are degenerate. */
WP_FN vec3 triangle_dp_du(vec3 p0, vec3 p1, vec3 p2, real u0, real v0, real u1, real v1, real u2, real v2) {
    real du1 = u1 - u0, dv1 = v1 - v0, du2 = u2 - u0, dv2 = v2 - v0;
    real det = du1 * dv2 - dv1 * du2;
    vec3 dp_du = v3_sub(v3_scale(v3_sub(p1, p0), dv2), v3_scale(v3_sub(p2, p0), dv1));
    return v3_scale(dp_du, det != REAL(0.0) ? REAL(1.0) / det : REAL(0.0));
}

/* A normal map's shading normal at a hit, and the alpha^2 of its shadow
 * terminator term (0 where it has none). */
typedef struct {
    vec3 normal;
    real terminator_alpha2;
} NormalMapped;

/* The shading normal a normal map's texel `colour` gives a hit reached from
 * wo (pointing away from the surface): n = 2 c - 1 in the frame (s, t,
 * side), where s is dp_du made orthogonal to the unperturbed shading normal
 * ns (frame_from_normal's tangent where dp_du is zero or along ns),
 * t = ns x s, and `side` is ns turned to wo's side of the geometric normal.
 * Mitsuba 3.9's normalmap (src/bsdfs/normalmap_helpers.h) with a twosided
 * outside: a back face is the front's frame mirrored (z negated, s and t
 * kept), and where wo lies below n (its flip_invalid_normals, after
 * Schuessler et al. 2017) n's tangential part is negated. A flat texel
 * (n = (0, 0, z), z > 0) gives `side` exactly, a degenerate one (n = 0)
 * `side` too. The terminator's alpha^2 is min(tan^2 theta_n / 8, 1), its
 * use_shadowing_function (normal_map_terminator). */
WP_FN NormalMapped normal_mapped(vec3 ns, vec3 side, vec3 dp_du, vec3 colour, vec3 wo) {
    vec3 n =
        make_vec3(REAL(2.0) * colour.x - REAL(1.0), REAL(2.0) * colour.y - REAL(1.0), REAL(2.0) * colour.z - REAL(1.0));
    vec3 tangent = v3_sub(dp_du, v3_scale(ns, v3_dot(ns, dp_du)));
    real tangent_length = v3_length(tangent);
    lane_int has_tangent = tangent_length > REAL(0.0);
    vec3 s = v3_select(has_tangent, v3_scale(tangent, REAL(1.0) / (has_tangent ? tangent_length : REAL(1.0))),
                       frame_from_normal(ns).tangent);
    vec3 tangential = v3_add(v3_scale(s, n.x), v3_scale(v3_cross(ns, s), n.y));
    vec3 up = v3_scale(side, n.z);
    vec3 perturbed = v3_add(tangential, up);
    lane_int flip = v3_dot(wo, side) * v3_dot(wo, perturbed) <= REAL(0.0);
    perturbed = v3_select(flip, v3_sub(up, tangential), perturbed);
    real length = v3_length(perturbed);
    lane_int keeps_side = (n.x == REAL(0.0) && n.y == REAL(0.0) && n.z > REAL(0.0)) || !(length > REAL(0.0));
    NormalMapped m;
    m.normal = v3_select(keeps_side, side, v3_scale(perturbed, REAL(1.0) / (keeps_side ? REAL(1.0) : length)));
    real tan2 = (n.x * n.x + n.y * n.y) / (n.z * n.z);
    m.terminator_alpha2 = keeps_side ? REAL(0.0) : fmin(REAL(0.125) * tan2, REAL(1.0));
    return m;
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
