/* Type and function mapping that lets the shared math compile both as
 * OpenCL C (float only) and as C++ (float or double, via src/core/shared_math.h).
 *
 * Lanes: in OpenCL C a work item may handle WP_LANES paths at once (built
 * with -DWP_LANES=4, 8 or 16, see kernels/device/lanes.h); `real` is then
 * float4, float8 or float16 and every operation runs on all lanes. PoCL does not vectorise the stage
 * kernels across work items by itself (its SLP pass packs scalar code into
 * small vectors first, which its loop vectoriser then refuses), so the SIMD
 * the wavefront is built for is written out. WP_LANES is 1 by default.
 *
 * Rules for the code in kernels/shared, so that it compiles for one lane or
 * for many and as C++:
 *   - functions are WP_FN, take and return values (no references, no templates);
 *   - scalars are `real`, conditions on them `lane_int`; vectors are `vec3`,
 *     built with make_vec3(x, y, z) and combined only through the v3_*
 *     functions below, never with operators (vec3 is a struct of three
 *     `real`s, not float3);
 *   - code that must also run with many lanes chooses with `c ? a : b`, never
 *     with `if` on a value (but on lanes_any of one, to skip work no lane
 *     needs), and combines conditions with && and ||;
 *   - only sqrt, fabs, fmin, fmax, floor and copysign on scalars are assumed
 *     to exist on both sides (no sin or cos: see cos_sin_turns);
 *   - floating constants are written REAL(1.0) (always with a decimal point);
 *   - device memory is read at per-lane indices with gather(p, index), and
 *     pointers into it are WP_GLOBAL.
 */
#ifndef WP_SHARED_PRELUDE_H
#define WP_SHARED_PRELUDE_H

#ifdef __OPENCL_C_VERSION__
#pragma OPENCL FP_CONTRACT OFF
#define WP_FN static inline
#define WP_GLOBAL __global
#ifndef WP_LANES
#define WP_LANES 1
#endif
typedef float real_element; /* what a `real` is stored as in device memory */
#if WP_LANES == 1
typedef float real;
typedef int lane_int;
typedef uint lane_uint;
#define TO_REAL(x) ((real)(x))
#define TO_LANE_INT(x) ((lane_int)(x))
#define TO_LANE_UINT(x) ((lane_uint)(x))
#else
/* F(s0, 0) F(s1, 1) ...: code once per lane, given its component and its
 * number (kernels/device/lane_memory.h, kernels/device/lanes.h). */
#define WP_LANES_0_TO_3(F) F(s0, 0) F(s1, 1) F(s2, 2) F(s3, 3)
#define WP_LANES_4_TO_7(F) F(s4, 4) F(s5, 5) F(s6, 6) F(s7, 7)
#define WP_LANES_8_TO_15(F) F(s8, 8) F(s9, 9) F(sa, 10) F(sb, 11) F(sc, 12) F(sd, 13) F(se, 14) F(sf, 15)
#if WP_LANES == 4
#define WP_FOR_LANES(F) WP_LANES_0_TO_3(F)
#elif WP_LANES == 8
#define WP_FOR_LANES(F) WP_LANES_0_TO_3(F) WP_LANES_4_TO_7(F)
#elif WP_LANES == 16
#define WP_FOR_LANES(F) WP_LANES_0_TO_3(F) WP_LANES_4_TO_7(F) WP_LANES_8_TO_15(F)
#else
#error "WP_LANES must be 1, 4, 8 or 16"
#endif
/* name##WP_LANES: the lanes' vector type or built-in (float8, vload8 with 8 lanes). */
#define WP_PASTE(name, lanes) name##lanes
#define WP_LANE_NAME(name, lanes) WP_PASTE(name, lanes)
#define WP_LANE_VECTOR(name) WP_LANE_NAME(name, WP_LANES)
typedef WP_LANE_VECTOR(float) real;
typedef WP_LANE_VECTOR(int) lane_int; /* a condition: -1 (all bits) where true, as OpenCL's vector comparisons give */
typedef WP_LANE_VECTOR(uint) lane_uint;
#define TO_REAL(x) WP_LANE_VECTOR(convert_float)(x)
#define TO_LANE_INT(x) WP_LANE_VECTOR(convert_int)(x) /* toward zero, as a C cast */
#define TO_LANE_UINT(x) WP_LANE_VECTOR(convert_uint)(x)
/* The WP_LANES consecutive elements at p. */
#define LANES_LOAD(p) WP_LANE_VECTOR(vload)(0, p)
#endif
/* A shared function that LLVM's inliner left as a call in a shading kernel,
 * its vectors passed through the stack (found by the calls left in PoCL's
 * kernel objects): always inlined. Not every function: inlining all of them
 * cut the material scene's kernel instructions by a quarter but doubled the
 * kernels' build time (bench/results/analysis.md, "Inlining"). */
