/* A work item's lanes (trace.h's kernels): with WP_LANES > 1 a work item
 * takes WP_LANES consecutive entries of its input queue. The math runs on
 * all lanes at once (`real` is a vector, prelude.h); memory is read and
 * written lane by lane, since the paths' slots are scattered: gathers, and
 * stores only where a lane is active and its condition holds. With one lane
 * these are a work item's plain loads and stores. */
#ifndef WP_LANES_H
#define WP_LANES_H

#include "trace.h"

#if WP_LANES == 1
#define LANES_LOAD(array) ((array)[0])
#define LANES_STORE(value, array) ((array)[0] = (value))
#else
#if !defined(WP_COMPACT_SCAN)
#error "kernels with several lanes push to their queues by marks (-DWP_COMPACT_SCAN)"
#endif
#define LANES_LOAD(array) vload8(0, array)
#define LANES_STORE(value, array) vstore8((value), 0, array)
#endif

typedef struct {
    uint slot[WP_LANES]; /* 0 where inactive */
    int active[WP_LANES]; /* the lane holds a queue entry */
} Lanes;

/* Entries get_global_id(0) * WP_LANES onwards of `queue`; lanes past its end are inactive. */
WP_FN Lanes queue_lanes(__global const uint *queues, __global const uint *counts, uint capacity, uint queue) {
    Lanes lanes;
    uint first = get_global_id(0) * WP_LANES, length = counts[queue];
    for (uint i = 0u; i < WP_LANES; ++i) {
        lanes.active[i] = first + i < length;
        lanes.slot[i] = lanes.active[i] ? queues[queue * capacity + first + i] : 0u;
    }
    return lanes;
}

WP_FN lane_int lanes_active(Lanes lanes) { return LANES_LOAD(lanes.active) != 0; }

WP_FN real gather_real(__global const float *p, Lanes lanes) {
    float values[WP_LANES];
    for (uint i = 0u; i < WP_LANES; ++i) values[i] = p[lanes.slot[i]];
    return LANES_LOAD(values);
}

WP_FN lane_uint gather_uint(__global const uint *p, Lanes lanes) {
    uint values[WP_LANES];
    for (uint i = 0u; i < WP_LANES; ++i) values[i] = p[lanes.slot[i]];
    return LANES_LOAD(values);
}

#define GATHER_XYZ(name, lanes) \
    make_vec3(gather_real(name##_x, lanes), gather_real(name##_y, lanes), gather_real(name##_z, lanes))
#define GATHER_RGB(name, lanes) \
    make_vec3(gather_real(name##_r, lanes), gather_real(name##_g, lanes), gather_real(name##_b, lanes))

/* p[stride * slot + offset] = value in each active lane where `where` holds. */
WP_FN void scatter_real(__global float *p, uint stride, uint offset, Lanes lanes, lane_int where, real value) {
    float values[WP_LANES];
    int wheres[WP_LANES];
    LANES_STORE(value, values);
    LANES_STORE(where, wheres);
    for (uint i = 0u; i < WP_LANES; ++i)
        if (lanes.active[i] && wheres[i]) p[stride * lanes.slot[i] + offset] = values[i];
}

/* p[slot] += value in each active lane where `value` is not 0. */
WP_FN void scatter_add_uint(__global uint *p, Lanes lanes, lane_uint value) {
    uint values[WP_LANES];
    LANES_STORE(value, values);
    for (uint i = 0u; i < WP_LANES; ++i)
        if (lanes.active[i] && values[i] != 0u) p[lanes.slot[i]] += values[i];
}

WP_FN void scatter_uint(__global uint *p, Lanes lanes, lane_int where, lane_uint value) {
    uint values[WP_LANES];
    int wheres[WP_LANES];
    LANES_STORE(value, values);
    LANES_STORE(where, wheres);
    for (uint i = 0u; i < WP_LANES; ++i)
        if (lanes.active[i] && wheres[i]) p[lanes.slot[i]] = values[i];
}

#define SCATTER_RGB(name, lanes, where, v)                 \
    (scatter_real(name##_r, 1u, 0u, lanes, where, (v).x),  \
     scatter_real(name##_g, 1u, 0u, lanes, where, (v).y),  \
     scatter_real(name##_b, 1u, 0u, lanes, where, (v).z))

/* The same lanes addressing index[i] instead of their slots. */
WP_FN Lanes lanes_at(Lanes lanes, lane_uint index) {
    uint indices[WP_LANES];
    LANES_STORE(index, indices);
    for (uint i = 0u; i < WP_LANES; ++i) lanes.slot[i] = indices[i];
    return lanes;
}

/* Marks (scan compaction) or pushes (atomic compaction, one lane) the active
 * lanes where `push` holds. Every work item of the group must call it. */
WP_FN void push_lanes(__global uint *queues, __global uint *counts, uint capacity, uint queue, Lanes lanes,
                      lane_int push, __local uint *group_count, __local uint *group_base) {
#ifdef WP_COMPACT_SCAN
    scatter_uint(queues + WP_QUEUE_MARKS(queue) * capacity, lanes, push, (lane_uint)1u);
#else
    queue_push(queues, counts, capacity, queue, lanes.active[0] && push, lanes.slot[0], group_count, group_base);
#endif
}

/* count_nonfinite (wavefront.h) for each lane. */
WP_FN void count_nonfinite_lanes(__global uint *slot_nonfinite, uint capacity, uint stage_counter, Lanes lanes,
                                 lane_uint dropped) {
    scatter_add_uint(slot_nonfinite + (stage_counter - WP_COUNTER_NONFINITE_EMISSION) * capacity, lanes, dropped);
}

/* finish_path (wavefront.h) for the lanes where `where` holds; `items` addresses pass entries. */
WP_FN void finish_lanes(__global float *pass_radiance, Lanes items, lane_int where, vec3 radiance) {
    scatter_real(pass_radiance, 3u, 0u, items, where, radiance.x);
    scatter_real(pass_radiance, 3u, 1u, items, where, radiance.y);
    scatter_real(pass_radiance, 3u, 2u, items, where, radiance.z);
}

#endif
