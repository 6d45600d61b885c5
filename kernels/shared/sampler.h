/* The camera path's random numbers: Owen-scrambled Sobol' points, padded in
 * two dimensions (Burley, "Practical Hash-based Owen Scrambling", JCGT 9(4),
 * 2020; pbrt-v4's PaddedSobolSampler pads alike), for the 2-D integrals of a
 * vertex, and stratified 1-D numbers for its discrete choices.
 *
 * Each of the first DIM_SOBOL_PAIRS pairs of camera dimensions (2k, 2k + 1
 * of shared/rng.h: the pixel, the light point, the BSDF direction) at each
 * bounce is one 2-D Sobol' point. Sobol's first two dimensions are a
 * (0,2)-sequence: the first 2^m samples of a pixel put one point in each of
 * the 2^m cells of every grid of 2^a x 2^(m-a) cells, where independent
 * numbers leave some cells empty and others doubled, so the error of smooth
 * integrands (a pixel's area, a light's, a diffuse lobe) falls faster than
 * 1/sqrt(n). Each choice (which light, which triangle, the lobe, the
 * roulette) takes Sobol's first dimension alone, a (0,1)-sequence: the
 * first 2^m samples put one number in each 1/2^m of [0, 1), so a lobe of
 * fixed probability p is chosen by p 2^m samples give or take one, where
 * independent numbers spread the count by sqrt(p (1 - p) 2^m) (as Mitsuba's
 * ldsampler draws its 1-D numbers; bench/results/analysis.md, "Materials
 * against Mitsuba 3", measures the gain).
 *
 * Each pair and each choice is a stream of its own, keyed by (seed, pixel,
 * bounce, stream) and so the same for every sample of a pixel: a pair's
 * stream is its index k, a choice's its dimension (>= 2 DIM_SOBOL_PAIRS, so
 * apart from the pairs'). Two scrambles, both hashes of the key:
 *   - the sample index is shuffled by a nested uniform scramble, which keeps
 *     each block of 2^m samples a net while making the streams'
 *     points independent of one another (unshuffled, sample i would take the
 *     same point in every stream);
 *   - each coordinate is Owen-scrambled, which keeps the net and makes every
 *     number uniform on [0, 1) over seeds: the estimate stays unbiased.
 * No state, so the image stays a function of (seed, pixel, sample) as with
 * shared/rng.h; any sample count works, powers of two best. */
#ifndef WP_SHARED_SAMPLER_H
#define WP_SHARED_SAMPLER_H

#include "shared/prelude.h"
#include "shared/rng.h"

/* Bit k of x moved to bit 31 - k. */
WP_FN lane_uint reverse_bits(lane_uint x) {
    x = ((x >> 1u) & 0x55555555u) | ((x & 0x55555555u) << 1u);
    x = ((x >> 2u) & 0x33333333u) | ((x & 0x33333333u) << 2u);
    x = ((x >> 4u) & 0x0f0f0f0fu) | ((x & 0x0f0f0f0fu) << 4u);
    x = ((x >> 8u) & 0x00ff00ffu) | ((x & 0x00ff00ffu) << 8u);
    return (x >> 16u) | (x << 16u);
}

/* A random permutation of 32-bit words in which bit k of the result depends
 * only on bits 0..k of x (additions and products by even constants carry
 * upwards only): Laine and Karras's hash with Burley's constants. */
WP_FN lane_uint laine_karras_permutation(lane_uint x, lane_uint seed) {
    x += seed;
    x ^= x * 0x6c50b47cu;
    x ^= x * 0xb82f1e52u;
    x ^= x * 0xc7afe638u;
    x ^= x * 0x8d22f6e6u;
    return x;
}

/* Owen's scramble of the binary fraction 0.x31 x30 ... x0: each digit flipped
 * by a hash of the digits before it (more significant). Reversed, those are
 * the lower bits, which is the dependence laine_karras_permutation has. */
WP_FN lane_uint nested_uniform_scramble(lane_uint x, lane_uint seed) {
    return reverse_bits(laine_karras_permutation(reverse_bits(x), seed));
}

