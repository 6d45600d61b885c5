/* The BVH traversal of shared/bvh.h with 8 lanes: each lane traces its own
 * ray with its own stack, node and distance, the steps of all lanes run as
 * vector code (a node's boxes and a leaf's triangles read per lane), until
 * every lane has finished. Each lane does exactly what bvh_trace does for
 * its ray, so the results are bit-identical to it. */
#ifndef WP_DEVICE_BVH_LANES_H
#define WP_DEVICE_BVH_LANES_H
#if WP_LANES != 1 /* one lane: shared/bvh.h's bvh_trace */

#include "device/lane_memory.h"
#include "shared/bvh.h"
#include "shared/prelude.h"
#include "shared/triangle.h"

#define WP_NODE_WORDS 16u /* sizeof(BvhNode) / 4 */

WP_FN real node_bound(__global const BvhNode *nodes, lane_uint node, uint child, uint k) {
    return gather(&nodes[0].bounds[child][k], node * WP_NODE_WORDS);
}

/* The lanes' entry distances (box_entry) into child `child` of their nodes. */
WP_FN real lanes_child_entry(__global const BvhNode *nodes, lane_uint node, uint child, vec3 origin, vec3 inverse,
                             real limit) {
    lane_int parallel_x = isinf(inverse.x), parallel_y = isinf(inverse.y), parallel_z = isinf(inverse.z);
    real lx = node_bound(nodes, node, child, 0u), ly = node_bound(nodes, node, child, 1u);
    real lz = node_bound(nodes, node, child, 2u), ux = node_bound(nodes, node, child, 3u);
    real uy = node_bound(nodes, node, child, 4u), uz = node_bound(nodes, node, child, 5u);
    return box_entry(
        slab_enter(lx, ux, origin.x, inverse.x, parallel_x), slab_enter(ly, uy, origin.y, inverse.y, parallel_y),
        slab_enter(lz, uz, origin.z, inverse.z, parallel_z), slab_leave(lx, ux, origin.x, inverse.x, parallel_x),
        slab_leave(ly, uy, origin.y, inverse.y, parallel_y), slab_leave(lz, uz, origin.z, inverse.z, parallel_z),
        limit);
}

#define WP_PUSH_LANE(s)                            \
    if (push.s) {                                  \
        stack[stack_size.s].s = far_node.s;        \
        stack_entry[stack_size.s].s = far_entry.s; \
        ++stack_size.s;                            \
    }
#define WP_POP_LANE(s)                                                                           \
    if (pop.s) {                                                                                 \
        while (stack_size.s > 0 && stack_entry[stack_size.s - 1].s > farthest.s) --stack_size.s; \
        if (stack_size.s == 0) {                                                                 \
            running.s = 0;                                                                       \
        } else {                                                                                 \
            --stack_size.s;                                                                      \
            node.s = stack[stack_size.s].s;                                                      \
        }                                                                                        \
    }

/* bvh_trace (shared/bvh.h) in every lane. */
WP_FN real bvh_trace(__global const BvhNode *nodes, __global const MeshTriangle *triangles, vec3 origin, vec3 direction,
                     real t_max, int any_mode, lane_uint *triangle) {
    vec3 inverse = make_vec3(REAL(1.0) / direction.x, REAL(1.0) / direction.y, REAL(1.0) / direction.z);
    TriangleRay ray = triangle_ray(direction);
    real limit = box_limit(t_max);
    uint8 stack[WP_BVH_STACK_SIZE];
    float8 stack_entry[WP_BVH_STACK_SIZE];
    int8 stack_size = 0;
    lane_uint node = 0u;
    lane_int running = (lane_int)(-1); /* the lane has not finished */
    while (any(running)) {
        lane_uint next[2];
        real entry[2] = {lanes_child_entry(nodes, node, 0u, origin, inverse, limit),
                         lanes_child_entry(nodes, node, 1u, origin, inverse, limit)};
        lane_int entered[2];
        for (uint i = 0; i < 2u; ++i) {
            lane_uint child = gather((__global const uint *)nodes + 12u + i, node * WP_NODE_WORDS);
            real t_enter = entry[i];
            lane_int in = running && child != WP_BVH_NO_CHILD && t_enter != WP_INFINITY;
            lane_int leaf = in && (child & WP_BVH_LEAF) != 0u;
            next[i] = child;
            entered[i] = in && !leaf;
            lane_uint first = (child & ~WP_BVH_LEAF) >> WP_BVH_LEAF_COUNT_BITS;
            lane_uint count = leaf ? (child & (WP_BVH_MAX_LEAF_SIZE - 1u)) + 1u : (lane_uint)0u;
            for (uint k = 0u; any(convert_int8(count > k) & running); ++k) {
                lane_int testing = count > k && running;
                lane_uint index = testing ? first + k : (lane_uint)0u;
                vec3 p0 = SCENE_FIELD(triangles, index, p0), p1 = SCENE_FIELD(triangles, index, p1);
                vec3 p2 = SCENE_FIELD(triangles, index, p2);
                real t = triangle_distance(ray_triangle_edges(ray, p0, p1, p2, origin), t_max);
                lane_int hit = testing && t < t_max;
                t_max = hit ? t : t_max;
                limit = hit ? box_limit(t_max) : limit;
                *triangle = hit ? index : *triangle;
                if (any_mode) running = running && !hit;
            }
        }
        lane_int both = running && entered[0] && entered[1];
        lane_int near_is_1 = both && entry[1] < entry[0];
        lane_uint far_node = near_is_1 ? next[0] : next[1];
        real far_entry = near_is_1 ? entry[0] : entry[1];
        lane_int push = both;
        WP_FOR_LANES(WP_PUSH_LANE)
        node = both ? (near_is_1 ? next[1] : next[0])
                    : (running && entered[0] ? next[0] : (running && entered[1] ? next[1] : node));
        lane_int pop = running && !entered[0] && !entered[1];
        real farthest = limit * box_leave_scale();
        WP_FOR_LANES(WP_POP_LANE)
    }
    return t_max;
}

#undef WP_PUSH_LANE
#undef WP_POP_LANE

#endif

#endif
