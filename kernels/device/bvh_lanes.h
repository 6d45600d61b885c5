/* The BVH traversal of shared/bvh.h with several lanes: each lane traces its own
 * ray with its own stack, node and distance, the steps of all lanes run as
 * vector code, until every lane has finished. Each lane does exactly what
 * bvh_trace does for its ray, so the results are bit-identical to it.
 *
 * Memory is read a row per lane and then transposed: a lane's node is one
 * 64-byte vector load (a cache line) and its triangle's vertices one 32-byte
 * load and a word, rather than one scalar load per lane and word (14 per
 * node, 9 per triangle). For any number of lanes. */
#ifndef WP_DEVICE_BVH_LANES_H
#define WP_DEVICE_BVH_LANES_H
#if WP_LANES != 1 /* one lane: shared/bvh.h's bvh_trace */

#include "device/lane_memory.h"
#include "shared/bvh.h"
#include "shared/prelude.h"
#include "shared/triangle.h"

/* The lanes' nodes: each child's box, lower x, y, z then upper x, y, z, and its child word. */
typedef struct {
    real box[2][6];
    lane_uint child[2];
} LaneNodes;

/* A lane's node, one 64-byte load, into its component of each word's vector. */
#define WP_NODE_LANE(s, k)                                                                              \
    {                                                                                                   \
        float16 row = vload16(0, &nodes[node.s].bounds[0][0]);                                          \
        n.box[0][0].s = row.s0, n.box[0][1].s = row.s1, n.box[0][2].s = row.s2, n.box[0][3].s = row.s3; \
        n.box[0][4].s = row.s4, n.box[0][5].s = row.s5, n.box[1][0].s = row.s6, n.box[1][1].s = row.s7; \
        n.box[1][2].s = row.s8, n.box[1][3].s = row.s9, n.box[1][4].s = row.sa, n.box[1][5].s = row.sb; \
        n.child[0].s = as_uint(row.sc), n.child[1].s = as_uint(row.sd);                                 \
    }
WP_LANE_FN LaneNodes lane_nodes(__global const BvhNode *nodes, lane_uint node) {
    LaneNodes n;
    WP_FOR_LANES(WP_NODE_LANE)
    return n;
}
#undef WP_NODE_LANE

/* The lanes' triangles' vertices. */
typedef struct {
    vec3 p0, p1, p2;
} LaneTriangles;

/* A lane's triangle: p0, p1 and p2's x, y from one 32-byte load, then p2's z. */
#define WP_TRIANGLE_LANE(s, k)                                                      \
    {                                                                               \
        float8 row = vload8(0, &triangles[index.s].p0[0]);                          \
        t.p0.x.s = row.s0, t.p0.y.s = row.s1, t.p0.z.s = row.s2, t.p1.x.s = row.s3; \
        t.p1.y.s = row.s4, t.p1.z.s = row.s5, t.p2.x.s = row.s6, t.p2.y.s = row.s7; \
        t.p2.z.s = triangles[index.s].p2[2];                                        \
    }
WP_LANE_FN LaneTriangles lane_triangles(__global const MeshTriangle *triangles, lane_uint index) {
    LaneTriangles t;
    WP_FOR_LANES(WP_TRIANGLE_LANE)
    return t;
}
#undef WP_TRIANGLE_LANE

/* The lanes' entry distances (box_entry) into a box of their nodes. */
WP_FN real lanes_box_entry(const real *box, vec3 origin, vec3 inverse, real limit) {
    lane_int parallel_x = isinf(inverse.x), parallel_y = isinf(inverse.y), parallel_z = isinf(inverse.z);
    return box_entry(slab_enter(box[0], box[3], origin.x, inverse.x, parallel_x),
                     slab_enter(box[1], box[4], origin.y, inverse.y, parallel_y),
                     slab_enter(box[2], box[5], origin.z, inverse.z, parallel_z),
                     slab_leave(box[0], box[3], origin.x, inverse.x, parallel_x),
                     slab_leave(box[1], box[4], origin.y, inverse.y, parallel_y),
                     slab_leave(box[2], box[5], origin.z, inverse.z, parallel_z), limit);
}

/* A leaf's child word: its triangle count, its first triangle. */
WP_FN lane_uint leaf_count(lane_uint child) { return (child & (WP_BVH_MAX_LEAF_SIZE - 1u)) + 1u; }
WP_FN lane_uint leaf_first(lane_uint child) { return (child & ~WP_BVH_LEAF) >> WP_BVH_LEAF_COUNT_BITS; }