#define WP_INLINED_FN static inline __attribute__((always_inline))
/* A function that repeats its body per lane (WP_FOR_LANES): always inlined
 * too. At 16 lanes LLVM's inliner otherwise calls it, its vector arguments and
 * result passed through the stack (the shading stages ran at half speed). */
#define WP_LANE_FN WP_INLINED_FN
/* Kernel-side functions overloaded on their pointer's type (clang's
 * extension, which every OpenCL C compiler built on clang has). */
#define WP_OVERLOAD __attribute__((overloadable))
typedef struct {
    real x, y, z;
} vec3;
WP_FN vec3 make_vec3(real x, real y, real z) {
    vec3 v;
    v.x = x, v.y = y, v.z = z;
    return v;
}
#define REAL(x) (x##f)
#define WP_REAL_MAX FLT_MAX
#define WP_UNIT_ROUNDOFF REAL(5.9604644775390625e-08) /* 2^-24, float's */

/* p[index] for each lane's index: a plain load with one lane, one load per
 * lane (a gather) with several. */
#if WP_LANES == 1
WP_OVERLOAD WP_FN real gather(__global const float *p, lane_uint index) { return p[index]; }
WP_OVERLOAD WP_FN lane_uint gather(__global const uint *p, lane_uint index) { return p[index]; }
#else
#define WP_GATHER_LANE(s, k) p[index.s],
WP_OVERLOAD WP_LANE_FN real gather(__global const float *p, lane_uint index) {
    float values[WP_LANES] = {WP_FOR_LANES(WP_GATHER_LANE)};
    return LANES_LOAD(values);
}
WP_OVERLOAD WP_LANE_FN lane_uint gather(__global const uint *p, lane_uint index) {
    uint values[WP_LANES] = {WP_FOR_LANES(WP_GATHER_LANE)};
    return LANES_LOAD(values);
}
#undef WP_GATHER_LANE
#endif

/* The lanes' counts added up, and lanes_any (below) for several lanes. */
#if WP_LANES == 1
WP_FN uint lanes_sum(lane_uint x) { return x; }
#else
/* Whether any lane's sign bit is set, as any() answers: the vector's halves
 * ORed together down to two ints. PoCL's any() tests the lanes one by one,
 * which took 8% of the material scene's kernel instructions (callgrind,
 * bench/results/analysis.md, "`lanes_any`"). */
WP_FN int sign_any2(int2 condition) { return (condition.x | condition.y) < 0; }
WP_FN int sign_any4(int4 condition) { return sign_any2(condition.lo | condition.hi); }
WP_FN int sign_any8(int8 condition) { return sign_any4(condition.lo | condition.hi); }
WP_FN int sign_any16(int16 condition) { return sign_any8(condition.lo | condition.hi); }
WP_FN int lanes_any(lane_int condition) { return WP_LANE_VECTOR(sign_any)(condition); }
#define WP_ADD_LANE(s, k) sum += x.s;
WP_LANE_FN uint lanes_sum(lane_uint x) {
    uint sum = 0u;
    WP_FOR_LANES(WP_ADD_LANE)
    return sum;
}
#undef WP_ADD_LANE
#endif
#else
/* C++: the including namespace (src/core/shared_math.h) defines `real`,
 * `vec3`, `uint`, `real_max` and `unit_roundoff`; one lane. */
