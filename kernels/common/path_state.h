/* The wavefront's path state, declared once. Every field is one device buffer
 * with one element per path slot (structure of arrays). The list expands into
 * the host's buffers (src/wavefront/path_state.cpp), the kernels' parameter
 * lists (WP_PATH_STATE_PARAMS below), the bytes-per-path estimate and the
 * table in docs/architecture.md, so adding a field is one line here.
 *
 * X(type, name, feature, written by, read by), where feature says when the
 * buffer exists:
 *   ALWAYS   every scene;
 *   SPECULAR the scene has a mirror or glass material (otherwise every
 *            bounce is diffuse and "previous vertex specular" is depth == 0);
 *   NEE      the scene has at least one light (next-event estimation). */
#ifndef WP_PATH_STATE_H
#define WP_PATH_STATE_H

#define WP_PATH_STATE(X)                                                                            \
    X(uint, pixel, ALWAYS, "generate", "shade_direct scatter")                                      \
    X(uint, sample, ALWAYS, "generate", "shade_direct scatter")                                     \
    X(uint, pass_item, ALWAYS, "generate", "intersect shade_direct scatter")                        \
    X(uint, depth, ALWAYS, "generate scatter", "shade_direct scatter")                              \
    X(float, origin_x, ALWAYS, "generate scatter", "intersect shade_direct scatter")                \
    X(float, origin_y, ALWAYS, "generate scatter", "intersect shade_direct scatter")                \
    X(float, origin_z, ALWAYS, "generate scatter", "intersect shade_direct scatter")                \
    X(float, direction_x, ALWAYS, "generate scatter", "intersect shade_direct scatter")             \
    X(float, direction_y, ALWAYS, "generate scatter", "intersect shade_direct scatter")             \
    X(float, direction_z, ALWAYS, "generate scatter", "intersect shade_direct scatter")             \
    X(float, throughput_r, ALWAYS, "generate scatter", "intersect shade_direct scatter")            \
    X(float, throughput_g, ALWAYS, "generate scatter", "intersect shade_direct scatter")            \
    X(float, throughput_b, ALWAYS, "generate scatter", "intersect shade_direct scatter")            \
    X(float, radiance_r, ALWAYS, "generate intersect shade_direct intersect_shadow",                \
      "intersect shade_direct intersect_shadow scatter")                                           \
    X(float, radiance_g, ALWAYS, "generate intersect shade_direct intersect_shadow",                \
      "intersect shade_direct intersect_shadow scatter")                                           \
    X(float, radiance_b, ALWAYS, "generate intersect shade_direct intersect_shadow",                \
      "intersect shade_direct intersect_shadow scatter")                                           \
    X(float, hit_t, ALWAYS, "intersect", "shade_direct scatter")                                    \
    X(uint, hit_shape, ALWAYS, "intersect", "shade_direct scatter")                                 \
    X(uint, specular, SPECULAR, "generate scatter", "shade_direct")                                 \
    X(float, shadow_origin_x, NEE, "shade_direct", "intersect_shadow")                              \
    X(float, shadow_origin_y, NEE, "shade_direct", "intersect_shadow")                              \
    X(float, shadow_origin_z, NEE, "shade_direct", "intersect_shadow")                              \
    X(float, shadow_direction_x, NEE, "shade_direct", "intersect_shadow")                           \
    X(float, shadow_direction_y, NEE, "shade_direct", "intersect_shadow")                           \
    X(float, shadow_direction_z, NEE, "shade_direct", "intersect_shadow")                           \
    X(float, shadow_distance, NEE, "shade_direct", "intersect_shadow")                              \
    X(float, shadow_radiance_r, NEE, "shade_direct", "intersect_shadow")                            \
    X(float, shadow_radiance_g, NEE, "shade_direct", "intersect_shadow")                            \
    X(float, shadow_radiance_b, NEE, "shade_direct", "intersect_shadow")

#ifdef __OPENCL_C_VERSION__
/* WP_IF_<feature>(...) keeps its arguments only when the feature is compiled in. */
#define WP_IF_ALWAYS(...) __VA_ARGS__
#ifdef WP_HAS_SPECULAR
#define WP_IF_SPECULAR(...) __VA_ARGS__
#else
#define WP_IF_SPECULAR(...)
#endif
#ifdef WP_HAS_NEE
#define WP_IF_NEE(...) __VA_ARGS__
#else
#define WP_IF_NEE(...)
#endif

/* ", __global float* origin_x, ..." for the fields of the compiled features;
 * every stage kernel ends its parameter list with it, so the host binds the
 * same buffers at the same positions for every stage. */
#define WP_PATH_STATE_PARAM(type, name, feature, writers, readers) WP_IF_##feature(, __global type* restrict name)
#define WP_PATH_STATE_PARAMS WP_PATH_STATE(WP_PATH_STATE_PARAM)
#endif

#endif
