/* The BVH traversal of shared/bvh.h with 8 lanes: each lane traces its own
 * ray with its own stack, node and distance, the steps of all lanes run as
 * vector code, until every lane has finished. Each lane does exactly what
 * bvh_trace does for its ray, so the results are bit-identical to it.
 *
 * Memory is read a row per lane and then transposed: a lane's node is one
 * 64-byte vector load (a cache line) and its triangle's vertices one 32-byte
 * load and a word, rather than one scalar load per lane and word (14 per
 * node, 9 per triangle). */
#ifndef WP_DEVICE_BVH_LANES_H
#define WP_DEVICE_BVH_LANES_H
#if WP_LANES != 1 /* one lane: shared/bvh.h's bvh_trace */

#include "device/lane_memory.h"
#include "shared/bvh.h"
#include "shared/prelude.h"
#include "shared/triangle.h"

/* Word w of the 8 lanes' rows. */
#define WP_COLUMN(row, w) \
    (float8)(row[0].s##w, row[1].s##w, row[2].s##w, row[3].s##w, row[4].s##w, row[5].s##w, row[6].s##w, row[7].s##w)

/* The lanes' nodes: each child's box, lower x, y, z then upper x, y, z, and its child word. */
typedef struct {
    real box[2][6];
    lane_uint child[2];
} LaneNodes;

#define WP_NODE_ROW(s) vload16(0, &nodes[node.s].bounds[0][0]),
WP_FN LaneNodes lane_nodes(__global const BvhNode *nodes, lane_uint node) {
    float16 row[WP_LANES] = {WP_FOR_LANES(WP_NODE_ROW)};
    LaneNodes n;
    n.box[0][0] = WP_COLUMN(row, 0), n.box[0][1] = WP_COLUMN(row, 1), n.box[0][2] = WP_COLUMN(row, 2);
    n.box[0][3] = WP_COLUMN(row, 3), n.box[0][4] = WP_COLUMN(row, 4), n.box[0][5] = WP_COLUMN(row, 5);
    n.box[1][0] = WP_COLUMN(row, 6), n.box[1][1] = WP_COLUMN(row, 7), n.box[1][2] = WP_COLUMN(row, 8);
    n.box[1][3] = WP_COLUMN(row, 9), n.box[1][4] = WP_COLUMN(row, a), n.box[1][5] = WP_COLUMN(row, b);
    n.child[0] = as_uint8(WP_COLUMN(row, c)), n.child[1] = as_uint8(WP_COLUMN(row, d));
    return n;
}
#undef WP_NODE_ROW

/* The lanes' triangles' vertices (p0, p1 and p2's x, y from one load per lane). */
typedef struct {
    vec3 p0, p1, p2;
} LaneTriangles;

#define WP_TRIANGLE_ROW(s) vload8(0, &triangles[index.s].p0[0]),
WP_FN LaneTriangles lane_triangles(__global const MeshTriangle *triangles, lane_uint index) {
    float8 row[WP_LANES] = {WP_FOR_LANES(WP_TRIANGLE_ROW)};
    LaneTriangles t;
    t.p0 = make_vec3(WP_COLUMN(row, 0), WP_COLUMN(row, 1), WP_COLUMN(row, 2));
    t.p1 = make_vec3(WP_COLUMN(row, 3), WP_COLUMN(row, 4), WP_COLUMN(row, 5));
    t.p2 = make_vec3(WP_COLUMN(row, 6), WP_COLUMN(row, 7), SCENE_FIELD(triangles, index, p2[2]));
    return t;
}
#undef WP_TRIANGLE_ROW

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

#define WP_EACH_LANE(F) F(s0, 0) F(s1, 1) F(s2, 2) F(s3, 3) F(s4, 4) F(s5, 5) F(s6, 6) F(s7, 7)
#define WP_PUSH_LANE(s, k) stacks->node[stacks->depth.s * WP_LANES + k] = node.s;
/* node pushed where push holds. */
WP_FN void lanes_push(LaneStacks *stacks, lane_int push, lane_uint node) {
    WP_EACH_LANE(WP_PUSH_LANE)
    stacks->depth -= push; /* push is -1 where true */
}
#define WP_TOP_LANE(s, k) top.s = stacks->node[top_depth.s * WP_LANES + k];
/* The nodes on top of the stacks where pop holds (popped; the depth must be above 0 there), else `node`. */
WP_FN lane_uint lanes_pop(LaneStacks *stacks, lane_int pop, lane_uint node) {
    lane_int top_depth = max(stacks->depth - 1, 0);
    lane_uint top;
    WP_EACH_LANE(WP_TOP_LANE)
    stacks->depth += pop;
    return pop ? top : node;
}
#undef WP_PUSH_LANE
#undef WP_TOP_LANE
#undef WP_EACH_LANE

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
    while (any(running)) {
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
        for (uint k = 0u; any(convert_int8(count > k) & running); ++k) {
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

#undef WP_COLUMN

#endif

#endif
