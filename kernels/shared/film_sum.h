/* The film's per-pixel sums, exact: a signed 256-bit fixed-point number
 * (four 64-bit limbs, least significant first, two's complement) with
 * WP_FILM_FRACTION_BITS (100) bits after the point. Every finite float of
 * magnitude at least 2^-77 converts exactly (smaller ones round to the
 * nearest multiple of 2^-100, ties to even), and sums of up to 2^20 floats of
 * any finite magnitude cannot overflow (|float| < 2^128, and values are
 * clamped below 2^134, so 2^20 of them stay below 2^154 < 2^155).
 * Integer addition is associative: a pixel's sum is the same bits whatever
 * the order of its samples, the pass boundaries, a resume from a checkpoint,
 * or a split of its samples over processes merged later. Compiled as OpenCL C
 * (kernels/accumulate.cl) and as C++ (src/core/film.h), with no fp64.
 *
 * A value m * 2^exponent with m < 2^53 (a float's or a double's significand)
 * becomes m * 2^(exponent + WP_FILM_FRACTION_BITS); magnitudes from 2^134 on
 * (a double's only, or a float's square) are clamped to 2^134. */
#ifndef WP_SHARED_FILM_SUM_H
#define WP_SHARED_FILM_SUM_H

#ifdef __OPENCL_C_VERSION__
typedef ulong film_limb;
typedef uint film_word;
/* Inlined and unrolled: PoCL 3.1 otherwise kept a sum's limbs in memory,
 * and every add paid a store-to-load round trip (accumulate.cl). */
#define WP_FILM_FN static inline __attribute__((always_inline))
#define WP_FILM_UNROLL _Pragma("unroll")
#define WP_FLOAT_BITS(x) as_uint(x)
#define WP_FILM_LDEXPF(x, e) ldexp((x), (e))
#define WP_FILM_WORDS_POINTER volatile __global film_word *
#define WP_FILM_CONST_WORDS_POINTER __global const film_word *
#define WP_ATOMIC_ADD_WORD(p, v) atomic_add((p), (v))
#define WP_FILM_LEADING_ZEROS(m) ((int)clz(m))
#else
#include <atomic>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
typedef std::uint64_t film_limb;
typedef std::uint32_t film_word;
#define WP_FILM_FN inline
#define WP_FILM_UNROLL
#define WP_FILM_LDEXPF(x, e) std::ldexp((x), (e))
#define WP_FILM_WORDS_POINTER film_word *
#define WP_FILM_CONST_WORDS_POINTER const film_word *
#define WP_ATOMIC_ADD_WORD(p, v) std::atomic_ref<film_word>(*(p)).fetch_add(v)
#define WP_FILM_LEADING_ZEROS(m) std::countl_zero(m)
inline std::uint32_t wp_float_bits(float x) {
    std::uint32_t bits;
    std::memcpy(&bits, &x, sizeof bits);
    return bits;
}
#define WP_FLOAT_BITS(x) wp_float_bits(x)
#endif

#define WP_FILM_LIMBS 4
#define WP_FILM_FRACTION_BITS 100
#define WP_FILM_CLAMP_BITS 134 /* values are clamped to at most 2^134 */

typedef struct {
    film_limb limb[WP_FILM_LIMBS];
} film_sum;

WP_FILM_FN film_sum film_sum_zero(void) {
    film_sum s;
    WP_FILM_UNROLL for (int i = 0; i < WP_FILM_LIMBS; ++i) s.limb[i] = 0;
    return s;
}

WP_FILM_FN film_sum film_sum_add(film_sum a, film_sum b) {
    film_limb carry = 0;
    WP_FILM_UNROLL for (int i = 0; i < WP_FILM_LIMBS; ++i) {
        film_limb partial = a.limb[i] + b.limb[i];
        film_limb next_carry = partial < a.limb[i] ? 1 : 0;
        a.limb[i] = partial + carry;
        next_carry += a.limb[i] < partial ? 1 : 0;
        carry = next_carry;
    }
    return a;
}

WP_FILM_FN film_sum film_sum_negate(film_sum a) {
    film_limb carry = 1;
    WP_FILM_UNROLL for (int i = 0; i < WP_FILM_LIMBS; ++i) {
        a.limb[i] = ~a.limb[i] + carry;
        carry = carry && a.limb[i] == 0 ? 1 : 0;
    }
    return a;
}

/* Both clz and std::countl_zero give 64 for 0: one instruction, where a
 * loop over the bits cost accumulate most of its time. */
WP_FILM_FN int film_bit_length(film_limb m) { return 64 - WP_FILM_LEADING_ZEROS(m); }

/* (negative ? -1 : 1) * m * 2^exponent, m < 2^53, in fixed point. A value
 * of at least 2^-100 (every float sum's term but the tiniest) lands in two
 * adjacent limbs, placed by selects rather than an indexed store. */
