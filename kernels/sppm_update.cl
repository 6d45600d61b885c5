/* SPPM's update after an iteration (shared/sppm.h), WP_LANES pixels per
 * work item: each pixel's photon count, radius and flux from what the
 * iteration's photons brought it (its count and its exact flux sum, rounded
 * once to float), and the iteration's photons added to visible points into
 * the counter WP_COUNTER_PHOTON_DEPOSITS (one atomic add per work item). */
#include "device/lanes.h"
#include "device/parameters.h"
#include "device/sppm_pixels.h"
#include "interface/kernel_parameters.h"
#include "interface/queues.h"
#include "shared/sppm.h"

__kernel __attribute__((reqd_work_group_size(WP_GROUP_SIZE, 1, 1))) void sppm_update(WP_SPPM_PARAMS) {
#ifdef WP_SPPM
    Lanes own = own_pixel_lanes(scene_pixel_count(scene));
    SppmPixel pixel;
    pixel.count = SPPM_READ(sppm_count, own);
    pixel.radius = SPPM_READ(sppm_radius, own);
    pixel.flux = SPPM_READ(sppm_flux, own);
    lane_uint photons = SPPM_READ(iteration_photons, own);
    pixel = sppm_pixel_update(pixel, photons, pixel_flux(SPPM_IN(iteration_flux), own.slot), scene->sppm_alpha);
    SPPM_WRITE(sppm_count, own, own.active, pixel.count);
    SPPM_WRITE(sppm_radius, own, own.active, pixel.radius);
    SPPM_WRITE(sppm_flux, own, own.active, pixel.flux);
    uint deposits = lanes_sum(own.active ? photons : (lane_uint)0u);
    if (deposits != 0u) atomic_add(&counts[WP_COUNTER_PHOTON_DEPOSITS], deposits);
#endif
}
