/* Where a stage sends its paths: into the queues of the stages that take
 * them next, or, when a path ends, its radiance into its pass entry
 * (device/pass_radiance.h). A stage kernel's first line names its queues
 * (STAGE_QUEUES) and every push goes through STAGE_PUSH, so that the
 * compiler holds the kernel to its declaration in interface/stages.h. */
#ifndef WP_DEVICE_PATH_QUEUES_H
#define WP_DEVICE_PATH_QUEUES_H

#include "device/lane_memory.h"
#include "device/lanes.h"
#include "device/pass_radiance.h"
#include "interface/queues.h"
#include "interface/stages.h"
#include "shared/prelude.h"

/* Each stage's declared queues as constants: wp_consumes_<stage>, wp_pushes_<stage>. */
#define WP_STAGE_QUEUE_CONSTANTS(stage, loop, consumes, pushes, runs_when, traces) \
    wp_consumes_##stage = WP_QUEUE_##consumes, wp_pushes_##stage = (pushes),
enum { WP_STAGES(WP_STAGE_QUEUE_CONSTANTS) };

/* A stage kernel's first line: the queue it consumes and those it may push to
 * (WP_PUSHES), which must be its declaration's, as the constants
 * stage_consumes and stage_pushes of the kernel's body. */
#define STAGE_QUEUES(stage, consumes, pushes)                                                                \
    enum { stage_consumes = WP_QUEUE_##consumes, stage_pushes = (pushes) };                                  \
    __extension__ _Static_assert(stage_consumes == wp_consumes_##stage && stage_pushes == wp_pushes_##stage, \
                                 "the queues of " #stage " differ from its declaration in interface/stages.h")

#ifndef WP_COMPACT_SCAN
/* Appends `slot` to `queue` where `push` is set, one global atomic per work
 * group (atomic compaction, one lane). Every work item of the group must
 * call it (it has barriers); work items past their queue's end push nothing.
 * Kernels do not return early before it, not even whole work groups: PoCL
 * 3.1 then loses private values across the barriers (the stage tests catch
 * it). The order inside a queue is not stable; nothing depends on it: a
 * path's random numbers are keyed by (pixel, sample, bounce), its result goes
 * to its own pass_radiance entry, and accumulation sums those in sample order. */
WP_FN void queue_push(__global uint *queues, __global uint *counts, uint capacity, uint queue, int push, uint slot,
                      __local uint *group_count, __local uint *group_base) {
    if (get_local_id(0) == 0) *group_count = 0u;
    barrier(CLK_LOCAL_MEM_FENCE);
    uint offset = push ? atomic_inc(group_count) : 0u;
    barrier(CLK_LOCAL_MEM_FENCE);
    if (get_local_id(0) == 0 && *group_count > 0u) *group_base = atomic_add(&counts[queue], *group_count);
    barrier(CLK_LOCAL_MEM_FENCE);
    if (push) queues[queue * capacity + *group_base + offset] = slot;
}
#endif

/* Queues the lanes where `push` holds (it must imply the lane is active) for
 * `queue`'s stage. Scan compaction (the default, kernels/compact.cl): marks
 * their slots, from which the queue is built in ascending slot order, with
 * no atomics and no barriers here. Atomic compaction: queue_push. Every work
 * item of the group must call it. */
WP_FN void push_lanes(__global uint *queues, __global uint *counts, uint queue, Lanes lanes, lane_int push,
                      __local uint *group_count, __local uint *group_base) {
#ifdef WP_COMPACT_SCAN
    slot_write(queues + WP_QUEUE_MARKS(queue) * lanes.capacity, lanes, push, (lane_uint)1u);
#else
    queue_push(queues, counts, lanes.capacity, queue, push, lanes.slot, group_count, group_base);
#endif
}

/* push_lanes from a stage kernel (after STAGE_QUEUES, with its parameters
 * `queues` and `counts` and queue_push's scratch `group_count` and
 * `group_base`): a queue the stage's declaration does not list fails to
 * compile. */
#define STAGE_PUSH(queue, lanes, push)                                                        \
    do {                                                                                      \
        __extension__ _Static_assert(stage_pushes & WP_QUEUE_BIT(queue),                      \
                                     "a push to " #queue                                      \
                                     ", which the stage's declaration in interface/stages.h " \
                                     "does not list");                                        \
        push_lanes(queues, counts, WP_QUEUE_##queue, lanes, push, &group_count, &group_base); \
    } while (0)

#endif
