/* Adds a drained pass into the film: one work item per pixel sums that
 * pixel's pass entries in sample order, in double (or compensated float
 * where the device lacks fp64), exactly as the reference sums its samples.
 * No atomics: the image does not depend on scheduling or wavefront size.
 *
 * The compensated float film (Kahan summation) holds each sum times
 * film_scale, a power of two at most 1/spp set by the host: the scaling is
 * exact, and a sum of spp finite floats then stays finite (each entry is at
 * most FLT_MAX), where an unscaled sum could overflow to Inf and Kahan's
 * correction then turn it into NaN. */
#include "device/parameters.h"
#include "interface/kernel_parameters.h"

#ifdef WP_FILM_DOUBLE
#pragma OPENCL EXTENSION cl_khr_fp64 : enable
typedef double film_real;
#else
typedef float film_real;
#endif

/* film holds 3 sums per pixel, then (compensated float only) 3 compensations. */
__kernel void accumulate(WP_PARAMETERS(WP_ACCUMULATE_PARAMETERS)) {
    uint px = get_global_id(0);
    if (px >= pixel_count) return;
    uint first = (uint)((px + pixel_count - pass_start % pixel_count) % pixel_count);
    for (uint c = 0; c < 3u; ++c) {
        film_real sum = film[3u * px + c];
#ifndef WP_FILM_DOUBLE
        /* Kahan summation */
        film_real compensation = film[3u * (pixel_count + px) + c];
#endif
        for (uint item = first; item < pass_size; item += pixel_count) {
#ifdef WP_FILM_DOUBLE
            sum += (film_real)pass_radiance[3u * item + c];
#else
            film_real y = pass_radiance[3u * item + c] * film_scale - compensation;
            film_real t = sum + y;
            compensation = (t - sum) - y;
            sum = t;
#endif
        }
        film[3u * px + c] = sum;
#ifndef WP_FILM_DOUBLE
        film[3u * (pixel_count + px) + c] = compensation;
#endif
    }
}
