/* Ray-primitive intersection. Rays have unit directions; a hit is reported
 * as a distance t in (0, t_max), a miss as WP_INFINITY. There is no minimum
 * distance: rays leave surfaces from points offset by offset_ray_origin(),
 * which is what keeps them from re-hitting their own surface. */
#ifndef WP_SHARED_GEOMETRY_H
#define WP_SHARED_GEOMETRY_H

#include "shared/prelude.h"

/* Sphere, in the numerically careful form of Haines et al., "Precision
 * Improvements for Ray/Sphere Intersection" (Ray Tracing Gems, ch. 7):
 * the discriminant from the ray's closest approach to the centre, and the
 * second root from Vieta's formula, so huge and tiny spheres and far origins
 * keep their precision. Rays starting inside report the exit distance. */
WP_FN real intersect_sphere(vec3 center, real radius, vec3 origin, vec3 direction, real t_max) {
    vec3 f = v3_sub(origin, center);
    real b = -v3_dot(f, direction);
    vec3 closest = v3_add_scaled(f, b, direction); /* centre to the ray's closest point */
    real discriminant = radius * radius - v3_dot(closest, closest);
    lane_int misses = discriminant < REAL(0.0);
    if (!lanes_any(!misses)) return WP_INFINITY; /* most rays: no root to take */
    real c = v3_dot(f, f) - radius * radius;
    real q = b + copysign(safe_sqrt(discriminant), b);
    real t0 = q != REAL(0.0) ? c / q : REAL(0.0);
    real t1 = q;
    real t_near = fmin(t0, t1);
    real t_far = fmax(t0, t1);
    real t = (t_near > REAL(0.0) && t_near < t_max) ? t_near
             : (t_far > REAL(0.0) && t_far < t_max) ? t_far
                                                    : WP_INFINITY;
    return misses ? WP_INFINITY : t;
}

/* Infinite plane through `point` with (not necessarily unit) `normal`. A ray
 * parallel to the plane misses it, also when it lies inside it. */
WP_FN real intersect_plane(vec3 point, vec3 normal, vec3 origin, vec3 direction, real t_max) {
    real denominator = v3_dot(normal, direction);
    real t = v3_dot(v3_sub(point, origin), normal) / denominator;
    return (denominator != REAL(0.0) && t > REAL(0.0) && t < t_max) ? t : WP_INFINITY;
}

/* What the parallelogram test needs of a quad beyond its corner and edges,
 * computed once per quad (the wavefront uploads it with the scene, so no
 * kernel recomputes it per ray). */
typedef struct {
    vec3 normal; /* edge1 x edge2, not normalised */
    vec3 w;      /* normal / |normal|^2, which turns the hit's offset into (u, v) */
} QuadPlane;

WP_FN QuadPlane quad_plane(vec3 edge1, vec3 edge2) {
    QuadPlane plane;
    plane.normal = v3_cross(edge1, edge2);
    plane.w = v3_div(plane.normal, v3_dot(plane.normal, plane.normal));
    return plane;
}

/* Parallelogram corner + u*edge1 + v*edge2 with u, v in [0, 1], edges and
 * corners included; `plane` is quad_plane(edge1, edge2). */
WP_FN real intersect_quad_plane(vec3 corner, vec3 edge1, vec3 edge2, QuadPlane plane, vec3 origin, vec3 direction,
                                real t_max) {
    real t = intersect_plane(corner, plane.normal, origin, direction, t_max);
    vec3 p = v3_sub(v3_add_scaled(origin, t, direction), corner);
    real u = v3_dot(plane.w, v3_cross(p, edge2));
    real v = v3_dot(plane.w, v3_cross(edge1, p));
    return (t != WP_INFINITY && u >= REAL(0.0) && u <= REAL(1.0) && v >= REAL(0.0) && v <= REAL(1.0)) ? t : WP_INFINITY;
}

WP_FN real intersect_quad(vec3 corner, vec3 edge1, vec3 edge2, vec3 origin, vec3 direction, real t_max) {
    return intersect_quad_plane(corner, edge1, edge2, quad_plane(edge1, edge2), origin, direction, t_max);
}

/* Outward unit normal at a point on a sphere. */
WP_FN vec3 sphere_normal(vec3 center, vec3 p) { return v3_normalize(v3_sub(p, center)); }

/* Moves a computed hit point back onto the sphere, removing most of the
 * error that origin + t * direction accumulated. */
WP_FN vec3 sphere_reproject(vec3 center, real radius, vec3 p) {
    vec3 d = v3_sub(p, center);
    return v3_add(center, v3_scale(d, radius / v3_length(d)));
}

WP_FN vec3 quad_normal(vec3 edge1, vec3 edge2) { return v3_normalize(v3_cross(edge1, edge2)); }

#endif
