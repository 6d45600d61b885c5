/* A work item's lanes in the stage kernels: with WP_LANES > 1 a work item
 * takes WP_LANES consecutive entries of its input queue and runs its math on
 * all of them at once (`real` is a vector, shared/prelude.h). With one lane
 * this is one path per work item.
 *
 * Path state is reached through two verbs only, PATH_READ(field, lanes) and
 * PATH_WRITE(field, lanes, where, value), with a field's name from
 * interface/path_state.h, whatever its type (uint, float or vec3). Every
 * write is conditioned on `where`, which must imply the lane holds an entry. */
#ifndef WP_DEVICE_LANES_H
#define WP_DEVICE_LANES_H

#include "device/lane_memory.h"
#include "device/parameters.h"
#include "shared/prelude.h"

/* Each lane's number: 0, 1, ..., WP_LANES - 1. */
#if WP_LANES == 1
WP_FN lane_uint lane_numbers(void) { return 0u; }
#else
#define WP_LANE_NUMBER(s, k) k##u,
WP_LANE_FN lane_uint lane_numbers(void) {
    uint numbers[WP_LANES] = {WP_FOR_LANES(WP_LANE_NUMBER)};
    return LANES_LOAD(numbers);
}
#undef WP_LANE_NUMBER
#endif

typedef struct {
    lane_uint slot;  /* the path's slot (meaningless where inactive) */
    lane_int active; /* the lane holds a queue entry */
    int contiguous;  /* every lane active, the slots consecutive: whole-vector loads and stores */
    uint capacity;   /* slots: the distance between a vec3 field's planes */
} Lanes;

/* Positions get_global_id(0) * WP_LANES onwards of a queue. */
WP_FN lane_uint lane_positions(void) { return (uint)get_global_id(0) * WP_LANES + lane_numbers(); }

WP_FN Lanes queue_lanes(__global const uint *queues, __global const uint *counts, uint capacity, uint queue) {
    Lanes lanes;
    lane_uint position = lane_positions();
    __global const uint *entries = queues + queue * capacity;
    lanes.active = position < counts[queue];
    lanes.capacity = capacity;
#if WP_LANES == 1
    lanes.slot = entries[lanes.active ? position : 0u];
    lanes.contiguous = 0;
#else
    /* The lanes' entries are consecutive: one vector load when all are in the queue. */
    int full = all(lanes.active);
    lanes.slot = full ? LANES_LOAD(entries + position.s0) : gather(entries, lanes.active ? position : (lane_uint)0u);
    /* Queues are compacted in slot order and freed slots are refilled each
     * iteration, so runs of consecutive slots are the common case. */
    lanes.contiguous = full && all(lanes.slot == lanes.slot.s0 + lane_numbers());
#endif
    return lanes;
}

/* The path state parameters are named state_<field> (device/parameters.h),
 * so that they never clash with a kernel's locals of the same name. */
#define PATH_READ(field, lanes) slot_read(state_##field, lanes)
#define PATH_WRITE(field, lanes, where, value) slot_write(state_##field, lanes, where, value)

/* An array with one element per slot, at the lanes' slots (slot_read,
 * slot_write): one vector load when the slots are consecutive, else a load per lane. A
 * store to consecutive slots is a vector read-select-write: those slots all
 * belong to this work item, so the other lanes' values stay as they were. */
#if WP_LANES == 1
WP_OVERLOAD WP_FN real slot_read(__global const float *field, Lanes lanes) { return field[lanes.slot]; }
WP_OVERLOAD WP_FN lane_uint slot_read(__global const uint *field, Lanes lanes) { return field[lanes.slot]; }
WP_OVERLOAD WP_FN void slot_write(__global float *field, Lanes lanes, lane_int where, real value) {
    store_where(field, lanes.slot, where, value);
}
WP_OVERLOAD WP_FN void slot_write(__global uint *field, Lanes lanes, lane_int where, lane_uint value) {
    store_where(field, lanes.slot, where, value);
}
#else
/* The lanes' vectors aligned as one element, so that they can be stored at
 * any slot in one instruction (PoCL 3.1's vstore16 of floats is four float4 stores). */
typedef real real_at_slot __attribute__((aligned(4)));
typedef lane_uint lane_uint_at_slot __attribute__((aligned(4)));
WP_OVERLOAD WP_LANE_FN real slot_read(__global const float *field, Lanes lanes) {
    return lanes.contiguous ? LANES_LOAD(field + lanes.slot.s0) : gather(field, lanes.slot);
}
WP_OVERLOAD WP_LANE_FN lane_uint slot_read(__global const uint *field, Lanes lanes) {
    return lanes.contiguous ? LANES_LOAD(field + lanes.slot.s0) : gather(field, lanes.slot);
}
WP_OVERLOAD WP_LANE_FN void slot_write(__global float *field, Lanes lanes, lane_int where, real value) {
    if (!lanes.contiguous) {
        store_where(field, lanes.slot, where, value);
        return;
    }
    __global float *at = field + lanes.slot.s0;
    *(__global real_at_slot *)at = select(LANES_LOAD(at), value, where);
}
WP_OVERLOAD WP_LANE_FN void slot_write(__global uint *field, Lanes lanes, lane_int where, lane_uint value) {
    if (!lanes.contiguous) {
        store_where(field, lanes.slot, where, value);
        return;
    }
    __global uint *at = field + lanes.slot.s0;
    *(__global lane_uint_at_slot *)at = select(LANES_LOAD(at), value, where);
}
#endif

/* A vec3 field: its three planes, each read and written as a float field. */
WP_OVERLOAD WP_LANE_FN vec3 slot_read(__global const PlanarVec3 *field, Lanes lanes) {
    __global const float *x = (__global const float *)field;
    return make_vec3(slot_read(x, lanes), slot_read(x + lanes.capacity, lanes),
                     slot_read(x + 2u * lanes.capacity, lanes));
}
WP_OVERLOAD WP_LANE_FN void slot_write(__global PlanarVec3 *field, Lanes lanes, lane_int where, vec3 value) {
    __global float *x = (__global float *)field;
    slot_write(x, lanes, where, value.x);
    slot_write(x + lanes.capacity, lanes, where, value.y);
    slot_write(x + 2u * lanes.capacity, lanes, where, value.z);
}

#endif
