/* Each shape's dp/du and dp/dv as Mitsuba 3's compute_surface_interaction
 * gives them: a sphere's azimuthal and polar tangents, a quad's edge1 and
 * edge2 (Mitsuba's rectangle's +x and +y), a mesh triangle's from its
 * vertex uvs (a mesh without uvs has the barycentric ones, (0, 0), (1, 0),
 * (0, 1): dp/du = p1 - p0, as Mitsuba's). Their uses: the tangent frame of
 * a normal map and the surface a bump map raises (shared/normal_map.h), and
 * the direction of an anisotropic roughness' alpha_u
 * (shared/materials/microfacet.h' microfacet_frame). */
#ifndef WP_SHARED_SURFACE_TANGENTS_H
#define WP_SHARED_SURFACE_TANGENTS_H

#include "shared/prelude.h"

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

#endif
