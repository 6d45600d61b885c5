/* What the kernels that trace rays share (intersect.cl, intersect_shadow.cl,
 * and through wavefront.h every other kernel): the scene layout, the path
 * state, the queues, closest and any hit over the scene, and the guarded
 * radiance sum. Compiles for one lane or for WP_LANES (lanes.h), so it holds
 * nothing that branches on a value. Features absent from the scene (WP_HAS_*
 * options, see src/wavefront/kernel_options.cpp) are compiled out. */
#ifndef WP_TRACE_H
#define WP_TRACE_H

#include "prelude.h"
#include "geometry.h"
#if defined(WP_HAS_MIRROR) || defined(WP_HAS_GLASS)
#define WP_HAS_SPECULAR
#endif
#include "scene_layout.h"
#include "path_state.h"
#include "queues.h"

#define WP_SCENE_PARAMS                                                                                  \
    __global const SceneHeader *scene, __global const DeviceSphere *spheres, __global const DevicePlane *planes, \
        __global const DeviceQuad *quads, __global const DeviceMaterial *materials,                      \
        __global const DeviceLight *lights, __global const float *light_cdf
#define WP_SCENE_ARGS scene, spheres, planes, quads, materials, lights, light_cdf

/* The parameter list of every stage kernel, in this order (the host binds it
 * once per kernel, src/wavefront/pipeline.cpp). */
#define WP_STAGE_PARAMS                                                                                \
    WP_SCENE_PARAMS, __global uint *queues, __global uint *counts, uint capacity, ulong pass_start, uint pass_size, \
        __global float *pass_radiance, __global uint *slot_nonfinite WP_PATH_STATE_PARAMS

/* Shape and light counts: compile-time constants where the host passes them
 * (src/wavefront/kernel_options.cpp, small scenes), so the loops over them
 * unroll into straight-line code that runs as SIMD lanes;
 * otherwise read from the scene header at run time. */
#ifdef WP_SPHERE_COUNT
#define SPHERE_COUNT WP_SPHERE_COUNT
#else
#define SPHERE_COUNT scene->sphere_count
#endif
#ifdef WP_PLANE_COUNT
#define PLANE_COUNT WP_PLANE_COUNT
#else
#define PLANE_COUNT scene->plane_count
#endif
#ifdef WP_QUAD_COUNT
#define QUAD_COUNT WP_QUAD_COUNT
#else
#define QUAD_COUNT scene->quad_count
#endif
#ifdef WP_LIGHT_COUNT
#define LIGHT_COUNT WP_LIGHT_COUNT
#else
#define LIGHT_COUNT scene->light_count
#endif

WP_FN vec3 vec3_at(__global const float *p) { return make_vec3((real)p[0], (real)p[1], (real)p[2]); }

typedef struct {
    real t;
    lane_uint shape; /* WP_NO_HIT or (WP_SHAPE_* << WP_SHAPE_TYPE_SHIFT) | index */
} Hit;

WP_FN uint shape_id(uint type, uint index) { return (type << WP_SHAPE_TYPE_SHIFT) | index; }

/* Each shape's test, t in (0, t_max) or WP_INFINITY. */
WP_FN real sphere_t(__global const DeviceSphere *sphere, vec3 origin, vec3 direction, real t_max) {
    return intersect_sphere(vec3_at(sphere->center), sphere->radius, origin, direction, t_max);
}
WP_FN real plane_t(__global const DevicePlane *plane, vec3 origin, vec3 direction, real t_max) {
    return intersect_plane(vec3_at(plane->point), vec3_at(plane->normal), origin, direction, t_max);
}
WP_FN real quad_t(__global const DeviceQuad *quad, vec3 origin, vec3 direction, real t_max) {
    QuadPlane plane;
    plane.normal = vec3_at(quad->plane_normal);
    plane.w = vec3_at(quad->plane_w);
    return intersect_quad_plane(vec3_at(quad->corner), vec3_at(quad->edge1), vec3_at(quad->edge2), plane, origin,
                                direction, t_max);
}

/* `hit` moved to `shape` at t in the lanes where t is closer. */
WP_FN Hit keep_closer(Hit hit, real t, uint shape) {
    hit.shape = t < hit.t ? (lane_uint)shape : hit.shape;
    hit.t = fmin(t, hit.t);
    return hit;
}

