/* Where a finished path's radiance goes: its pass entry, which accumulate.cl
 * adds to the film in sample order (the stage kernels and the megakernel). */
#ifndef WP_DEVICE_PASS_RADIANCE_H
#define WP_DEVICE_PASS_RADIANCE_H

#include "device/lane_memory.h"
#include "shared/prelude.h"

/* Ends the paths of the lanes where `where` holds: their radiance (finite:
 * every addition was checked) becomes their pass entry (index `item`); a
 * stage kernel then frees their slots for generate. */
WP_FN void finish_paths(__global float *pass_radiance, lane_uint item, lane_int where, vec3 radiance) {
    store_where(pass_radiance, 3u * item + 0u, where, radiance.x);
    store_where(pass_radiance, 3u * item + 1u, where, radiance.y);
    store_where(pass_radiance, 3u * item + 2u, where, radiance.z);
}

#endif
