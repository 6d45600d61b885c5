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
        __global float *pass_radiance WP_PATH_STATE_PARAMS

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

/* Closest hit over spheres, then planes, then quads, as the reference tests them. */
WP_FN Hit closest_hit(WP_SCENE_PARAMS, vec3 origin, vec3 direction) {
    Hit hit;
    hit.t = WP_INFINITY;
    hit.shape = WP_NO_HIT;
#ifdef WP_HAS_SPHERES
    for (uint i = 0; i < scene->sphere_count; ++i) {
        real t = intersect_sphere(vec3_at(spheres[i].center), spheres[i].radius, origin, direction, hit.t);
        if (t < hit.t) hit.t = t, hit.shape = shape_id(WP_SHAPE_SPHERE, i);
    }
#endif
#ifdef WP_HAS_PLANES
    for (uint i = 0; i < scene->plane_count; ++i) {
        real t = intersect_plane(vec3_at(planes[i].point), vec3_at(planes[i].normal), origin, direction, hit.t);
        if (t < hit.t) hit.t = t, hit.shape = shape_id(WP_SHAPE_PLANE, i);
    }
#endif
#ifdef WP_HAS_QUADS
    for (uint i = 0; i < scene->quad_count; ++i) {
        real t = intersect_quad(vec3_at(quads[i].corner), vec3_at(quads[i].edge1), vec3_at(quads[i].edge2), origin,
                                direction, hit.t);
        if (t < hit.t) hit.t = t, hit.shape = shape_id(WP_SHAPE_QUAD, i);
    }
#endif
    return hit;
}

/* Whether any shape is hit at a distance below t_max. */
WP_FN int any_hit(WP_SCENE_PARAMS, vec3 origin, vec3 direction, real t_max) {
#ifdef WP_HAS_SPHERES
    for (uint i = 0; i < scene->sphere_count; ++i)
        if (intersect_sphere(vec3_at(spheres[i].center), spheres[i].radius, origin, direction, t_max) < t_max)
            return 1;
#endif
#ifdef WP_HAS_PLANES
    for (uint i = 0; i < scene->plane_count; ++i)
        if (intersect_plane(vec3_at(planes[i].point), vec3_at(planes[i].normal), origin, direction, t_max) < t_max)
            return 1;
#endif
#ifdef WP_HAS_QUADS
    for (uint i = 0; i < scene->quad_count; ++i)
        if (intersect_quad(vec3_at(quads[i].corner), vec3_at(quads[i].edge1), vec3_at(quads[i].edge2), origin,
                           direction, t_max) < t_max)
            return 1;
#endif
    return 0;
}

typedef struct {
    vec3 point;
    vec3 normal; /* geometric: outward (sphere), the plane's, normalize(edge1 x edge2) (quad) */
    uint material;
    real error; /* bound on the point's distance from the surface (offset.h) */
} Surface;

WP_FN Surface surface_at(WP_SCENE_PARAMS, uint shape, vec3 origin, vec3 direction, real t) {
    Surface s;
    s.point = origin + t * direction;
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
 * Inf term, or an overflowing sum): then it is dropped and counted in the
 * stage's counter, so no non-finite value reaches the film. */
WP_FN vec3 add_finite(vec3 radiance, vec3 term, __global uint *counts, uint stage_counter) {
    vec3 sum = radiance + term;
    if (vec3_is_finite(sum)) return sum;
    atomic_inc(&counts[stage_counter]);
    return radiance;
}

/* Whether the throughput may carry the path on; a non-finite one ends it and is counted. */
WP_FN int throughput_is_finite(vec3 throughput, __global uint *counts) {
    if (vec3_is_finite(throughput)) return 1;
    atomic_inc(&counts[WP_COUNTER_NONFINITE_SCATTER]);
    return 0;
}

/* Ends the path in `slot`: its radiance (finite: every addition was checked)
 * becomes its pass entry and the slot is freed for generate (the caller pushes it). */
WP_FN void finish_path(__global float *pass_radiance, uint item, vec3 radiance) {
    pass_radiance[3u * item + 0u] = radiance.x;
    pass_radiance[3u * item + 1u] = radiance.y;
    pass_radiance[3u * item + 2u] = radiance.z;
}

#endif
