/* The surface point where a ray hit a shape, its geometric normal, and a
 * bound on the point's distance from the true surface (the `error` that
 * offset_ray_origin, shared/offset.h, moves spawned rays by), for each kind
 * of shape. Each bound is derived for the formulas that compute the point,
 * in the manner of pbrt-v4 (Pharr, Jakob and Humphreys, 4th ed., section
 * 6.8) with Higham's gamma(n) (shared/offset.h), and evaluated from the
 * actual quantities of the hit, not from the shape's magnitude, so that it
 * stays within a small factor of the worst error measured
 * (tests/shared/hit_point_test.cpp). u is the unit roundoff of the
 * precision compiled for; n the unit normal; abs_dot(a, n) = sum |a_i| |n_i|
 * is what per-component errors |a_i| delta_i, |delta_i| <= u, add up to
 * along n (at most |a|, when a is along n). Every bound is first order in
 * u: gamma(n) = n u / (1 - n u) exceeds n u by the second-order terms and
 * by the rounding of the bound's own evaluation. */
#ifndef WP_SHARED_HIT_POINT_H
#define WP_SHARED_HIT_POINT_H

#include "shared/geometry.h"
#include "shared/offset.h"
#include "shared/prelude.h"
#include "shared/triangle.h"

typedef struct {
    vec3 point;
    vec3 normal; /* unit geometric normal: outward (sphere), the plane's, edge1 x edge2 (quad), the front (triangle) */
    real error;  /* bound on the point's distance from the surface */
} HitPoint;

WP_FN HitPoint select_hit_point(lane_int choose_a, HitPoint a, HitPoint b) {
    HitPoint h;
    h.point = v3_select(choose_a, a.point, b.point);
    h.normal = v3_select(choose_a, a.normal, b.normal);
    h.error = choose_a ? a.error : b.error;
    return h;
}

/* Sphere: origin + t direction is moved back onto the sphere
 * (sphere_reproject), which forgets the error of t (large for huge spheres:
 * the root cancels at the magnitude of the centre). What remains:
 * d = p - center rounds per component, which turns d but not the length
 * the next steps give it; |d|^2 errs by gamma(3) (three positive terms), its
 * square root by gamma(3)/2 + u, s = r / |d| by another u and d s by u per
 * component, so |d s| = r (1 +- 4.5 u); then center + d s rounds by u per
 * component, u abs_dot(p, n) along n. Distance from the sphere <=
 * gamma(5) r + gamma(1) abs_dot(p, n): ulp(r)-sized for a radius-1e5 wall
 * of a small room, not ulp(|center| + r). */
WP_FN HitPoint sphere_hit(vec3 center, real radius, vec3 origin, vec3 direction, real t) {
    HitPoint h;
    h.point = sphere_reproject(center, radius, v3_add_scaled(origin, t, direction));
    h.normal = sphere_normal(center, h.point);
    h.error = rounding_gamma(REAL(5.0)) * radius + rounding_gamma(REAL(1.0)) * abs_dot(h.point, h.normal);
    return h;
}

/* Plane through `anchor` with unit normal n, met at t = num / den,
 * num = dot(anchor - origin, n), den = dot(n, direction) (intersect_plane).
 * anchor - origin rounds by u per component and the dot product by gamma(3),
 * so num errs by gamma(4) abs_dot(anchor - origin, n); den errs by
 * gamma(3) abs_dot(direction, n), which moves the point along the ray by a
 * relative error/den of t, off the plane by gamma(3) t abs_dot(direction, n)
 * whatever the incidence; the division rounds t by u (u t |cos| off the
 * plane), t direction by u per component (u t abs_dot(direction, n)) and
 * origin + t direction by u per component (u abs_dot(p, n)). Distance <=
 * gamma(4) abs_dot(anchor - origin, n) + gamma(5) t abs_dot(direction, n)
 * + gamma(1) abs_dot(p, n). */
