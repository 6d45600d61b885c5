/* e^x, ln x, erf and its inverse, atan2 in turns, written out from +, -, *, /, sqrt, fabs,
 * floor, copysign and selects only (shared/prelude.h), so that every backend
 * computes the same bits: the library's exp, log and erf round their last
 * bits differently in libm and in PoCL. The microfacet models need them
 * (Beckmann's distribution, its masking function and its sampling,
 * shared/materials/microfacet.h), and textures and environment maps their
 * angles (shared/texture.h, shared/environment_map.h).
 *
 * Accuracy: float's, a few ulp (tests/shared/special_functions_test.cpp
 * measures each against std:: over its domain). The double build runs the same
 * polynomials, so these functions are no more accurate in double than in
 * float. */
#ifndef WP_SHARED_SPECIAL_FUNCTIONS_H
#define WP_SHARED_SPECIAL_FUNCTIONS_H

#include "shared/prelude.h"

#define WP_LN2 REAL(0.69314718055994530942)
#define WP_SQRT_PI REAL(1.77245385090551602730)
/* Cody and Waite's split of ln 2: the high part has 16 significant bits, so
 * k * WP_LN2_HIGH is exact for every |k| < 2^8 and x - k ln 2 loses nothing. */
#define WP_LN2_HIGH REAL(0.693145751953125)
#define WP_LN2_LOW REAL(1.42860682030941723212e-6)
/* e^x for x in [WP_EXP_MIN, WP_EXP_MAX] is a normal float. */
#define WP_EXP_MIN REAL(-87.0)
#define WP_EXP_MAX REAL(88.0)
/* 2^64, the largest step of wp_log's scaling. */
#define WP_TWO_TO_64 REAL(18446744073709551616.0)

/* 2^k for an integer k with |k| <= 127, exactly: the product of the powers
 * 2^(2^j) of |k|'s binary digits (each a power of two, so no product rounds),
 * inverted for a negative k. */
WP_FN real power_of_two(real k) {
    lane_int n = TO_LANE_INT(fabs(k));
    real p = REAL(1.0);
    p = (n & 1) != 0 ? p * REAL(2.0) : p;
    p = (n & 2) != 0 ? p * REAL(4.0) : p;
    p = (n & 4) != 0 ? p * REAL(16.0) : p;
    p = (n & 8) != 0 ? p * REAL(256.0) : p;
    p = (n & 16) != 0 ? p * REAL(65536.0) : p;
    p = (n & 32) != 0 ? p * REAL(4294967296.0) : p;
    p = (n & 64) != 0 ? p * WP_TWO_TO_64 : p;
    return k < REAL(0.0) ? REAL(1.0) / p : p;
}

/* e^x: x = k ln 2 + r with the integer k nearest x / ln 2 and |r| <= ln 2 / 2,
 * then e^x = 2^k e^r with e^r's Taylor polynomial through r^8, whose remainder
 * is below (ln 2 / 2)^9 / 9! < 2.0e-10 relative. Below WP_EXP_MIN it returns 0
 * (e^x is then below float's smallest normal number, where float flushes to
 * zero on some devices); above WP_EXP_MAX, e^WP_EXP_MAX. */
WP_FN real wp_exp(real x) {
    real clamped = wp_clamp(x, WP_EXP_MIN, WP_EXP_MAX);
    real k = floor(clamped / WP_LN2 + REAL(0.5));
    real r = (clamped - k * WP_LN2_HIGH) - k * WP_LN2_LOW;
    /* Horner form of sum r^n / n!, n = 0..8 */
    real p = REAL(1.0) / REAL(40320.0);
    p = p * r + REAL(1.0) / REAL(5040.0);
    p = p * r + REAL(1.0) / REAL(720.0);
    p = p * r + REAL(1.0) / REAL(120.0);
    p = p * r + REAL(1.0) / REAL(24.0);
    p = p * r + REAL(1.0) / REAL(6.0);
    p = p * r + REAL(0.5);
    p = p * r + REAL(1.0);
    p = p * r + REAL(1.0);
    return x < WP_EXP_MIN ? REAL(0.0) : p * power_of_two(k);
}

