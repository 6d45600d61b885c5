/* Adds a drained pass into the film: one work item per pixel of the round
 * (round_pixels, interface/kernel_parameters.h) adds that pixel's pass entries to its exact fixed-point sums
 * (shared/film_sum.h), in sample order as the reference does, although with exact sums the order no longer matters. No
 * atomics, no fp64: the film's bits depend neither on scheduling, wavefront size or pass boundaries nor on the device.
 *
 * The film holds WP_FILM_LIMBS limbs per channel and pixel: 3 sums per pixel,
 * then (built with -DWP_FILM_SQUARES, for per-pixel variance) 3 sums of
 * squares per pixel. */
#include "device/parameters.h"
#include "interface/kernel_parameters.h"
#include "shared/film_sum.h"

WP_FILM_FN film_sum load_film_sum(__global const ulong *film, uint index) {
    film_sum s;
    for (int i = 0; i < WP_FILM_LIMBS; ++i) s.limb[i] = film[WP_FILM_LIMBS * index + i];
    return s;
}

WP_FILM_FN void store_film_sum(__global ulong *film, uint index, film_sum s) {
    for (int i = 0; i < WP_FILM_LIMBS; ++i) film[WP_FILM_LIMBS * index + i] = s.limb[i];
}

__kernel void accumulate(WP_PARAMETERS(WP_ACCUMULATE_PARAMETERS)) {
    uint index = get_global_id(0);
    if (index >= round_pixel_count) return;
    uint px = round_pixels[index];
    uint first = (uint)((index + round_pixel_count - pass_start % round_pixel_count) % round_pixel_count);
    film_sum sum[3];
    for (uint c = 0; c < 3u; ++c) sum[c] = load_film_sum(film, 3u * px + c);
#ifdef WP_FILM_SQUARES
    film_sum squares[3];
    for (uint c = 0; c < 3u; ++c) squares[c] = load_film_sum(film, 3u * (pixel_count + px) + c);
#endif
    for (uint item = first; item < pass_size; item += round_pixel_count) {
        for (uint c = 0; c < 3u; ++c) {
            float value = pass_radiance[3u * item + c];
            sum[c] = film_sum_add(sum[c], film_sum_from_float(value));
#ifdef WP_FILM_SQUARES
            squares[c] = film_sum_add(squares[c], film_sum_from_float_squared(value));
#endif
        }
    }
    for (uint c = 0; c < 3u; ++c) store_film_sum(film, 3u * px + c, sum[c]);
#ifdef WP_FILM_SQUARES
    for (uint c = 0; c < 3u; ++c) store_film_sum(film, 3u * (pixel_count + px) + c, squares[c]);
#endif
}