WP_FN HitPoint plane_hit(vec3 anchor, vec3 normal, vec3 origin, vec3 direction, real t) {
    HitPoint h;
    h.point = v3_add_scaled(origin, t, direction);
    h.normal = normal;
    h.error = rounding_gamma(REAL(4.0)) * abs_dot(v3_sub(anchor, origin), normal) +
              rounding_gamma(REAL(5.0)) * t * abs_dot(direction, normal) +
              rounding_gamma(REAL(1.0)) * abs_dot(h.point, normal);
    return h;
}

/* edge1 x edge2 with every product taken positive: component i bounds what
 * the two products of the cross product's component i add up to. */
WP_FN vec3 abs_cross(vec3 a, vec3 b) {
    vec3 p = v3_abs(a), q = v3_abs(b);
    return make_vec3(p.y * q.z + p.z * q.y, p.z * q.x + p.x * q.z, p.x * q.y + p.y * q.x);
}

/* Quad: the plane test with the normal N = edge1 x edge2 as computed
 * (intersect_quad_plane), plus that plane's tilt against the quad's true
 * plane: component i of N errs by gamma(2) abs_cross(edge1, edge2)_i (two
 * products and a difference), which turns the plane about the corner by up
 * to that over |N| and moves a point p of it off the true plane by up to
 * gamma(2) abs_dot(p - corner, abs_cross(edge1, edge2)) / |N| (zero for
 * axis-aligned edges, whose cross product is exact). */
WP_FN HitPoint quad_hit(vec3 corner, vec3 edge1, vec3 edge2, vec3 origin, vec3 direction, real t) {
    real area = v3_length(v3_cross(edge1, edge2));
    HitPoint h = plane_hit(corner, quad_normal(edge1, edge2), origin, direction, t);
    h.error = h.error + rounding_gamma(REAL(2.0)) * abs_dot(v3_sub(h.point, corner), abs_cross(edge1, edge2)) / area;
    return h;
}

/* Triangle: the point is interpolated from the barycentric coordinates
 * b_i = e_i / det of the watertight test (pbrt-v4, section 6.8.6), not
 * origin + t direction, so its error does not grow with t. Whatever error
 * the edge functions carry only moves the point within the triangle's
 * plane, dot(x, n) = c, as long as the weights sum to 1. They do to
 * gamma(4): det sums three numbers of one sign (gamma(2)) and
 * b_i = e_i (1 / det) rounds twice, and weights b_i (1 + eps_i) put the
 * point off the plane by sum b_i eps_i c, at most gamma(4) |c|. The
 * interpolation (b0 p0 + b1 p1) + b2 p2 rounds each w_i = b_i p_i, then the
 * two sums: at most u (|w0| + |w1| + |w2|) + u (|w0| + |w1|) + u |p| per
 * component. Distance from the plane <= gamma(4) |dot(p, n)| +
 * gamma(3) abs_dot(|w0| + |w1| + |w2|, n) (pbrt bounds both by
 * gamma(7) sum |b_i p_i| per component). */
WP_FN HitPoint triangle_hit(vec3 p0, vec3 p1, vec3 p2, vec3 origin, vec3 direction) {
    TriangleEdges e = triangle_edges(p0, p1, p2, origin, direction);
    real inverse_det = REAL(1.0) / e.det;
    vec3 w0 = v3_scale(p0, e.e0 * inverse_det), w1 = v3_scale(p1, e.e1 * inverse_det);
    vec3 w2 = v3_scale(p2, e.e2 * inverse_det);
    HitPoint h;
    h.point = v3_add(v3_add(w0, w1), w2);
    h.normal = triangle_normal(p0, p1, p2);
    vec3 w_magnitude = v3_add(v3_add(v3_abs(w0), v3_abs(w1)), v3_abs(w2));
    h.error = rounding_gamma(REAL(4.0)) * fabs(v3_dot(h.point, h.normal)) +
              rounding_gamma(REAL(3.0)) * abs_dot(w_magnitude, h.normal);
    return h;
}

#endif
