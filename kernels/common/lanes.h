/* A work item's lanes in the stage kernels: with WP_LANES > 1 a work item
 * takes WP_LANES consecutive entries of its input queue and runs its math on
 * all of them at once (`real` is a vector, prelude.h); the paths' state is
 * read and written per lane at their slots (lane_memory.h). Every store is
 * conditioned on the lane holding an entry. With one lane this is one path
 * per work item. */
#ifndef WP_LANES_H
#define WP_LANES_H

#include "trace.h"

#if WP_LANES == 1
#define LANE_INDEX 0u
#else
#if !defined(WP_COMPACT_SCAN)
#error "kernels with several lanes push to their queues by marks (-DWP_COMPACT_SCAN)"
#endif
#define LANE_INDEX ((lane_uint)(0u, 1u, 2u, 3u, 4u, 5u, 6u, 7u))
#endif

typedef struct {
    lane_uint slot;   /* the path's slot (meaningless where inactive) */
    lane_int active;  /* the lane holds a queue entry */
    int contiguous;   /* every lane active, the slots consecutive: whole-vector loads and stores */
} Lanes;

/* Positions get_global_id(0) * WP_LANES onwards of `queue`, and their slots. */
WP_FN lane_uint lane_positions(void) { return (uint)get_global_id(0) * WP_LANES + LANE_INDEX; }

WP_FN Lanes queue_lanes(__global const uint *queues, __global const uint *counts, uint capacity, uint queue) {
    Lanes lanes;
    lane_uint position = lane_positions();
    lanes.active = position < counts[queue];
    lanes.slot = load_uint(queues + queue * capacity, lanes.active ? position : (lane_uint)0u);
#if WP_LANES == 1
    lanes.contiguous = 0;
#else
    /* Queues are compacted in slot order and freed slots are refilled each
     * iteration, so runs of consecutive slots are the common case. */
    lanes.contiguous = all(lanes.active) && all(lanes.slot == lanes.slot.s0 + LANE_INDEX);
#endif
    return lanes;
}

/* The lanes' path state field p[slot] (lanes_load_real, lanes_load_uint):
 * one vector load when the slots are consecutive, else a load per lane. And
 * p[slot] = value where `where` holds (lanes_store_real, lanes_store_uint;
 * `where` must imply the lane is active): consecutive slots all belong to
 * this work item, so a vector read-select-write leaves the other lanes'
 * values as they were. */
#if WP_LANES == 1
#define WP_LANES_ACCESS(kind, element, value_type)                                                    \
    WP_FN value_type lanes_load_##kind(__global const element *p, Lanes lanes) {                      \
        return load_##kind(p, lanes.slot);                                                            \
    }                                                                                                 \
    WP_FN void lanes_store_##kind(__global element *p, Lanes lanes, lane_int where, value_type value) { \
        store_##kind(p, lanes.slot, where, value);                                                    \
    }
#else
#define WP_LANES_ACCESS(kind, element, value_type)                                                    \
    WP_FN value_type lanes_load_##kind(__global const element *p, Lanes lanes) {                      \
        return lanes.contiguous ? vload8(0, p + lanes.slot.s0) : load_##kind(p, lanes.slot);          \
    }                                                                                                 \
    WP_FN void lanes_store_##kind(__global element *p, Lanes lanes, lane_int where, value_type value) { \
        if (!lanes.contiguous) {                                                                      \
            store_##kind(p, lanes.slot, where, value);                                                \
            return;                                                                                   \
        }                                                                                             \
        __global element *at = p + lanes.slot.s0;                                                     \
        vstore8(select(vload8(0, at), value, where), 0, at);                                          \
    }
#endif
WP_LANES_ACCESS(real, float, real)
WP_LANES_ACCESS(uint, uint, lane_uint)
#undef WP_LANES_ACCESS

#define LOAD_LANES_XYZ(name, lanes) \
    make_vec3(lanes_load_real(name##_x, lanes), lanes_load_real(name##_y, lanes), lanes_load_real(name##_z, lanes))
#define LOAD_LANES_RGB(name, lanes) \
    make_vec3(lanes_load_real(name##_r, lanes), lanes_load_real(name##_g, lanes), lanes_load_real(name##_b, lanes))
#define STORE_LANES_XYZ(name, lanes, where, v)                                                             \
    (lanes_store_real(name##_x, lanes, where, (v).x), lanes_store_real(name##_y, lanes, where, (v).y), \
     lanes_store_real(name##_z, lanes, where, (v).z))
#define STORE_LANES_RGB(name, lanes, where, v)                                                             \
    (lanes_store_real(name##_r, lanes, where, (v).x), lanes_store_real(name##_g, lanes, where, (v).y), \
     lanes_store_real(name##_b, lanes, where, (v).z))

/* Marks (scan compaction) or pushes (atomic compaction, one lane) the
 * lanes where `push` holds (it must imply the lane is active). Every work
 * item of the group must call it. */
WP_FN void push_lanes(__global uint *queues, __global uint *counts, uint capacity, uint queue, Lanes lanes,
                      lane_int push, __local uint *group_count, __local uint *group_base) {
#ifdef WP_COMPACT_SCAN
    lanes_store_uint(queues + WP_QUEUE_MARKS(queue) * capacity, lanes, push, (lane_uint)1u);
#else
    queue_push(queues, counts, capacity, queue, push, lanes.slot, group_count, group_base);
#endif
}

/* Adds the lanes' dropped non-finite values to their slots' counters for the
 * stage (WP_COUNTER_NONFINITE_*): one counter per slot and stage, so no
 * atomics; the host sums them after each pass. */
WP_FN void count_nonfinite(__global uint *slot_nonfinite, uint capacity, uint stage_counter, Lanes lanes,
                           lane_uint dropped) {
    add_uint(slot_nonfinite + (stage_counter - WP_COUNTER_NONFINITE_EMISSION) * capacity, lanes.slot,
             lanes.active ? dropped : (lane_uint)0u);
}

/* Ends the paths of the lanes where `where` holds: their radiance (finite:
 * every addition was checked) becomes their pass entry (index `item`), and
 * their slots are freed for generate (the caller pushes them). */
WP_FN void finish_paths(__global float *pass_radiance, lane_uint item, lane_int where, vec3 radiance) {
    store_real(pass_radiance, 3u * item + 0u, where, radiance.x);
    store_real(pass_radiance, 3u * item + 1u, where, radiance.y);
    store_real(pass_radiance, 3u * item + 2u, where, radiance.z);
}

#endif
