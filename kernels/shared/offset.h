/* Spawned-ray origins without a fixed epsilon, from error bounds in the
 * manner of pbrt-v4 (Pharr, Jakob and Humphreys, "Physically Based
 * Rendering", 4th ed., section 6.8): every computed surface point comes with
 * `error`, a bound on its distance from the true surface that follows from
 * the magnitudes of the numbers it was computed from, and offset_ray_origin
 * moves it along the geometric normal by twice that bound. One bound carries
 * the point to the surface; the other covers the rounding of the moved point
 * and of the next ray's own test against the surface, which involve the same
 * magnitudes. A scene scaled by 2^k has every offset scaled by exactly 2^k.
 *
 * Where the error comes from:
 *  - a point o + t d on a plane or quad (t from the plane equation): the
 *    numerator dot(anchor - o, N) errs by ~gamma(4) sqrt(3) (|anchor| + |o|),
 *    the grazing-sensitive denominator moves the point along d by a relative
 *    gamma(3) of t, which puts it at most gamma(3) |t| off the plane, and
 *    o + t d rounds by gamma(2) (|o| + |t|) per component: together below
 *    11 u (|o| + |t| + |anchor|); a ray from far away therefore has a large
 *    error even where it lands near the origin.
 *  - a sphere point moved back onto the sphere (sphere_reproject), or a point
 *    sampled on a light (center + r n, corner + u e1 + v e2), depends on the
 *    shape alone: below 9 u (|center| + r), 6 u (|corner| + |e1| + |e2|).
 *    A wall of radius 1e5 thus carries an error of ulp(1e5) size.
 * The bounds use 16 roundings (gamma(16)), a margin over those sums, with
 * |v| the largest component magnitude.
 *
 * The unit roundoff is float's, 2^-24, in the double build too: the bound
 * holds there with room to spare, and both precisions render the same
 * offset geometry, so float against double measures arithmetic alone. */
#ifndef WP_SHARED_OFFSET_H
#define WP_SHARED_OFFSET_H

#include "shared/prelude.h"

#define WP_FLOAT_UNIT_ROUNDOFF REAL(5.9604644775390625e-08) /* 2^-24 */
#define WP_POINT_ERROR_ROUNDINGS REAL(16.0)

/* Higham's gamma(n) = n u / (1 - n u): the relative error of n roundings. */
WP_FN real rounding_gamma(real n) { return n * WP_FLOAT_UNIT_ROUNDOFF / (REAL(1.0) - n * WP_FLOAT_UNIT_ROUNDOFF); }

WP_FN real max_abs(vec3 v) { return fmax(fabs(v.x), fmax(fabs(v.y), fabs(v.z))); }

/* The magnitude a shape's points and intersections are computed from. */
WP_FN real sphere_magnitude(vec3 center, real radius) { return max_abs(center) + fabs(radius); }
WP_FN real plane_magnitude(vec3 point) { return max_abs(point); }
WP_FN real quad_magnitude(vec3 corner, vec3 edge1, vec3 edge2) {
    return max_abs(corner) + max_abs(edge1) + max_abs(edge2);
}

/* Error of a point computed from the shape's own data: a reprojected sphere
 * hit or a sampled light point. */
WP_FN real shape_point_error(real shape_magnitude) {
    return rounding_gamma(WP_POINT_ERROR_ROUNDINGS) * shape_magnitude;
}

/* Error of the point origin + t * direction where a ray meets a plane or quad. */
WP_FN real ray_point_error(vec3 origin, real t, real shape_magnitude) {
    return rounding_gamma(WP_POINT_ERROR_ROUNDINGS) * (max_abs(origin) + fabs(t) + shape_magnitude);
}

/* Error of the far end of a shadow ray from x to the light point `target`:
 * the sample's own error plus the error with which the shadow ray would meet
 * the light there, so that the ray stops short of the light. */
WP_FN real shadow_target_error(vec3 x, vec3 target, real light_magnitude) {
    return shape_point_error(light_magnitude) + ray_point_error(x, v3_length(v3_sub(target, x)), light_magnitude);
}

/* `n` is the unit geometric normal on the side the ray leaves into; `error`
 * bounds p's distance from the surface. */
WP_FN vec3 offset_ray_origin(vec3 p, vec3 n, real error) { return v3_add_scaled(p, REAL(2.0) * error, n); }

#endif
