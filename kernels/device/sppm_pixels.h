/* SPPM's per-pixel state (interface/sppm_state.h) as the kernels reach it:
 * SPPM_READ(field, pixels) and SPPM_WRITE(field, pixels, where, value), with
 * `pixels` the lanes' pixels (pixel_lanes), the way PATH_READ and PATH_WRITE
 * reach the path state at the lanes' slots (device/lanes.h); and the atomic
 * adds by which photons anywhere add to a pixel: its photon count and its
 * flux, summed exactly (film_words_add, shared/film_sum.h). */
#ifndef WP_DEVICE_SPPM_PIXELS_H
#define WP_DEVICE_SPPM_PIXELS_H

#include "device/lanes.h"
#include "interface/scene_layout.h"
#include "shared/film_sum.h"
#include "shared/prelude.h"

WP_FN uint scene_pixel_count(__global const SceneHeader *scene) { return scene->width * scene->height; }

/* The lanes' pixels, where `active`, as lanes of SPPM's per-pixel arrays
 * (`capacity` is the distance between a vec3 entry's planes: the pixels). */
WP_FN Lanes pixel_lanes(lane_uint pixel, lane_int active, uint pixels) {
    Lanes lanes;
    lanes.active = active;
    lanes.slot = active ? pixel : (lane_uint)0u;
    lanes.capacity = pixels;
#if WP_LANES == 1
    lanes.contiguous = 0;
#else
    lanes.contiguous = all(active) && all(pixel == pixel.s0 + lane_numbers());
#endif
    return lanes;
}

/* The lanes of the work item's consecutive pixels (one work item per
 * WP_LANES pixels). */
WP_FN Lanes own_pixel_lanes(uint pixels) {
    lane_uint pixel = lane_positions();
    return pixel_lanes(pixel, pixel < pixels, pixels);
}

#define SPPM_READ(field, pixels) slot_read(state_##field, pixels)
#define SPPM_WRITE(field, pixels, where, value) slot_write(state_##field, pixels, where, value)
/* An entry's buffer as a whole, for what is not per lane (atomic adds, the
 * grid's prefix sum): SPPM_IN where the kernel only reads it, SPPM_OUT where
 * it writes it too. */
#define SPPM_IN(field) (state_##field)
#define SPPM_OUT(field) (state_##field)

/* p[index] += 1 atomically where `where` holds; returns the old values
 * (0 elsewhere). */
#if WP_LANES == 1
WP_FN lane_uint atomic_increment_where(volatile __global uint *p, lane_uint index, lane_int where) {
    return where ? atomic_inc(&p[index]) : 0u;
}
#else
#define WP_INCREMENT_LANE(s, k) old.s = where.s ? atomic_inc(&p[index.s]) : 0u;
WP_LANE_FN lane_uint atomic_increment_where(volatile __global uint *p, lane_uint index, lane_int where) {
    lane_uint old = 0u;
    WP_FOR_LANES(WP_INCREMENT_LANE)
    return old;
}
#undef WP_INCREMENT_LANE
#endif

/* Adds `value` (not negative) to the lanes' pixels' flux sums where `where`
 * holds: WP_FILM_WORDS words per pixel and channel. */
WP_FN void add_flux_where(volatile __global uint *words, lane_uint pixel, lane_int where, vec3 value) {
#if WP_LANES == 1
    if (!where) return;
    film_words_add(words + (3u * pixel + 0u) * WP_FILM_WORDS, film_sum_from_float(value.x));
    film_words_add(words + (3u * pixel + 1u) * WP_FILM_WORDS, film_sum_from_float(value.y));
    film_words_add(words + (3u * pixel + 2u) * WP_FILM_WORDS, film_sum_from_float(value.z));
#else
#define WP_ADD_FLUX_LANE(s, k)                                                                       \
    if (where.s) {                                                                                   \
        film_words_add(words + (3u * pixel.s + 0u) * WP_FILM_WORDS, film_sum_from_float(value.x.s)); \
        film_words_add(words + (3u * pixel.s + 1u) * WP_FILM_WORDS, film_sum_from_float(value.y.s)); \
        film_words_add(words + (3u * pixel.s + 2u) * WP_FILM_WORDS, film_sum_from_float(value.z.s)); \
    }
    WP_FOR_LANES(WP_ADD_FLUX_LANE)
#undef WP_ADD_FLUX_LANE
#endif
}

/* The lanes' pixels' flux sums (no add under way), each rounded to float. */
WP_FN real flux_channel(__global const uint *words, lane_uint pixel, uint channel) {
#if WP_LANES == 1
    return film_sum_to_float(film_sum_from_words(words + (3u * pixel + channel) * WP_FILM_WORDS));
#else
    float values[WP_LANES];
#define WP_FLUX_LANE(s, k) \
    values[k] = film_sum_to_float(film_sum_from_words(words + (3u * pixel.s + channel) * WP_FILM_WORDS));
    WP_FOR_LANES(WP_FLUX_LANE)
#undef WP_FLUX_LANE
    return LANES_LOAD(values);
#endif
}

WP_FN vec3 pixel_flux(__global const uint *words, lane_uint pixel) {
    return make_vec3(flux_channel(words, pixel, 0u), flux_channel(words, pixel, 1u), flux_channel(words, pixel, 2u));
}

#endif
