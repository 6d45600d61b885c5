/* Type and function mapping that lets the shared math compile both as
 * OpenCL C (float only) and as C++ (float or double, via src/core/shared_math.h).
 *
 * Rules for the code in kernels/common:
 *   - functions are WP_FN, take and return values (no references, no templates);
 *   - scalars are `real`, vectors `vec3` built with make_vec3(x, y, z);
 *   - floating constants are written REAL(1.0) (always with a decimal point);
 *   - only dot, cross, normalize, length, sqrt, fabs, fmin, fmax, floor, sin,
 *     cos, atan2, acos and copysign on scalars are assumed to exist on both sides;
 *   - pointers into device memory are WP_GLOBAL.
 */
#ifdef __OPENCL_C_VERSION__
#pragma OPENCL FP_CONTRACT OFF
#define WP_FN static inline
#define WP_GLOBAL __global
typedef float real;
typedef float3 vec3;
typedef int real_bits; /* integer of the same width as real, for ULP offsets */
#define make_vec3(x, y, z) ((float3)((x), (y), (z)))
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

WP_FN real wp_clamp(real x, real lo, real hi) { return fmin(fmax(x, lo), hi); }
WP_FN real wp_sqr(real x) { return x * x; }
/* sqrt that tolerates arguments a rounding error below zero. */
WP_FN real safe_sqrt(real x) { return sqrt(fmax(x, REAL(0.0))); }
WP_FN real max_component(vec3 v) { return fmax(v.x, fmax(v.y, v.z)); }
WP_FN int vec3_is_finite(vec3 v) { return isfinite(v.x) && isfinite(v.y) && isfinite(v.z); }
/* Rec. 709 luminance, used for light selection by power. */
WP_FN real luminance(vec3 c) { return REAL(0.2126) * c.x + REAL(0.7152) * c.y + REAL(0.0722) * c.z; }