WP_FILM_FN film_sum film_sum_from_scaled(film_limb m, int exponent, int negative) {
    int clamped = m != 0 && film_bit_length(m) + exponent > WP_FILM_CLAMP_BITS;
    int shift = clamped ? WP_FILM_CLAMP_BITS + WP_FILM_FRACTION_BITS : exponent + WP_FILM_FRACTION_BITS;
    film_sum s = film_sum_zero();
    if (clamped) m = 1;
    if (shift >= 0) {
        int word = shift >> 6, bit = shift & 63;
        film_limb low = m << bit;
        film_limb high = (m >> 1) >> (63 - bit); /* m >> (64 - bit), and 0 for bit 0 */
        WP_FILM_UNROLL for (int i = 0; i < WP_FILM_LIMBS; ++i) s.limb[i] = i == word ? low : (i == word + 1 ? high : 0);
    } else if (-shift < 54) { /* m < 2^53: a right shift of 54 or more leaves less than a half */
        int r = -shift;
        film_limb quotient = m >> r;
        film_limb remainder = m & ((((film_limb)1) << r) - 1);
        film_limb halfway = ((film_limb)1) << (r - 1);
        if (remainder > halfway || (remainder == halfway && (quotient & 1) != 0)) quotient += 1;
        s.limb[0] = quotient;
    }
    return negative ? film_sum_negate(s) : s;
}

/* A float's significand and exponent: x = m * 2^exponent (non-finite
 * values, which the guards never let through, count as the clamp). */
WP_FILM_FN film_limb film_float_significand(float x, int *exponent) {
    unsigned int bits = WP_FLOAT_BITS(x);
    int biased = (int)((bits >> 23) & 0xffu);
    film_limb m = bits & 0x7fffffu;
    if (biased == 255) {
        *exponent = WP_FILM_CLAMP_BITS;
        return 1;
    }
    if (biased != 0) m |= 0x800000u;
    *exponent = (biased == 0 ? 1 : biased) - 150;
    return m;
}

WP_FILM_FN film_sum film_sum_from_float(float x) {
    int exponent;
    film_limb m = film_float_significand(x, &exponent);
    return film_sum_from_scaled(m, exponent, (WP_FLOAT_BITS(x) >> 31) != 0);
}

/* x * x, exactly (a 48-bit significand), clamped like any value. */
WP_FILM_FN film_sum film_sum_from_float_squared(float x) {
    int exponent;
    film_limb m = film_float_significand(x, &exponent);
    return film_sum_from_scaled(m * m, 2 * exponent, 0);
}

/* A sum that many threads add to at once (SPPM's photon flux at a pixel,
 * which photons anywhere add to), kept as WP_FILM_WORDS 32-bit words, least
 * significant first: film_words_add adds each word of a non-negative value
 * with an atomic add, and a word that wraps carries 1 into the next with
 * another. Integer adds commute, so once every add has returned the words
 * hold the exact sum, whatever the order (OpenCL 1.2 has 32-bit integer
 * atomics, no float or 64-bit ones). */
#define WP_FILM_WORDS (2 * WP_FILM_LIMBS)

WP_FILM_FN void film_words_add(WP_FILM_WORDS_POINTER words, film_sum value) {
    for (int i = 0; i < WP_FILM_WORDS; ++i) {
        film_word part = (film_word)(value.limb[i / 2] >> (32 * (i % 2)));
        for (int k = i; part != 0u && k < WP_FILM_WORDS; ++k) {
            film_word before = WP_ATOMIC_ADD_WORD(&words[k], part);
            part = (film_word)(before + part) < before ? 1u : 0u; /* the carry */
        }
    }
}

/* The sum the words hold, once no add is under way. */
WP_FILM_FN film_sum film_sum_from_words(WP_FILM_CONST_WORDS_POINTER words) {
    film_sum s;
    WP_FILM_UNROLL for (int i = 0; i < WP_FILM_LIMBS; ++i) s.limb[i] =
        ((film_limb)words[2 * i + 1] << 32) | words[2 * i];
    return s;
}

/* The sum rounded once to the nearest float, ties to even (the photon
 * flux an SPPM iteration deposited at a pixel, shared/sppm.h): its top 64
 * bits from the highest set bit, every bit below them ORed into the lowest
 * (a sticky bit), then the 24 kept and rounded. Sums are multiples of
 * 2^-100, far above float's subnormals, so ldexp rounds nothing more; a sum
 * beyond float's range is infinite. */
WP_FILM_FN float film_sum_to_float(film_sum sum) {
    int negative = (sum.limb[WP_FILM_LIMBS - 1] >> 63) != 0;
    film_sum magnitude = negative ? film_sum_negate(sum) : sum;
    int top = WP_FILM_LIMBS - 1;
    while (top >= 0 && magnitude.limb[top] == 0) --top;
    if (top < 0) return 0.0f;
    int lead = 64 - film_bit_length(magnitude.limb[top]); /* leading zeros of the top limb */
    film_limb window = magnitude.limb[top] << lead;
    int sticky = 0;
    if (top > 0) {
        if (lead != 0) window |= magnitude.limb[top - 1] >> (64 - lead);
        sticky = (magnitude.limb[top - 1] << lead) != 0;
        for (int i = top - 2; i >= 0; --i) sticky = sticky || magnitude.limb[i] != 0;
    }
    film_limb kept = window >> 40; /* 24 bits, the highest set */
    film_limb rest = window & ((((film_limb)1) << 40) - 1);
    film_limb halfway = ((film_limb)1) << 39;
    if (rest > halfway || (rest == halfway && (sticky || (kept & 1) != 0))) kept += 1; /* 2^24 still converts exactly */
    float value = WP_FILM_LDEXPF((float)kept, 64 * top - lead + 40 - WP_FILM_FRACTION_BITS);
    return negative ? -value : value;
}

#endif
