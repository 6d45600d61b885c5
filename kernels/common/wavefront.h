/* What the one-lane stage kernels share beyond trace.h: the shared math of
 * sampling and shading, path state access by slot, the queue push, the hit
 * surface and the end of a path. */
#ifndef WP_WAVEFRONT_H
#define WP_WAVEFRONT_H

#include "trace.h"
#include "rng.h"
#include "offset.h"
#include "sampling.h"
#if defined(WP_HAS_MIRROR) || defined(WP_HAS_GLASS)
#include "fresnel.h"
#endif
#ifndef WP_HAS_GLASS
/* Without glass the dielectric code must not be compiled in: any use is a build error. */
#pragma GCC poison fresnel_dielectric refract_direction
#endif

#define LOAD_XYZ(name, i) make_vec3(name##_x[i], name##_y[i], name##_z[i])
#define LOAD_RGB(name, i) make_vec3(name##_r[i], name##_g[i], name##_b[i])
#define STORE_XYZ(name, i, v) (name##_x[i] = (v).x, name##_y[i] = (v).y, name##_z[i] = (v).z)
#define STORE_RGB(name, i, v) (name##_r[i] = (v).x, name##_g[i] = (v).y, name##_b[i] = (v).z)


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
