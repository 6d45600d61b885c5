/* Traversal of the meshes' bounding volume hierarchy, shared by the kernels
 * and the reference so that both visit the same nodes in the same order and
 * find the same triangle at the same distance. The tree is binary, built on
 * the host (src/accel/bvh.cpp) and flattened depth first: 64-byte nodes that
 * hold both children's boxes, so one node read decides which children the
 * ray enters; leaves of up to 8 triangles, stored in leaf order.
 *
 * bvh_trace here is for one lane (the reference, the megakernel, stage
 * kernels on GPUs; the kernels test a node's two boxes as one vector); with
 * 8 lanes the stage kernels run device/bvh_lanes.h, the same steps in each
 * lane. The box tests below are written for any number of lanes. */
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

/* min and max by comparison: the slabs below make no NaN, and these compile
 * to one instruction where C++'s fmin and fmax are library calls (their NaN
 * rules keep compilers from inlining them), which made the reference's
 * traversal 3x slower than the kernel's. */
WP_FN real min_of(real a, real b) { return a < b ? a : b; }
WP_FN real max_of(real a, real b) { return a > b ? a : b; }

/* The leaving distances of the boxes are widened by 1 + 2 gamma(3) so that
 * rounding never loses a box the ray meets (pbrt-v4, Bounds3::IntersectP):
 * the boxes' limit for a search up to t_max is t_max / that factor. */
WP_FN real box_leave_scale(void) { return REAL(1.0) + REAL(2.0) * rounding_gamma(REAL(3.0)); }
WP_FN real box_limit(real t_max) { return t_max / box_leave_scale(); }

/* The distance at which the ray enters a box within [0, t_max] from the
 * slabs' entering and leaving distances (the boxes' limit is box_limit(t_max)),
 * or WP_INFINITY when it misses it. */
WP_FN real box_entry(real enter_x, real enter_y, real enter_z, real leave_x, real leave_y, real leave_z, real limit) {
    real enter = max_of(max_of(enter_x, enter_y), max_of(enter_z, REAL(0.0)));
    real leave = min_of(min_of(leave_x, leave_y), min_of(leave_z, limit)) * box_leave_scale();
    return enter <= leave ? enter : WP_INFINITY;
}

/* Where the ray is between the planes lower and upper of one axis: the
 * interval [enter, leave] of t. A ray parallel to them (its direction's
 * component 0, so the reciprocal is infinite) is between them for every t or
 * for none, decided by its origin alone: the products would otherwise be
 * 0 * inf = NaN for a ray lying in one of the planes. The kernels compute
 * the six slabs of a node's two boxes as one vector (the same arithmetic in
 * each element, so the same distances as the reference's scalar code). */
#if defined(__OPENCL_C_VERSION__) && WP_LANES == 1
typedef float8 slabs;
typedef int8 slab_condition;
#else
typedef real slabs;
typedef lane_int slab_condition;
#endif
WP_FN slabs slab_enter(slabs lower, slabs upper, slabs origin, slabs inverse_direction, slab_condition parallel) {
    slabs t0 = (lower - origin) * inverse_direction, t1 = (upper - origin) * inverse_direction;
    slab_condition between = origin >= lower && origin <= upper;
    return parallel ? (between ? -WP_INFINITY : WP_INFINITY) : (t0 < t1 ? t0 : t1);
}
WP_FN slabs slab_leave(slabs lower, slabs upper, slabs origin, slabs inverse_direction, slab_condition parallel) {
    slabs t0 = (lower - origin) * inverse_direction, t1 = (upper - origin) * inverse_direction;
    slab_condition between = origin >= lower && origin <= upper;
    return parallel ? (between ? WP_INFINITY : -WP_INFINITY) : (t0 > t1 ? t0 : t1);
}

#if !defined(__OPENCL_C_VERSION__) || WP_LANES == 1

/* A ray as the box tests use it. Kernels: origin, inverse direction and
 * which axes the ray is parallel to, each as x, y, z, x, y, z (then x, x):
 * the lanes of a node's two boxes. */
#ifdef __OPENCL_C_VERSION__
typedef struct {
    float8 origin, inverse_direction;
    int8 parallel;
} BoxRay;
#else
typedef struct {
    vec3 origin, inverse_direction;
} BoxRay;
#endif

/* Each child's entry distance (box_entry) into node's boxes. */
typedef struct {
    real entry[2];
} ChildEntries;

#ifdef __OPENCL_C_VERSION__
WP_FN float8 box_lanes(vec3 v) { return (float8)(v.x, v.y, v.z, v.x, v.y, v.z, v.x, v.x); }

WP_FN BoxRay box_ray(vec3 origin, vec3 inverse_direction) {
    BoxRay r;
    r.origin = box_lanes(origin);
    r.inverse_direction = box_lanes(inverse_direction);
    r.parallel = isinf(r.inverse_direction);
    return r;
}