#define WP_FN static inline
#define WP_INLINED_FN static inline
#define WP_GLOBAL
typedef int lane_int;
typedef uint lane_uint;
typedef real real_element;
#define TO_REAL(x) (static_cast<real>(x))
#define TO_LANE_INT(x) (static_cast<lane_int>(x))
#define TO_LANE_UINT(x) (static_cast<lane_uint>(x))
template <class T>
static T gather(const T *p, uint index) {
    return p[index];
}
#define make_vec3(x, y, z) (vec3((x), (y), (z)))
#define REAL(x) (static_cast<real>(x))
#define WP_REAL_MAX real_max
#define WP_UNIT_ROUNDOFF unit_roundoff
#endif

/* Whether a condition holds in any lane: a loop runs while some lane needs
 * it, and work no lane needs is skipped. Here for one lane (C++, and kernels
 * of one lane); for several, above. */
#if !defined(__OPENCL_C_VERSION__) || WP_LANES == 1
WP_FN int lanes_any(lane_int condition) { return condition != 0; }
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
WP_FN vec3 v3_select(lane_int choose_a, vec3 a, vec3 b) {
    return make_vec3(choose_a ? a.x : b.x, choose_a ? a.y : b.y, choose_a ? a.z : b.z);
}

/* (p[index], p[index + 1], p[index + 2]) per lane: an RGB texel. With
 * several lanes, each lane's three values come in one 4-wide load, where
 * three gathers took a load per lane each (scalar loads on PoCL's CPUs), so
 * p[index + 3] must lie in the buffer too: the texel buffers end in a spare
 * value (scene/texture_layout.h; an environment map's texels are followed
 * by its distributions). */
#if defined(__OPENCL_C_VERSION__) && WP_LANES > 1
#define WP_LOAD_TEXEL_LANE(s, k) float4 texel##k = vload4(0, p + index.s);
#define WP_RED_LANE(s, k) texel##k.x,
#define WP_GREEN_LANE(s, k) texel##k.y,
#define WP_BLUE_LANE(s, k) texel##k.z,
WP_LANE_FN vec3 gather_rgb(__global const float *p, lane_uint index) {
    WP_FOR_LANES(WP_LOAD_TEXEL_LANE)
    float red[WP_LANES] = {WP_FOR_LANES(WP_RED_LANE)};
    float green[WP_LANES] = {WP_FOR_LANES(WP_GREEN_LANE)};
    float blue[WP_LANES] = {WP_FOR_LANES(WP_BLUE_LANE)};
    return make_vec3(LANES_LOAD(red), LANES_LOAD(green), LANES_LOAD(blue));
}
#undef WP_LOAD_TEXEL_LANE
#undef WP_RED_LANE
#undef WP_GREEN_LANE
#undef WP_BLUE_LANE
#else
WP_FN vec3 gather_rgb(WP_GLOBAL const real_element *p, lane_uint index) {
    return make_vec3(p[index], p[index + 1u], p[index + 2u]);
}
#endif

WP_FN real wp_clamp(real x, real lo, real hi) { return fmin(fmax(x, lo), hi); }
/* sqrt that tolerates arguments a rounding error below zero. */
WP_FN real safe_sqrt(real x) { return sqrt(fmax(x, REAL(0.0))); }
WP_FN real max_component(vec3 v) { return fmax(v.x, fmax(v.y, v.z)); }
WP_FN lane_int vec3_is_finite(vec3 v) { return isfinite(v.x) && isfinite(v.y) && isfinite(v.z); }

#endif
