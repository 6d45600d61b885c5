/* Traversal of the meshes' bounding volume hierarchy, shared by the kernels
 * and the reference so that both visit the same nodes in the same order and
 * find the same triangle at the same distance. The tree is binary, built on
 * the host (src/accel/bvh.cpp) and flattened depth first: 64-byte nodes that
 * hold both children's boxes, so one node read decides which children the
 * ray enters; leaves of up to 8 triangles, stored in leaf order.
 *
 * Traversal is scalar code (a stack and a data-dependent loop): one lane. */
#ifndef WP_SHARED_BVH_H
#define WP_SHARED_BVH_H

#include "shared/offset.h"
#include "shared/prelude.h"
#include "shared/triangle.h"

/* A child is a node index, a leaf (WP_BVH_LEAF | first triangle << 3 |
 * triangle count - 1) or WP_BVH_NO_CHILD. */
#define WP_BVH_LEAF 0x80000000u
#define WP_BVH_LEAF_COUNT_BITS 3u
#define WP_BVH_MAX_LEAF_SIZE 8u
#define WP_BVH_NO_CHILD 0xffffffffu
/* Nodes on the traversal stack at most: the builder's depth limit is 32 (src/accel/bvh.cpp). */
#define WP_BVH_STACK_SIZE 64

typedef struct {
    float bounds[2][6]; /* per child: lower x, y, z, upper x, y, z (rounded outward to float) */
    uint child[2];
    uint unused[2]; /* to 64 bytes */
} BvhNode;

#if !defined(__OPENCL_C_VERSION__) || WP_LANES == 1

/* Where the ray is between the planes lower and upper of one axis: the
 * interval [enter, leave] of t. A ray parallel to them (its direction's
 * component 0, so the reciprocal is infinite) is between them for every t or
 * for none, decided by its origin alone: the products would otherwise be
 * 0 * inf = NaN for a ray lying in one of the planes. */
typedef struct {
    real enter, leave;
} Slab;

/* min and max by comparison: the slabs below make no NaN, and these compile
 * to one instruction where C++'s fmin and fmax are library calls (their NaN
 * rules keep compilers from inlining them), which made the reference's
 * traversal 3x slower than the kernel's. */
WP_FN real min_of(real a, real b) { return a < b ? a : b; }
WP_FN real max_of(real a, real b) { return a > b ? a : b; }

WP_FN Slab slab(real lower, real upper, real origin, real inverse_direction) {
    real t0 = (lower - origin) * inverse_direction, t1 = (upper - origin) * inverse_direction;
    lane_int parallel = isinf(inverse_direction);
    lane_int between = origin >= lower && origin <= upper;
    Slab s;
    s.enter = parallel ? (between ? -WP_INFINITY : WP_INFINITY) : min_of(t0, t1);
    s.leave = parallel ? (between ? WP_INFINITY : -WP_INFINITY) : max_of(t0, t1);
    return s;
}

/* Distance at which the ray enters the box within [0, t_max], or
 * WP_INFINITY. The leaving distance is widened by 1 + 2 gamma(3) so that
 * rounding never loses a box the ray meets (pbrt-v4, Bounds3::IntersectP). */
WP_FN real box_entry(WP_GLOBAL const float *bounds, vec3 origin, vec3 inverse_direction, real t_max) {
    real leave_scale = REAL(1.0) + REAL(2.0) * rounding_gamma(REAL(3.0));
    Slab x = slab((real)bounds[0], (real)bounds[3], origin.x, inverse_direction.x);
    Slab y = slab((real)bounds[1], (real)bounds[4], origin.y, inverse_direction.y);
    Slab z = slab((real)bounds[2], (real)bounds[5], origin.z, inverse_direction.z);
    real enter = max_of(max_of(x.enter, y.enter), max_of(z.enter, REAL(0.0)));
    real leave = min_of(min_of(x.leave, y.leave), min_of(z.leave, t_max / leave_scale)) * leave_scale;
    return enter <= leave ? enter : WP_INFINITY;
}

WP_FN vec3 triangle_vertex(WP_GLOBAL const real_element *p) { return make_vec3((real)p[0], (real)p[1], (real)p[2]); }

WP_FN real mesh_triangle_t(WP_GLOBAL const MeshTriangle *triangle, vec3 origin, vec3 direction, real t_max) {
    return intersect_triangle(triangle_vertex(triangle->p0), triangle_vertex(triangle->p1),
                              triangle_vertex(triangle->p2), origin, direction, t_max);
}

/* The closest triangle the ray meets before t_max: its distance (t_max when
 * none), and its index in *triangle (unchanged when none). `any` stops at the
 * first triangle met (shadow rays). Children are entered nearer first. */
WP_FN real bvh_trace(WP_GLOBAL const BvhNode *nodes, WP_GLOBAL const MeshTriangle *triangles, vec3 origin,
                     vec3 direction, real t_max, int any, uint *triangle) {
    vec3 inverse_direction = make_vec3(REAL(1.0) / direction.x, REAL(1.0) / direction.y, REAL(1.0) / direction.z);
    uint stack[WP_BVH_STACK_SIZE];
    int stack_size = 0;
    uint node = 0u; /* the root is always a node */
    for (;;) {
        uint next[2];
        real entry[2];
        int children = 0;
        for (int i = 0; i < 2; ++i) {
            uint child = nodes[node].child[i];
            if (child == WP_BVH_NO_CHILD) continue;
            real t_enter = box_entry(nodes[node].bounds[i], origin, inverse_direction, t_max);
            if (t_enter == WP_INFINITY) continue;
            if ((child & WP_BVH_LEAF) == 0u) {
                next[children] = child;
                entry[children] = t_enter;
                ++children;
                continue;
            }
            uint first = (child & ~WP_BVH_LEAF) >> WP_BVH_LEAF_COUNT_BITS;
            uint count = (child & (WP_BVH_MAX_LEAF_SIZE - 1u)) + 1u;
            for (uint k = first; k < first + count; ++k) {
                real t = mesh_triangle_t(&triangles[k], origin, direction, t_max);
                if (t < t_max) {
                    t_max = t;
                    *triangle = k;
                    if (any) return t_max;
                }
            }
        }
        if (children == 2) {
            int near_child = entry[1] < entry[0] ? 1 : 0;
            stack[stack_size++] = next[1 - near_child];
            node = next[near_child];
        } else if (children == 1) {
            node = next[0];
        } else if (stack_size > 0) {
            node = stack[--stack_size];
        } else {
            return t_max;
        }
    }
}

#endif

#endif