/* ln x for x in [2^-126, 2^128) (float's normal numbers; x outside is first
 * clamped into that range, so 0 gives ln 2^-126 = -87.3). x = 2^e m with
 * m in [sqrt(1/2), sqrt(2)), found by exact scalings by powers of two; then
 * ln m = 2 atanh(s), s = (m - 1) / (m + 1), |s| <= 0.1716, by its series
 * through s^11, whose remainder is below 1e-10 relative to ln m. */
WP_FN real wp_log(real x) {
    real m = wp_clamp(x, REAL(1.17549435082228750797e-38), REAL(3.40282346638528859812e+38));
    real e = REAL(0.0);
    /* Down into [1, 2) from above, dividing by 2^64, 2^32, ..., 2 where m is
     * at least that; then up into [1, 2) from below, multiplying by 2^j where
     * m < 2^(1 - j). Each step is exact; each loop runs only where some lane
     * needs it (the samplers take logarithms of numbers below 1). */
    real_element step = REAL(64.0), scale = WP_TWO_TO_64;
    for (int j = 0; j < 7 && lanes_any(m >= REAL(2.0)); ++j, step *= REAL(0.5), scale = sqrt(scale)) {
        lane_int big = m >= scale;
        m = big ? m / scale : m;
        e = big ? e + step : e;
    }
    step = REAL(64.0), scale = WP_TWO_TO_64;
    for (int j = 0; j < 7 && lanes_any(m < REAL(1.0)); ++j, step *= REAL(0.5), scale = sqrt(scale)) {
        lane_int small = m < REAL(2.0) / scale;
        m = small ? m * scale : m;
        e = small ? e - step : e;
    }
    lane_int above_sqrt2 = m > REAL(1.41421356237309504880);
    m = above_sqrt2 ? m * REAL(0.5) : m;
    e = above_sqrt2 ? e + REAL(1.0) : e;
    real s = (m - REAL(1.0)) / (m + REAL(1.0));
    real s2 = s * s;
    /* Horner form of sum s^(2n) / (2n + 1), n = 0..5 */
    real p = REAL(1.0) / REAL(11.0);
    p = p * s2 + REAL(1.0) / REAL(9.0);
    p = p * s2 + REAL(1.0) / REAL(7.0);
    p = p * s2 + REAL(1.0) / REAL(5.0);
    p = p * s2 + REAL(1.0) / REAL(3.0);
    p = p * s2 + REAL(1.0);
    real log_m = REAL(2.0) * s * p;
    return e * WP_LN2_HIGH + (e * WP_LN2_LOW + log_m);
}

/* erf x. For |x| < 1/2, its Taylor series through x^13 (the remainder is
 * below 2 / sqrt(pi) x^15 / (7! 15) < 1e-9 relative); beyond, 1 - erfc |x|
 * with Numerical Recipes' Chebyshev fit of erfc (Press et al., Numerical
 * Recipes in C, 2nd ed., section 6.2, erfcc: fractional error below 1.2e-7
 * everywhere), whose value is below 1/2 there, so erf keeps float's relative
 * accuracy. */
WP_FN real wp_erf(real x) {
    real z = fabs(x);
    real z2 = z * z;
    /* Horner form of sum (-1)^n z^(2n) / (n! (2n + 1)), n = 0..6 */
    real series = REAL(1.0) / REAL(9360.0);
    series = series * z2 - REAL(1.0) / REAL(1320.0);
    series = series * z2 + REAL(1.0) / REAL(216.0);
    series = series * z2 - REAL(1.0) / REAL(42.0);
    series = series * z2 + REAL(1.0) / REAL(10.0);
    series = series * z2 - REAL(1.0) / REAL(3.0);
    series = series * z2 + REAL(1.0);
    series = series * z * (REAL(2.0) / WP_SQRT_PI);
    /* erfc z = t e^(q(t) - z^2), t = 1 / (1 + z / 2), q in Horner form */
    real t = REAL(1.0) / (REAL(1.0) + REAL(0.5) * z);
    real q = REAL(0.17087277);
    q = q * t - REAL(0.82215223);
    q = q * t + REAL(1.48851587);
    q = q * t - REAL(1.13520398);
    q = q * t + REAL(0.27886807);
    q = q * t - REAL(0.18628806);
    q = q * t + REAL(0.09678418);
    q = q * t + REAL(0.37409196);
    q = q * t + REAL(1.00002368);
    q = q * t - REAL(1.26551223);
    real complement = t * wp_exp(q - z2);
    return copysign(z < REAL(0.5) ? series : REAL(1.0) - complement, x);
}