/* Sobol's second dimension, before its bits are reversed: its direction
 * numbers are the rows of Pascal's triangle mod 2, so digit j of the point
 * is the parity of the index's bits k with C(k, j) odd, that is (Lucas) the
 * bits k whose set bits include j's. Five steps of a superset sum compute
 * all 32 digits at once. Its first dimension is the index itself (van der
 * Corput's radical inverse: the bits reversed). */
WP_FN lane_uint sobol_second_dimension_reversed(lane_uint index) {
    lane_uint y = index;
    y ^= (y >> 1u) & 0x55555555u;
    y ^= (y >> 2u) & 0x33333333u;
    y ^= (y >> 4u) & 0x0f0f0f0fu;
    y ^= (y >> 8u) & 0x00ff00ffu;
    y ^= (y >> 16u) & 0x0000ffffu;
    return y;
}

/* Stream `stream`'s hashes at bounce `bounce` of pixel `pixel`: apart from
 * rng_bits's keys, whose w is the seed. */
WP_FN RngKey sobol_stream_hashes(uint seed, lane_uint pixel, lane_uint bounce, uint stream) {
    RngKey key;
    key.x = pixel;
    key.y = (bounce << 6u) | stream;
    key.z = seed;
    key.w = 0x5ca1ab1eu;
    return pcg4d(key);
}

/* Sobol's first dimension (van der Corput's radical inverse) at the
 * shuffled index, Owen-scrambled by `hash`: the nested_uniform_scramble of
 * the point, whose first reversal undoes the digits' reversal here. */
WP_FN real owen_scrambled_radical_inverse(lane_uint index, lane_uint hash) {
    return uniform_from_bits(reverse_bits(laine_karras_permutation(index, hash)));
}

/* The two numbers of Sobol' pair `first_dimension` / 2 (its dimensions
 * first_dimension and first_dimension + 1) at bounce `bounce` of sample
 * `sample` of pixel `pixel`: the point at the shuffled index, each coordinate
 * Owen-scrambled, uniform in [0, 1) with 24 bits as rng_uniform. Without
 * `sobol` (render.sampler "independent"), the two dimensions' rng_uniform
 * numbers. */
typedef struct {
    real u, v;
} CameraPair;

WP_FN CameraPair camera_pair(uint seed, lane_uint pixel, lane_uint sample, lane_uint bounce, uint first_dimension,
                             int sobol) {
    CameraPair pair;
    if (!sobol) {
        pair.u = rng_uniform(seed, pixel, sample, bounce, first_dimension);
        pair.v = rng_uniform(seed, pixel, sample, bounce, first_dimension + 1u);
        return pair;
    }
    RngKey hashes = sobol_stream_hashes(seed, pixel, bounce, first_dimension >> 1u);
    lane_uint index = nested_uniform_scramble(sample, hashes.x);
    pair.u = owen_scrambled_radical_inverse(index, hashes.y);
    pair.v =
        uniform_from_bits(reverse_bits(laine_karras_permutation(sobol_second_dimension_reversed(index), hashes.z)));
    return pair;
}

/* The camera's number for any dimension `dimension` (DIM_* of shared/rng.h)
 * at bounce `bounce` of sample `sample` of pixel `pixel`: a coordinate of a
 * Sobol' pair (camera_pair), or a choice's stratified number. Without
 * `sobol`, an independent number. */
WP_FN real camera_uniform(uint seed, lane_uint pixel, lane_uint sample, lane_uint bounce, uint dimension, int sobol) {
    if (dimension < 2u * DIM_SOBOL_PAIRS) {
        CameraPair pair = camera_pair(seed, pixel, sample, bounce, dimension & ~1u, sobol);
        return (dimension & 1u) != 0u ? pair.v : pair.u;
    }
    if (!sobol) return rng_uniform(seed, pixel, sample, bounce, dimension);
    RngKey hashes = sobol_stream_hashes(seed, pixel, bounce, dimension);
    return owen_scrambled_radical_inverse(nested_uniform_scramble(sample, hashes.x), hashes.y);
}

#endif
