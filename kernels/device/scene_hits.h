/* Rays against the scene's shapes: the closest hit of an extension ray and
 * whether a shadow ray is blocked, over every shape kind compiled in, in
 * the order the reference tests them. Branch-free, for any number of lanes. */
#ifndef WP_DEVICE_SCENE_HITS_H
#define WP_DEVICE_SCENE_HITS_H

#include "device/features.h"
#include "device/lane_memory.h"
#include "device/parameters.h"
#include "shared/bvh.h"
#include "shared/geometry.h"
#include "shared/prelude.h"

typedef struct {
    real t;
    lane_uint shape; /* WP_NO_HIT or (WP_SHAPE_* << WP_SHAPE_TYPE_SHIFT) | index */
} Hit;

WP_FN lane_uint shape_id(uint type, lane_uint index) { return (type << WP_SHAPE_TYPE_SHIFT) | index; }

/* Each shape's test, t in (0, t_max) or WP_INFINITY. */
WP_FN real sphere_t(__global const DeviceSphere *sphere, vec3 origin, vec3 direction, real t_max) {
    return intersect_sphere(uniform_vec3(sphere->center), sphere->radius, origin, direction, t_max);
}
WP_FN real plane_t(__global const DevicePlane *plane, vec3 origin, vec3 direction, real t_max) {
    return intersect_plane(uniform_vec3(plane->point), uniform_vec3(plane->normal), origin, direction, t_max);
}
WP_FN real quad_t(__global const DeviceQuad *quad, vec3 origin, vec3 direction, real t_max) {
    QuadPlane plane;
    plane.normal = uniform_vec3(quad->plane_normal);
    plane.w = uniform_vec3(quad->plane_w);
    return intersect_quad_plane(uniform_vec3(quad->corner), uniform_vec3(quad->edge1), uniform_vec3(quad->edge2), plane,
                                origin, direction, t_max);
}

/* `hit` moved to `shape` at t in the lanes where t is closer. */
WP_FN Hit keep_closer(Hit hit, real t, lane_uint shape) {
    hit.shape = t < hit.t ? shape : hit.shape;
    hit.t = fmin(t, hit.t);
    return hit;
}

/* The BVH traversal: shared/bvh.h's with one lane, device/bvh_lanes.h's with 8. */
#if defined(WP_HAS_MESHES) && WP_LANES != 1
#include "device/bvh_lanes.h"
#endif

/* Closest hit over spheres, then planes, then quads, then the meshes'
 * triangles through their BVH, as the reference tests them. */
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
#ifdef WP_HAS_MESHES
    lane_uint triangle = 0u;
    real t = bvh_trace(bvh_nodes, triangles, origin, direction, hit.t, 0, &triangle);
    hit = keep_closer(hit, t, shape_id(WP_SHAPE_TRIANGLE, triangle));
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
#ifdef WP_HAS_MESHES
    lane_uint triangle = 0u;
    occluded |= bvh_trace(bvh_nodes, triangles, origin, direction, t_max, 1, &triangle) < t_max;
#endif
    return occluded;
}

#endif
