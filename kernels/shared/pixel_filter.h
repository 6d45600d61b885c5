/* The pixel filter, sampled by importance exactly: a camera sample's point is
 * the pixel's centre plus an offset drawn from the filter's own density, so
 * every sample weighs 1 and the pixel's plain mean of its samples estimates
 * the image convolved with the normalised filter (pbrt-v4's FilterSampler,
 * here in closed form). Each sample counts in its own pixel only: the film
 * stays an exact sum per pixel, independent of the schedule.
 *
 * The filters, separable (f(x, y) = f(x) f(y)), as Mitsuba 3 names them:
 *   - box: the pixel itself; the point is the jitter as drawn, bit for bit;
 *   - tent of radius r: f(x) = max(0, 1 - |x| / r), by inverting its
 *     cumulative distribution;
 *   - gaussian of standard deviation s: the Gaussian truncated at 4 s,
 *     x = s sqrt(2) erfinv((2u - 1) erf(2 sqrt 2)). Mitsuba's also subtracts
 *     its value at 4 s, e^-8 = 3.4e-4 of the peak, to reach 0 there; that
 *     window has no closed-form inverse, and it moves a pixel by at most
 *     2.7e-4 of the contrast across an edge (the integrals of the two
 *     normalised filters beyond any point differ by that much), against
 *     exact sampling with no weight at all here.
 * The host computes the constants once, in double (scene/pixel_filter.h),
 * and every backend reads the same rounded values. */
#ifndef WP_SHARED_PIXEL_FILTER_H
#define WP_SHARED_PIXEL_FILTER_H

#include "shared/prelude.h"
#include "shared/special_functions.h"

#define WP_FILTER_BOX 0u
#define WP_FILTER_TENT 1u
#define WP_FILTER_GAUSSIAN 2u

typedef struct {
    uint type;       /* WP_FILTER_* */
    real radius;     /* tent: r */
    real scale;      /* gaussian: s sqrt(2) */
    real erf_radius; /* gaussian: erf(4 s / (s sqrt 2)) */
} PixelFilter;

/* A camera sample's point, in pixels from its pixel's top left corner: in
 * [0, 1)^2 for the box, beyond where a filter reaches into the neighbours. */
typedef struct {
    real u, v;
} FilmPoint;

/* One axis of the tent: the inverse of its cumulative distribution at u. */
WP_FN real tent_offset(real radius, real u) {
    return u < REAL(0.5) ? radius * (sqrt(REAL(2.0) * u) - REAL(1.0))
                         : radius * (REAL(1.0) - sqrt(REAL(2.0) - REAL(2.0) * u));
}

/* One axis of the truncated Gaussian: the inverse of its cumulative distribution at u. */
WP_FN real gaussian_offset(PixelFilter f, real u) {
    return f.scale * wp_erfinv((REAL(2.0) * u - REAL(1.0)) * f.erf_radius);
}

/* The point of the jitter (u, v) in [0, 1)^2 under filter f. */
WP_FN FilmPoint pixel_filter_sample(PixelFilter f, real u, real v) {
    FilmPoint p;
    p.u = u;
    p.v = v;
    if (f.type == WP_FILTER_TENT) {
        p.u = REAL(0.5) + tent_offset(f.radius, u);
        p.v = REAL(0.5) + tent_offset(f.radius, v);
    } else if (f.type == WP_FILTER_GAUSSIAN) {
        p.u = REAL(0.5) + gaussian_offset(f, u);
        p.v = REAL(0.5) + gaussian_offset(f, v);
    }
    return p;
}

#endif
