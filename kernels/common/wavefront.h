/* What every wavefront stage kernel shares: the shared math, the scene
 * layout, the path state, the queues, closest/any hit over the scene and the
 * end of a path. Features absent from the scene (WP_HAS_* options, see
 * src/wavefront/kernel_options.cpp) are compiled out. */
#ifndef WP_WAVEFRONT_H
#define WP_WAVEFRONT_H

#include "prelude.h"
#include "rng.h"
#include "geometry.h"
#include "offset.h"
#include "sampling.h"
#if defined(WP_HAS_MIRROR) || defined(WP_HAS_GLASS)
#include "fresnel.h"
#endif
#ifndef WP_HAS_GLASS
/* Without glass the dielectric code must not be compiled in: any use is a build error. */
#pragma GCC poison fresnel_dielectric refract_direction
#endif
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
 * unroll into straight-line code that PoCL vectorises across work items;
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

#define LOAD_XYZ(name, i) make_vec3(name##_x[i], name##_y[i], name##_z[i])
#define LOAD_RGB(name, i) make_vec3(name##_r[i], name##_g[i], name##_b[i])
#define STORE_XYZ(name, i, v) (name##_x[i] = (v).x, name##_y[i] = (v).y, name##_z[i] = (v).z)
#define STORE_RGB(name, i, v) (name##_r[i] = (v).x, name##_g[i] = (v).y, name##_b[i] = (v).z)

WP_FN vec3 vec3_at(__global const float *p) { return make_vec3(p[0], p[1], p[2]); }

/* Index of this work item in its input queue, or ~0u past the queue's end.
 * Kernels are launched over the queues' capacity and read the length here,
 * so the host never waits for a length between stages. */
WP_FN uint queue_position(__global const uint *counts, uint queue) {
    uint k = get_global_id(0);
    return k < counts[queue] ? k : ~0u;
}

/* The start of a stage kernel: the work group's push scratch, this work
 * item's position k in its input queue (~0u past the end) and the slot there. */
#define WP_STAGE_INPUT(queue)                   \
    __local uint group_count, group_base;       \
    uint k = queue_position(counts, (queue));   \
    uint slot = k != ~0u ? queues[(queue) * capacity + k] : 0u

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

typedef struct {
    real t;
    uint shape; /* WP_NO_HIT or (WP_SHAPE_* << WP_SHAPE_TYPE_SHIFT) | index */
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

/* Closest hit over spheres, then planes, then quads, as the reference tests them. */
WP_FN Hit closest_hit(WP_SCENE_PARAMS, vec3 origin, vec3 direction) {
    Hit hit;
    hit.t = WP_INFINITY;
    hit.shape = WP_NO_HIT;
#ifdef WP_HAS_SPHERES
#pragma unroll
    for (uint i = 0; i < SPHERE_COUNT; ++i) {
        real t = sphere_t(&spheres[i], origin, direction, hit.t);
        hit.shape = t < hit.t ? shape_id(WP_SHAPE_SPHERE, i) : hit.shape;
        hit.t = fmin(t, hit.t);
    }
#endif
#ifdef WP_HAS_PLANES
#pragma unroll
    for (uint i = 0; i < PLANE_COUNT; ++i) {
        real t = plane_t(&planes[i], origin, direction, hit.t);
        hit.shape = t < hit.t ? shape_id(WP_SHAPE_PLANE, i) : hit.shape;
        hit.t = fmin(t, hit.t);
    }
#endif
#ifdef WP_HAS_QUADS
#pragma unroll
    for (uint i = 0; i < QUAD_COUNT; ++i) {
        real t = quad_t(&quads[i], origin, direction, hit.t);
        hit.shape = t < hit.t ? shape_id(WP_SHAPE_QUAD, i) : hit.shape;
        hit.t = fmin(t, hit.t);
    }
#endif
    return hit;
}

/* Whether any shape is hit at a distance below t_max. Every shape is tested
 * (no early exit), which keeps the unrolled loops free of branches. */
WP_FN int any_hit(WP_SCENE_PARAMS, vec3 origin, vec3 direction, real t_max) {
    int occluded = 0;
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

typedef struct {
    vec3 point;
    vec3 normal; /* geometric: outward (sphere), the plane's, normalize(edge1 x edge2) (quad) */
    uint material;
    real error; /* bound on the point's distance from the surface (offset.h) */
} Surface;

WP_FN Surface surface_at(WP_SCENE_PARAMS, uint shape, vec3 origin, vec3 direction, real t) {
    Surface s;
    s.point = v3_add_scaled(origin, t, direction);
    uint index = shape & WP_SHAPE_INDEX_MASK;
    uint type = shape >> WP_SHAPE_TYPE_SHIFT;
#ifdef WP_HAS_SPHERES
    if (type == WP_SHAPE_SPHERE) {
        vec3 center = vec3_at(spheres[index].center);
        s.point = sphere_reproject(center, spheres[index].radius, s.point);
        s.normal = sphere_normal(center, s.point);
        s.material = spheres[index].material;
        s.error = shape_point_error(sphere_magnitude(center, spheres[index].radius));
    }
#endif
#ifdef WP_HAS_PLANES
    if (type == WP_SHAPE_PLANE) {
        s.normal = vec3_at(planes[index].normal);
        s.material = planes[index].material;
        s.error = ray_point_error(origin, t, plane_magnitude(vec3_at(planes[index].point)));
    }
#endif
#ifdef WP_HAS_QUADS
    if (type == WP_SHAPE_QUAD) {
        vec3 edge1 = vec3_at(quads[index].edge1), edge2 = vec3_at(quads[index].edge2);
        s.normal = quad_normal(edge1, edge2);
        s.material = quads[index].material;
        s.error = ray_point_error(origin, t, quad_magnitude(vec3_at(quads[index].corner), edge1, edge2));
    }
#endif
    return s;
}

/* Adds `term` to the path's radiance unless the sum is not finite (a NaN or
 * Inf term, or an overflowing sum): then it is dropped and counted in
 * *dropped, so no non-finite value reaches the film. The caller adds *dropped
 * to the stage's counter (no atomics here: they would keep PoCL from
 * vectorising the stage). */
WP_FN vec3 add_finite(vec3 radiance, vec3 term, uint *dropped) {
    vec3 sum = v3_add(radiance, term);
    int finite = vec3_is_finite(sum);
    *dropped += finite ? 0u : 1u;
    return v3_select(finite, sum, radiance);
}

/* Adds a work item's dropped values to its slot's counter for the stage
 * (WP_COUNTER_NONFINITE_*): one counter per slot and stage, so no atomics;
 * the host sums them after each pass. */
WP_FN void count_nonfinite(__global uint *slot_nonfinite, uint capacity, uint stage_counter, uint slot, uint dropped) {
    if (dropped != 0u) slot_nonfinite[(stage_counter - WP_COUNTER_NONFINITE_EMISSION) * capacity + slot] += dropped;
}

/* Whether the throughput may carry the path on; a non-finite one ends it and is counted in *dropped. */
WP_FN int throughput_is_finite(vec3 throughput, uint *dropped) {
    int finite = vec3_is_finite(throughput);
    *dropped += finite ? 0u : 1u;
    return finite;
}

/* Ends the path in `slot`: its radiance (finite: every addition was checked)
 * becomes its pass entry and the slot is freed for generate (the caller pushes it). */
WP_FN void finish_path(__global float *pass_radiance, uint item, vec3 radiance) {
    pass_radiance[3u * item + 0u] = radiance.x;
    pass_radiance[3u * item + 1u] = radiance.y;
    pass_radiance[3u * item + 2u] = radiance.z;
}

#endif
