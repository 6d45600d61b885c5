/* A pass's items (the stage kernels and the megakernel): the sample each
 * traces, and where a finished path's radiance goes: its pass entry, which
 * accumulate.cl adds to the film in sample order. */
#ifndef WP_DEVICE_PASS_RADIANCE_H
#define WP_DEVICE_PASS_RADIANCE_H

#include "device/lane_memory.h"
#include "shared/prelude.h"

typedef struct {
    lane_uint pixel, sample;
} PassSample;

/* The pixel and sample of pass item `item`: work item w = pass_start + item
 * is pixel round_pixels[w % round_pixel_count], sample w / round_pixel_count
 * (docs/architecture.md, "Work, passes and determinism"), split without
 * 64-bit lanes: pass_pixel + item stays below 2^32 (limits.h: pixels <= 2^27,
 * passes <= 2^30). Lanes that are not `active` read round_pixels[0]. */
WP_FN PassSample pass_item_sample(__global const uint *round_pixels, uint round_pixel_count, ulong pass_start,
                                  lane_uint item, lane_int active) {
    uint pass_pixel = (uint)(pass_start % round_pixel_count), pass_sample = (uint)(pass_start / round_pixel_count);
    PassSample work;
    work.pixel = gather(round_pixels, active ? (pass_pixel + item) % round_pixel_count : (lane_uint)0u);
    work.sample = pass_sample + (pass_pixel + item) / round_pixel_count;
    return work;
}

/* Ends the paths of the lanes where `where` holds: their radiance (finite:
 * every addition was checked) becomes their pass entry (index `item`); a
 * stage kernel then frees their slots for generate. */
WP_FN void finish_paths(__global float *pass_radiance, lane_uint item, lane_int where, vec3 radiance) {
    store_where(pass_radiance, 3u * item + 0u, where, radiance.x);
    store_where(pass_radiance, 3u * item + 1u, where, radiance.y);
    store_where(pass_radiance, 3u * item + 2u, where, radiance.z);
}

#endif