/* The inverse of erf on (-1, 1): Giles' single-precision approximation
 * (M. Giles, "Approximating the erfinv function", GPU Computing Gems Jade
 * Edition, 2011, ch. 10): polynomials in w = -ln(1 - y^2), one in w for
 * w < 5 and one in sqrt(w) beyond, with a relative error of a few float ulp
 * (measured by the test). At +-1 it returns about +-9.3 (wp_log's clamp),
 * not infinity. */
WP_FN real wp_erfinv(real y) {
    real w = -wp_log((REAL(1.0) - y) * (REAL(1.0) + y));
    real central = w - REAL(2.5);
    real p = REAL(2.81022636e-08);
    p = p * central + REAL(3.43273939e-07);
    p = p * central - REAL(3.5233877e-06);
    p = p * central - REAL(4.39150654e-06);
    p = p * central + REAL(0.00021858087);
    p = p * central - REAL(0.00125372503);
    p = p * central - REAL(0.00417768164);
    p = p * central + REAL(0.246640727);
    p = p * central + REAL(1.50140941);
    real tail = sqrt(w) - REAL(3.0);
    real q = REAL(-0.000200214257);
    q = q * tail + REAL(0.000100950558);
    q = q * tail + REAL(0.00134934322);
    q = q * tail - REAL(0.00367342844);
    q = q * tail + REAL(0.00573950773);
    q = q * tail - REAL(0.0076224613);
    q = q * tail + REAL(0.00943887047);
    q = q * tail + REAL(1.00167406);
    q = q * tail + REAL(2.83297682);
    return (w < REAL(5.0) ? p : q) * y;
}

/* atan2(y, x) / (2 pi) in [0, 1) (0 for the origin): the quadrant's
 * reduction to a in [0, 1], then to |t| <= tan(pi/8) by
 * atan(a) = pi/4 + atan((a - 1) / (a + 1)), where atan's series through
 * t^19 errs by less than 5e-10. */
WP_FN real atan2_turns(real y, real x) {
    real ax = fabs(x), ay = fabs(y);
    real big = fmax(ax, ay), small = fmin(ax, ay);
    real a = big > REAL(0.0) ? small / big : REAL(0.0);
    lane_int shifted = a > REAL(0.41421356237309504880);
    real t = shifted ? (a - REAL(1.0)) / (a + REAL(1.0)) : a;
    real t2 = t * t;
    real s = REAL(1.0) / REAL(19.0);
    s = s * t2 - REAL(1.0) / REAL(17.0);
    s = s * t2 + REAL(1.0) / REAL(15.0);
    s = s * t2 - REAL(1.0) / REAL(13.0);
    s = s * t2 + REAL(1.0) / REAL(11.0);
    s = s * t2 - REAL(1.0) / REAL(9.0);
    s = s * t2 + REAL(1.0) / REAL(7.0);
    s = s * t2 - REAL(1.0) / REAL(5.0);
    s = s * t2 + REAL(1.0) / REAL(3.0);
    s = s * t2 - REAL(1.0);
    real angle = -s * t + (shifted ? WP_PI / REAL(4.0) : REAL(0.0)); /* atan(a), in [0, pi/4] */
    angle = ay > ax ? WP_PI / REAL(2.0) - angle : angle;
    angle = x < REAL(0.0) ? WP_PI - angle : angle;
    real turns = angle * (REAL(0.5) * WP_INV_PI); /* [0, 1/2] */
    return y < REAL(0.0) && turns > REAL(0.0) ? REAL(1.0) - turns : turns;
}

#endif