/* The lanes' stacks, interleaved (entry i of lane k at i * WP_LANES + k).
 * A push stores and a pop loads in every lane, at that lane's depth, and
 * only the depth tells which lanes did push or pop: no branch per lane,
 * which incoherent lanes would mispredict. */
typedef struct {
    uint node[WP_BVH_STACK_SIZE * WP_LANES];
    lane_int depth;
} LaneStacks;

#define WP_PUSH_LANE(s, k) stacks->node[stacks->depth.s * WP_LANES + k] = node.s;
/* node pushed where push holds. */
WP_LANE_FN void lanes_push(LaneStacks *stacks, lane_int push, lane_uint node) {
    WP_FOR_LANES(WP_PUSH_LANE)
    stacks->depth -= push; /* push is -1 where true */
}
#define WP_TOP_LANE(s, k) top.s = stacks->node[top_depth.s * WP_LANES + k];
/* The nodes on top of the stacks where pop holds (popped; the depth must be above 0 there), else `node`. */
WP_LANE_FN lane_uint lanes_pop(LaneStacks *stacks, lane_int pop, lane_uint node) {
    lane_int top_depth = max(stacks->depth - 1, 0);
    lane_uint top;
    WP_FOR_LANES(WP_TOP_LANE)
    stacks->depth += pop;
    return pop ? top : node;
}
#undef WP_PUSH_LANE
#undef WP_TOP_LANE

/* bvh_trace (shared/bvh.h) in every lane. A lane tests the triangles of both
 * children's leaves in one loop, child 0's first as bvh_trace does, so the
 * loop runs as long as the lane with the most of them, not as the longest
 * leaf of each child in turn. bvh_trace drops stacked nodes entered beyond
 * the nearest hit unread; here a lane visits them, which enters none of
 * their children (a child's box is entered no earlier than its parent's):
 * one step more, no branch per lane, the same result. */
WP_FN real bvh_trace(__global const BvhNode *nodes, __global const MeshTriangle *triangles, vec3 origin, vec3 direction,
                     real t_max, int any_mode, lane_uint *triangle) {
    vec3 inverse = make_vec3(REAL(1.0) / direction.x, REAL(1.0) / direction.y, REAL(1.0) / direction.z);
    TriangleRay ray = triangle_ray(direction);
    real limit = box_limit(t_max);
    LaneStacks stacks;
    stacks.depth = 0;
    lane_uint node = 0u;
    lane_int running = (lane_int)(-1); /* the lane has not finished */
    while (lanes_any(running)) {
        LaneNodes n = lane_nodes(nodes, node);
        real entry[2] = {lanes_box_entry(n.box[0], origin, inverse, limit),
                         lanes_box_entry(n.box[1], origin, inverse, limit)};
        lane_int in[2], leaf[2];
        for (uint i = 0; i < 2u; ++i) {
            in[i] = running && n.child[i] != WP_BVH_NO_CHILD && entry[i] != WP_INFINITY;
            leaf[i] = in[i] && (n.child[i] & WP_BVH_LEAF) != 0u;
        }
        lane_uint count0 = leaf[0] ? leaf_count(n.child[0]) : (lane_uint)0u;
        lane_uint count = count0 + (leaf[1] ? leaf_count(n.child[1]) : (lane_uint)0u);
        lane_uint first0 = leaf_first(n.child[0]), first1 = leaf_first(n.child[1]) - count0;
        for (uint k = 0u; lanes_any(count > k && running); ++k) {
            lane_int testing = count > k && running;
            lane_uint index = testing ? (k < count0 ? first0 : first1) + k : (lane_uint)0u;
            LaneTriangles p = lane_triangles(triangles, index);
            real t = triangle_distance(ray_triangle_edges(ray, p.p0, p.p1, p.p2, origin), t_max);
            lane_int hit = testing && t < t_max;
            t_max = hit ? t : t_max;
            limit = hit ? box_limit(t_max) : limit;
            *triangle = hit ? index : *triangle;
            if (any_mode) running = running && !hit;
        }
        lane_int entered0 = running && in[0] && !leaf[0], entered1 = running && in[1] && !leaf[1];
        lane_int both = entered0 && entered1;
        lane_int near_is_1 = both && entry[1] < entry[0];
        lanes_push(&stacks, both, near_is_1 ? n.child[0] : n.child[1]);
        lane_int pop = running && !entered0 && !entered1;
        running = running && !(pop && stacks.depth == 0);
        /* a finished lane keeps its node, which the next steps still read */
        node = both ? (near_is_1 ? n.child[1] : n.child[0]) : (entered0 ? n.child[0] : (entered1 ? n.child[1] : node));
        node = lanes_pop(&stacks, pop && running, node);
    }
    return t_max;
}

#endif

#endif
