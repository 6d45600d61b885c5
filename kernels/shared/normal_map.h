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
 * uvs. Mitsuba 3's `bumpmap` adapter (bump_mapped) shares the flip and the
 * terminator term; its normal is that of the surface raised along the
 * shading normal by a height texture, from dp/du and dp/dv (a quad's edge1
 * and edge2, sphere_tangents, triangle_dp_du and triangle_dp_dv). */
#ifndef WP_SHARED_NORMAL_MAP_H
#define WP_SHARED_NORMAL_MAP_H

#include "shared/prelude.h"
#include "shared/sampling.h"

/* dp/du of Mitsuba's sphere at unit normal `normal` (u the azimuth about
 * +z in turns): along (-y, x, 0); zero at the poles. */
WP_FN vec3 sphere_dp_du(vec3 normal) { return make_vec3(-normal.y, normal.x, REAL(0.0)); }

/* A surface's dp/du and dp/dv at a point, to their length (a bump map's
 * slope is per unit of uv). */
typedef struct {
    vec3 dp_du, dp_dv;
} SurfaceTangents;

/* Mitsuba's sphere's at unit normal `normal` on a sphere of `radius`: u the
 * azimuth in turns, 2 pi r (-y, x, 0); v the polar angle over pi,
 * pi r (z cos phi, z sin phi, -rho), rho = sqrt(x^2 + y^2), and (1, 0, 0)
 * there at the poles, as Mitsuba's. */
WP_FN SurfaceTangents sphere_tangents(vec3 normal, real radius) {
    real rho = sqrt(normal.x * normal.x + normal.y * normal.y);
    lane_int pole = rho == REAL(0.0);
    real inv_rho = REAL(1.0) / (pole ? REAL(1.0) : rho);
    vec3 dp_dv = make_vec3(normal.z * normal.x * inv_rho, normal.z * normal.y * inv_rho, -rho);
    SurfaceTangents t;
    t.dp_du = v3_scale(sphere_dp_du(normal), REAL(2.0) * WP_PI * radius);
    t.dp_dv = v3_scale(v3_select(pole, make_vec3(REAL(1.0), REAL(0.0), REAL(0.0)), dp_dv), WP_PI * radius);
    return t;
}

/* dp/du of the triangle p0 p1 p2 with vertex uvs (u0, v0), (u1, v1), (u2,
 * v2): the solution of dp = dp/du du + dp/dv dv along its two edges from
 * p0; zero where the uvs are degenerate. */
WP_FN vec3 triangle_dp_du(vec3 p0, vec3 p1, vec3 p2, real u0, real v0, real u1, real v1, real u2, real v2) {
    real du1 = u1 - u0, dv1 = v1 - v0, du2 = u2 - u0, dv2 = v2 - v0;
    real det = du1 * dv2 - dv1 * du2;
    vec3 dp_du = v3_sub(v3_scale(v3_sub(p1, p0), dv2), v3_scale(v3_sub(p2, p0), dv1));
    return v3_scale(dp_du, det != REAL(0.0) ? REAL(1.0) / det : REAL(0.0));
}

/* dp/dv of the same triangle (triangle_dp_du's other unknown); zero too
 * where the uvs are degenerate, so that a bump map leaves such a triangle's
 * normal (Mitsuba takes an arbitrary frame there). */
WP_FN vec3 triangle_dp_dv(vec3 p0, vec3 p1, vec3 p2, real u0, real v0, real u1, real v1, real u2, real v2) {
    real du1 = u1 - u0, dv1 = v1 - v0, du2 = u2 - u0, dv2 = v2 - v0;
    real det = du1 * dv2 - dv1 * du2;
    vec3 dp_dv = v3_sub(v3_scale(v3_sub(p2, p0), du1), v3_scale(v3_sub(p1, p0), du2));
    return v3_scale(dp_dv, det != REAL(0.0) ? REAL(1.0) / det : REAL(0.0));
}

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
 * side), where s is dp_du made orthogonal to the unperturbed shading normal
 * ns (frame_from_normal's tangent where dp_du is zero or along ns),
 * t = ns x s, and `side` is ns turned to wo's side of the geometric normal
 * (perturbed_normal does the rest). A flat texel (n = (0, 0, z), z > 0)
 * gives `side` exactly. */
WP_FN NormalMapped normal_mapped(vec3 ns, vec3 side, vec3 dp_du, vec3 colour, vec3 wo) {
    vec3 n =
        make_vec3(REAL(2.0) * colour.x - REAL(1.0), REAL(2.0) * colour.y - REAL(1.0), REAL(2.0) * colour.z - REAL(1.0));
    vec3 tangent = v3_sub(dp_du, v3_scale(ns, v3_dot(ns, dp_du)));
    real tangent_length = v3_length(tangent);
    lane_int has_tangent = tangent_length > REAL(0.0);
    vec3 s = v3_select(has_tangent, v3_scale(tangent, REAL(1.0) / (has_tangent ? tangent_length : REAL(1.0))),
                       frame_from_normal(ns).tangent);
    vec3 tangential = v3_add(v3_scale(s, n.x), v3_scale(v3_cross(ns, s), n.y));
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
