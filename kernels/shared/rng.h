/* Counter-based random numbers: every number is a pure function of
 * (seed, pixel, sample, bounce, dimension). No generator state exists, so an
 * image does not depend on thread count, scheduling or queue slots, and the
 * wavefront kernels retrace the reference's paths exactly.
 *
 * The hash is pcg4d (Jarzynski and Olano, "Hash Functions for GPU Rendering",
 * JCGT 2020), a 4-lane PCG variant with good avalanche on correlated inputs.
 * Photons draw these numbers; camera samples draw them through
 * shared/sampler.h, which makes their 2-D integrals' pairs Sobol' points. */
#ifndef WP_SHARED_RNG_H
#define WP_SHARED_RNG_H

#include "shared/prelude.h"

/* Sample dimensions consumed at each bounce. A camera sample draws the
 * first DIM_SOBOL_PAIRS pairs, 2k and 2k + 1, as 2-D Sobol' points and the
 * rest as independent numbers (shared/sampler.h). */
#define DIM_FILM_X 0u /* pixel jitter, bounce 0 only */
#define DIM_FILM_Y 1u
#define DIM_LIGHT_U 2u /* point on the light next-event estimation samples */
#define DIM_LIGHT_V 3u
#define DIM_BSDF_U 4u /* scattered direction */
#define DIM_BSDF_V 5u
#define DIM_SOBOL_PAIRS 3u
#define DIM_LIGHT_SELECT 6u   /* which light */
#define DIM_LIGHT_TRIANGLE 7u /* which triangle of a mesh light */
#define DIM_BSDF_LOBE 8u      /* reflect or refract at glass */
#define DIM_ROULETTE 9u
/* A photon's (SPPM, shared/photons.h): keyed by (photon, iteration) where a
 * camera sample is by (pixel, sample), with dimensions of their own, so that
 * photon k and pixel k of one iteration never share a number. Emission at
 * bounce 0, then the scattering at each bounce. */
#define DIM_PHOTON_LIGHT_SELECT 10u   /* which light emits it */
#define DIM_PHOTON_LIGHT_TRIANGLE 11u /* which triangle of a mesh light */
#define DIM_PHOTON_POINT_U 12u        /* where on that light */
#define DIM_PHOTON_POINT_V 13u
#define DIM_PHOTON_SIDE 14u /* which side of a two-sided light */
#define DIM_PHOTON_DIRECTION_U 15u
#define DIM_PHOTON_DIRECTION_V 16u
#define DIM_PHOTON_BSDF_LOBE 17u
#define DIM_PHOTON_BSDF_U 18u
#define DIM_PHOTON_BSDF_V 19u
#define DIM_PHOTON_ROULETTE 20u
#define DIM_COUNT 21u /* dimensions per bounce; fits in 6 bits */

typedef struct {
    lane_uint x, y, z, w;
} RngKey;

WP_FN RngKey pcg4d(RngKey v) {
    v.x = v.x * 1664525u + 1013904223u;
    v.y = v.y * 1664525u + 1013904223u;
    v.z = v.z * 1664525u + 1013904223u;
    v.w = v.w * 1664525u + 1013904223u;
    v.x += v.y * v.w;
    v.y += v.z * v.x;
    v.z += v.x * v.y;
    v.w += v.y * v.z;
    v.x ^= v.x >> 16u;
    v.y ^= v.y >> 16u;
    v.z ^= v.z >> 16u;
    v.w ^= v.w >> 16u;
    v.x += v.y * v.w;
    v.y += v.z * v.x;
    v.z += v.x * v.y;
    v.w += v.y * v.z;
    return v;
}

/* 32 random bits for one (seed, pixel, sample, bounce, dimension). */
WP_FN lane_uint rng_bits(uint seed, lane_uint pixel, lane_uint sample, lane_uint bounce, uint dimension) {
    RngKey key;
    key.x = pixel;
    key.y = sample;
    key.z = (bounce << 6u) | dimension;
    key.w = seed;
    return pcg4d(key).x;
}

/* Uniform in [0, 1) with 24 bits: exactly representable in float, so the
 * float and double builds draw identical numbers. */
WP_FN real uniform_from_bits(lane_uint bits) { return TO_REAL(bits >> 8u) * REAL(5.9604644775390625e-8); }

/* rng_bits as a uniform number. */
WP_FN real rng_uniform(uint seed, lane_uint pixel, lane_uint sample, lane_uint bounce, uint dimension) {
    return uniform_from_bits(rng_bits(seed, pixel, sample, bounce, dimension));
}

/* The random number of photon `photon` of SPPM iteration `iteration` (a
 * DIM_PHOTON_* dimension): a function of the photon alone, so the photons of
 * an iteration are the same however their tracing is split. */
WP_FN real photon_uniform(uint seed, uint iteration, lane_uint photon, lane_uint bounce, uint dimension) {
    return rng_uniform(seed, photon, (lane_uint)iteration, bounce, dimension);
}

#endif