WP_FN ChildEntries child_entries(__global const BvhNode *node, BoxRay ray, real limit) {
    float16 words = vload16(0, &node->bounds[0][0]);
    float8 lower = shuffle(words, (uint8)(0u, 1u, 2u, 6u, 7u, 8u, 0u, 0u));
    float8 upper = shuffle(words, (uint8)(3u, 4u, 5u, 9u, 10u, 11u, 3u, 3u));
    float8 enter = slab_enter(lower, upper, ray.origin, ray.inverse_direction, ray.parallel);
    float8 leave = slab_leave(lower, upper, ray.origin, ray.inverse_direction, ray.parallel);
    ChildEntries c;
    c.entry[0] = box_entry(enter.s0, enter.s1, enter.s2, leave.s0, leave.s1, leave.s2, limit);
    c.entry[1] = box_entry(enter.s3, enter.s4, enter.s5, leave.s3, leave.s4, leave.s5, limit);
    return c;
}
#else
WP_FN BoxRay box_ray(vec3 origin, vec3 inverse_direction) {
    BoxRay r;
    r.origin = origin, r.inverse_direction = inverse_direction;
    return r;
}

WP_FN ChildEntries child_entries(const BvhNode *node, BoxRay ray, real limit) {
    vec3 o = ray.origin, inverse = ray.inverse_direction;
    lane_int parallel_x = isinf(inverse.x), parallel_y = isinf(inverse.y), parallel_z = isinf(inverse.z);
    ChildEntries c;
    for (int i = 0; i < 2; ++i) {
        const float *b = node->bounds[i];
        c.entry[i] = box_entry(
            slab_enter(b[0], b[3], o.x, inverse.x, parallel_x), slab_enter(b[1], b[4], o.y, inverse.y, parallel_y),
            slab_enter(b[2], b[5], o.z, inverse.z, parallel_z), slab_leave(b[0], b[3], o.x, inverse.x, parallel_x),
            slab_leave(b[1], b[4], o.y, inverse.y, parallel_y), slab_leave(b[2], b[5], o.z, inverse.z, parallel_z),
            limit);
    }
    return c;
}
#endif

WP_FN vec3 triangle_vertex(WP_GLOBAL const real_element *p) { return make_vec3((real)p[0], (real)p[1], (real)p[2]); }

WP_FN TriangleEdges mesh_triangle_edges(WP_GLOBAL const MeshTriangle *triangle, TriangleRay ray, vec3 origin) {
    return ray_triangle_edges(ray, triangle_vertex(triangle->p0), triangle_vertex(triangle->p1),
                              triangle_vertex(triangle->p2), origin);
}

WP_FN real mesh_triangle_t(WP_GLOBAL const MeshTriangle *triangle, TriangleRay ray, vec3 origin, real t_max) {
    return triangle_distance(mesh_triangle_edges(triangle, ray, origin), t_max);
}

/* The closest triangle the ray meets before t_max: its distance (t_max when
 * none), and its index in *triangle (unchanged when none). `any` stops at the
 * first triangle met (shadow rays). Children are entered nearer first; the
 * farther one waits on the stack with its entry distance, and is dropped
 * unread when a hit found meanwhile lies before it: a child's box is entered
 * no earlier than its parent's, so every box test below it would fail (the
 * result is that of visiting it). What depends on the ray alone (its inverse
 * direction, the triangle test's shear) and on t_max alone (the boxes'
 * limit) is computed once, not per node. */
WP_FN real bvh_trace(WP_GLOBAL const BvhNode *nodes, WP_GLOBAL const MeshTriangle *triangles, vec3 origin,
                     vec3 direction, real t_max, int any, uint *triangle) {
    vec3 inverse_direction = make_vec3(REAL(1.0) / direction.x, REAL(1.0) / direction.y, REAL(1.0) / direction.z);
    BoxRay box_view = box_ray(origin, inverse_direction);
    TriangleRay ray = triangle_ray(direction);
    real limit = box_limit(t_max);
    uint stack[WP_BVH_STACK_SIZE];
    real stack_entry[WP_BVH_STACK_SIZE];
    int stack_size = 0;
    uint node = 0u; /* the root is always a node */
    for (;;) {
        uint next[2];
        real entry[2];
        int children = 0;
        ChildEntries entries = child_entries(&nodes[node], box_view, limit);
        for (int i = 0; i < 2; ++i) {
            uint child = nodes[node].child[i];
            if (child == WP_BVH_NO_CHILD) continue;
            real t_enter = entries.entry[i];
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
                real t = mesh_triangle_t(&triangles[k], ray, origin, t_max);
                if (t < t_max) {
                    t_max = t;
                    limit = box_limit(t_max);
                    *triangle = k;
                    if (any) return t_max;
                }
            }
        }
        if (children == 2) {
            int near_child = entry[1] < entry[0] ? 1 : 0;
            stack[stack_size] = next[1 - near_child];
            stack_entry[stack_size++] = entry[1 - near_child];
            node = next[near_child];
        } else if (children == 1) {
            node = next[0];
        } else {
            /* every box below is tested against at most limit * box_leave_scale() */
            real farthest = limit * box_leave_scale();
            while (stack_size > 0 && stack_entry[stack_size - 1] > farthest) --stack_size;
            if (stack_size == 0) return t_max;
            node = stack[--stack_size];
        }
    }
}

#endif

#endif