/* Closest hit over spheres, then planes, then quads, as the reference tests them. */
WP_FN Hit closest_hit(WP_SCENE_PARAMS, vec3 origin, vec3 direction) {
    Hit hit;
    hit.t = WP_INFINITY;
    hit.shape = (lane_uint)WP_NO_HIT;
#ifdef WP_HAS_SPHERES
#pragma unroll
    for (uint i = 0; i < SPHERE_COUNT; ++i)
        hit = keep_closer(hit, sphere_t(&spheres[i], origin, direction, hit.t), shape_id(WP_SHAPE_SPHERE, i));
#endif
#ifdef WP_HAS_PLANES
#pragma unroll
    for (uint i = 0; i < PLANE_COUNT; ++i)
        hit = keep_closer(hit, plane_t(&planes[i], origin, direction, hit.t), shape_id(WP_SHAPE_PLANE, i));
#endif
#ifdef WP_HAS_QUADS
#pragma unroll
    for (uint i = 0; i < QUAD_COUNT; ++i)
        hit = keep_closer(hit, quad_t(&quads[i], origin, direction, hit.t), shape_id(WP_SHAPE_QUAD, i));
#endif
    return hit;
}

/* Whether any shape is hit at a distance below t_max. Every shape is tested
 * (no early exit), which keeps the unrolled loops free of branches. */
WP_FN lane_int any_hit(WP_SCENE_PARAMS, vec3 origin, vec3 direction, real t_max) {
    lane_int occluded = 0;
#ifdef WP_HAS_SPHERES
#pragma unroll
    for (uint i = 0; i < SPHERE_COUNT; ++i) occluded |= sphere_t(&spheres[i], origin, direction, t_max) < t_max;
#endif
#ifdef WP_HAS_PLANES
#pragma unroll
    for (uint i = 0; i < PLANE_COUNT; ++i) occluded |= plane_t(&planes[i], origin, direction, t_max) < t_max;
#endif
#ifdef WP_HAS_QUADS
#pragma unroll
    for (uint i = 0; i < QUAD_COUNT; ++i) occluded |= quad_t(&quads[i], origin, direction, t_max) < t_max;
#endif
    return occluded;
}

/* Adds `term` to the path's radiance unless the sum is not finite (a NaN or
 * Inf term, or an overflowing sum): then it is dropped and counted in
 * *dropped, so no non-finite value reaches the film. The caller adds *dropped
 * to the stage's counter (no atomics here: they would keep PoCL from
 * vectorising the stage). */
WP_FN vec3 add_finite(vec3 radiance, vec3 term, lane_uint *dropped) {
    vec3 sum = v3_add(radiance, term);
    lane_int finite = vec3_is_finite(sum);
    *dropped += finite ? (lane_uint)0u : (lane_uint)1u;
    return v3_select(finite, sum, radiance);
}

/* Appends `slot` to `queue` where `push` is set, one global atomic per work
 * group. Every work item of the group must call it (it has barriers); work
 * items past their queue's end push nothing. Kernels do not return early
 * before it, not even whole work groups: PoCL 3.1 then loses private values
 * across the barriers (the stage tests catch it). The
 * order inside a queue is not stable; nothing depends on it: a path's random
 * numbers are keyed by (pixel, sample, bounce), its result goes to its own
 * pass_radiance entry, and accumulation sums those in sample order. */
WP_FN void queue_push(__global uint *queues, __global uint *counts, uint capacity, uint queue, int push,
                      uint slot, __local uint *group_count, __local uint *group_base) {
#ifdef WP_COMPACT_SCAN
    /* Prefix-sum compaction (kernels/compact.cl) builds the queue from these
     * marks, in ascending slot order: no atomics, no barriers here. */
    if (push) queues[WP_QUEUE_MARKS(queue) * capacity + slot] = 1u;
    return;
#endif
    if (get_local_id(0) == 0) *group_count = 0u;
    barrier(CLK_LOCAL_MEM_FENCE);
    uint offset = push ? atomic_inc(group_count) : 0u;
    barrier(CLK_LOCAL_MEM_FENCE);
    if (get_local_id(0) == 0 && *group_count > 0u) *group_base = atomic_add(&counts[queue], *group_count);
    barrier(CLK_LOCAL_MEM_FENCE);
    if (push) queues[queue * capacity + *group_base + offset] = slot;
}

#endif
