/* Spawned-ray origins without a fixed epsilon, from error bounds in the
 * manner of pbrt-v4 (Pharr, Jakob and Humphreys, "Physically Based
 * Rendering", 4th ed., section 6.8): every computed surface point comes with
 * `error`, a bound on its distance from the true surface that follows from
 * the numbers it was computed from, and offset_ray_origin moves it along the
 * geometric normal by twice that bound. One bound carries the point to the
 * surface; the other covers the rounding of the moved point and of the next
 * ray's own test against the surface, which involve the same magnitudes. A
 * scene scaled by 2^k has every offset scaled by exactly 2^k.
 *
 * Ray hits get bounds derived for their own formulas from the actual
 * quantities (shared/hit_point.h). Points sampled on lights and the far end
 * of a shadow ray use the coarser magnitude bounds below:
 *  - a point sampled on a light (center + r n, corner + u e1 + v e2, a
 *    barycentric combination) errs by less than 9 u (|center| + r),
 *    6 u (|corner| + |e1| + |e2|), 7 u max |p_i|;
 *  - a point o + t d where a ray meets a shape errs by less than
 *    11 u (|o| + |t| + the shape's magnitude) (the plane equation's
 *    numerator errs by ~gamma(4) sqrt(3) (|anchor| + |o|), its
 *    grazing-sensitive denominator moves the point along d by a relative
 *    gamma(3) of t, and o + t d rounds by gamma(2) (|o| + |t|)); for a
 *    sphere the root's cancellation adds ~3 u r. The shadow ray's far end is
 *    moved off the light by this, so that the ray stops short of the light
 *    even where it meets it at a grazing angle from far away.
 * These use 16 roundings (gamma(16)), a margin over those sums, with |v| the
 * largest component magnitude.
 *
 * u is the unit roundoff of the precision the code is compiled for
 * (WP_UNIT_ROUNDOFF: 2^-24 in float, 2^-53 in double), so the double build
 * is a reference with double's own offsets, not float's. */
#ifndef WP_SHARED_OFFSET_H
#define WP_SHARED_OFFSET_H

#include "shared/prelude.h"

#define WP_POINT_ERROR_ROUNDINGS REAL(16.0)

/* Higham's gamma(n) = n u / (1 - n u) (Higham, "Accuracy and Stability of
 * Numerical Algorithms", 2nd ed., section 3.1): a product of n factors
 * (1 + delta_i), |delta_i| <= u, lies within 1 +- gamma(n). */
WP_FN real rounding_gamma(real n) { return n * WP_UNIT_ROUNDOFF / (REAL(1.0) - n * WP_UNIT_ROUNDOFF); }

WP_FN real max_abs(vec3 v) { return fmax(fabs(v.x), fmax(fabs(v.y), fabs(v.z))); }
WP_FN vec3 v3_abs(vec3 v) { return make_vec3(fabs(v.x), fabs(v.y), fabs(v.z)); }
/* sum |a_i| |b_i|: what per-component errors |a_i| delta_i can add up to
 * along the direction b. */
WP_FN real abs_dot(vec3 a, vec3 b) { return v3_dot(v3_abs(a), v3_abs(b)); }

/* The magnitude a shape's points and intersections are computed from. */
WP_FN real sphere_magnitude(vec3 center, real radius) { return max_abs(center) + fabs(radius); }
WP_FN real plane_magnitude(vec3 point) { return max_abs(point); }
WP_FN real quad_magnitude(vec3 corner, vec3 edge1, vec3 edge2) {
    return max_abs(corner) + max_abs(edge1) + max_abs(edge2);
}

/* Error of a point sampled on a light. */
WP_FN real shape_point_error(real shape_magnitude) {
    return rounding_gamma(WP_POINT_ERROR_ROUNDINGS) * shape_magnitude;
}

/* Error of the point origin + t * direction where a ray meets a shape. */
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
