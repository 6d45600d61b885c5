/* Type and function mapping that lets the shared math compile both as
 * OpenCL C (float only) and as C++ (float or double, via src/core/shared_math.h).
 *
 * Rules for the code in kernels/common:
 *   - functions are WP_FN, take and return values (no references, no templates);
 *   - scalars are `real`, vectors `vec3` built with make_vec3(x, y, z) and
 *     combined only through the v3_* functions below, never with operators:
 *     in OpenCL C vec3 is a struct of three scalars, not float3, because
 *     PoCL's loop vectoriser (which runs a work group's work items in SIMD
 *     lanes) gives up on any instruction of a vector type;
 *   - only sqrt, fabs, fmin, fmax, floor and copysign on scalars are assumed
 *     to exist on both sides (no sin or cos: calls into the OpenCL library
 *     cannot be vectorised; see wp_sincos_turns);
 *   - floating constants are written REAL(1.0) (always with a decimal point);
 *   - pointers into device memory are WP_GLOBAL.
 */
#ifdef __OPENCL_C_VERSION__
#pragma OPENCL FP_CONTRACT OFF
#define WP_FN static inline
#define WP_GLOBAL __global
typedef float real;
typedef struct {
    float x, y, z;
} vec3;
typedef int real_bits; /* integer of the same width as real, for ULP offsets */
WP_FN vec3 make_vec3(real x, real y, real z) {
    vec3 v;
    v.x = x, v.y = y, v.z = z;
    return v;
}
#define REAL(x) (x##f)
#define real_as_bits(x) as_int(x)
#define bits_as_real(x) as_float(x)
#define WP_REAL_MAX FLT_MAX
#define WP_REAL_MANTISSA_BITS 24
#else
/* C++: the including namespace (src/core/shared_math.h) defines `real`,
 * `real_bits`, `vec3`, `uint`, `real_max` and `real_mantissa_bits`. */
#define WP_FN static inline
#define WP_GLOBAL
#define make_vec3(x, y, z) (vec3((x), (y), (z)))
#define REAL(x) (static_cast<real>(x))
#define real_as_bits(x) (std::bit_cast<real_bits>(static_cast<real>(x)))
#define bits_as_real(x) (std::bit_cast<real>(static_cast<real_bits>(x)))
#define WP_REAL_MAX real_max
#define WP_REAL_MANTISSA_BITS real_mantissa_bits
#endif

#define WP_PI REAL(3.14159265358979323846)
#define WP_INV_PI REAL(0.31830988618379067154)
#define WP_INFINITY WP_REAL_MAX

/* Vector arithmetic, written once for both sides and component by component
 * in the same order, so kernels and C++ round alike. */
WP_FN vec3 v3_add(vec3 a, vec3 b) { return make_vec3(a.x + b.x, a.y + b.y, a.z + b.z); }
WP_FN vec3 v3_sub(vec3 a, vec3 b) { return make_vec3(a.x - b.x, a.y - b.y, a.z - b.z); }
WP_FN vec3 v3_mul(vec3 a, vec3 b) { return make_vec3(a.x * b.x, a.y * b.y, a.z * b.z); } /* per component */
WP_FN vec3 v3_scale(vec3 a, real s) { return make_vec3(a.x * s, a.y * s, a.z * s); }
WP_FN vec3 v3_div(vec3 a, real s) { return make_vec3(a.x / s, a.y / s, a.z / s); }
WP_FN vec3 v3_neg(vec3 a) { return make_vec3(-a.x, -a.y, -a.z); }
/* a + s * b */
WP_FN vec3 v3_add_scaled(vec3 a, real s, vec3 b) { return make_vec3(a.x + s * b.x, a.y + s * b.y, a.z + s * b.z); }
WP_FN real v3_dot(vec3 a, vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
WP_FN vec3 v3_cross(vec3 a, vec3 b) {
    return make_vec3(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);
}
WP_FN real v3_length(vec3 a) { return sqrt(v3_dot(a, a)); }
WP_FN vec3 v3_normalize(vec3 a) { return v3_scale(a, REAL(1.0) / v3_length(a)); }
/* a if choose_a, else b: a select in the kernels, not a branch. */
WP_FN vec3 v3_select(int choose_a, vec3 a, vec3 b) {
    return make_vec3(choose_a ? a.x : b.x, choose_a ? a.y : b.y, choose_a ? a.z : b.z);
}

WP_FN real wp_clamp(real x, real lo, real hi) { return fmin(fmax(x, lo), hi); }
WP_FN real wp_sqr(real x) { return x * x; }
/* sqrt that tolerates arguments a rounding error below zero. */
WP_FN real safe_sqrt(real x) { return sqrt(fmax(x, REAL(0.0))); }
WP_FN real max_component(vec3 v) { return fmax(v.x, fmax(v.y, v.z)); }
WP_FN int vec3_is_finite(vec3 v) { return isfinite(v.x) && isfinite(v.y) && isfinite(v.z); }
/* Rec. 709 luminance, used for light selection by power. */
WP_FN real luminance(vec3 c) { return REAL(0.2126) * c.x + REAL(0.7152) * c.y + REAL(0.0722) * c.z; }
