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
#define WP_FILM_FN static inline
#define WP_FLOAT_BITS(x) as_uint(x)
#else
#include <cstdint>
#include <cstring>
typedef std::uint64_t film_limb;
#define WP_FILM_FN inline
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
    for (int i = 0; i < WP_FILM_LIMBS; ++i) s.limb[i] = 0;
    return s;
}

WP_FILM_FN film_sum film_sum_add(film_sum a, film_sum b) {
    film_limb carry = 0;
    for (int i = 0; i < WP_FILM_LIMBS; ++i) {
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
    for (int i = 0; i < WP_FILM_LIMBS; ++i) {
        a.limb[i] = ~a.limb[i] + carry;
        carry = carry && a.limb[i] == 0 ? 1 : 0;
    }
    return a;
}

WP_FILM_FN int film_bit_length(film_limb m) {
    int bits = 0;
    while (m != 0) {
        m >>= 1;
        ++bits;
    }
    return bits;
}

/* (negative ? -1 : 1) * m * 2^exponent, m < 2^53, in fixed point. */
WP_FILM_FN film_sum film_sum_from_scaled(film_limb m, int exponent, int negative) {
    film_sum s = film_sum_zero();
    int shift = exponent + WP_FILM_FRACTION_BITS;
    if (m == 0) return s;
    if (film_bit_length(m) + exponent > WP_FILM_CLAMP_BITS) {
        m = 1;
        shift = WP_FILM_CLAMP_BITS + WP_FILM_FRACTION_BITS;
    }
    if (shift >= 0) {
        int word = shift / 64, bit = shift % 64;
        s.limb[word] = m << bit;
        if (bit != 0 && word + 1 < WP_FILM_LIMBS) s.limb[word + 1] = m >> (64 - bit);
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

#endif
