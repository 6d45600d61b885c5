/* Stable compaction by prefix sum (built with -DWP_COMPACT_SCAN): stage
 * kernels mark the slots they push (push_lanes), then these three kernels
 * turn each queue's marks into the queue, in ascending slot order, so the
 * next stage reads the path state in memory order. Each work item handles
 * one block of WP_COMPACT_BLOCK consecutive slots; no atomics, no barriers.
 * compact_count and compact_scan count the queues their queue_mask selects
 * (bit q for queue q), compact_write builds those its own queue_mask
 * selects: a queue read only for its length (src/wavefront/queue_plan.h,
 * counted_after) is counted and never written. Each kernel clears, once
 * read, the marks of the queues its clear_mask selects. */
#include "device/parameters.h"
#include "interface/kernel_parameters.h"
#include "interface/queues.h"

static inline uint compact_blocks(uint capacity) { return (capacity + WP_COMPACT_BLOCK - 1u) / WP_COMPACT_BLOCK; }

/* Whether `mask` selects queue q, and where q's marks start in the queues buffer. */
static inline int selects(uint mask, uint q) { return (mask >> q) & 1u; }
static inline uint marks_start(uint capacity, uint q) { return WP_QUEUE_MARKS(q) * capacity; }

__kernel void compact_count(WP_PARAMETERS(WP_COMPACT_COUNT_PARAMETERS)) {
    uint block = get_global_id(0), blocks = compact_blocks(capacity);
    if (block >= blocks) return;
    uint end = min(capacity, (block + 1u) * WP_COMPACT_BLOCK);
    for (uint q = 0u; q < WP_QUEUE_COUNT; ++q) {
        if (!selects(queue_mask, q)) continue;
        __global uint *marks = queues + marks_start(capacity, q);
        uint n = 0u;
        for (uint slot = block * WP_COMPACT_BLOCK; slot < end; ++slot) n += marks[slot];
        if (selects(clear_mask, q))
            for (uint slot = block * WP_COMPACT_BLOCK; slot < end; ++slot) marks[slot] = 0u;
        block_counts[q * blocks + block] = n;
    }
}

/* One work item per queue: block counts become block offsets (exclusive
 * prefix sum), and the total the queue's length. */
__kernel void compact_scan(WP_PARAMETERS(WP_COMPACT_SCAN_PARAMETERS)) {
    uint q = get_global_id(0), blocks = compact_blocks(capacity);
    if (q >= WP_QUEUE_COUNT || !selects(queue_mask, q)) return;
    uint sum = 0u;
    for (uint block = 0u; block < blocks; ++block) {
        uint n = block_counts[q * blocks + block];
        block_counts[q * blocks + block] = sum;
        sum += n;
    }
    counts[q] = sum;
}

/* Each block's marked slots, gathered first in private memory without a
 * branch (the entry after the last marked one is overwritten or left
 * unused), then copied to the queue. With `if (marks[slot])` the branch
 * went wrong about as often as a mark was set, and compact_write took ten
 * times as long as compact_count, which reads the same marks (cornell
 * 256x256 32 spp on PoCL, --profile: 62-70 ms with the branch, 27-28
 * without). */
__kernel void compact_write(WP_PARAMETERS(WP_COMPACT_WRITE_PARAMETERS)) {
    uint block = get_global_id(0), blocks = compact_blocks(capacity);
    if (block >= blocks) return;
    uint start = block * WP_COMPACT_BLOCK, end = min(capacity, start + WP_COMPACT_BLOCK);
    uint marked[WP_COMPACT_BLOCK + 1u];
    for (uint q = 0u; q < WP_QUEUE_COUNT; ++q) {
        if (!selects(queue_mask, q)) continue;
        __global uint *marks = queues + marks_start(capacity, q);
        uint n = 0u;
        for (uint slot = start; slot < end; ++slot) {
            marked[n] = slot;
            n += marks[slot];
        }
        if (selects(clear_mask, q))
            for (uint slot = start; slot < end; ++slot) marks[slot] = 0u;
        __global uint *queue = queues + q * capacity + block_counts[q * blocks + block];
        for (uint i = 0u; i < n; ++i) queue[i] = marked[i];
    }
}
