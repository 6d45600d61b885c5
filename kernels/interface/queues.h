/* Queue and counter indices shared by the host (src/wavefront/queue_set.h)
 * and the kernels. `queues` holds WP_QUEUE_COUNT queues of path slots, each
 * `capacity` long; `counts` holds their lengths, then the counters. Which
 * stage consumes each queue and which push to it: interface/stages.h. */
#ifndef WP_INTERFACE_QUEUES_H
#define WP_INTERFACE_QUEUES_H

#define WP_QUEUE_FREE 0u   /* slots without a path */
#define WP_QUEUE_HIT 1u    /* paths whose extension ray was traced: a hit, or a miss (hit_shape WP_NO_HIT) */
#define WP_QUEUE_RAY 2u    /* paths with an extension ray to trace */
#define WP_QUEUE_SHADOW 3u /* paths with a shadow ray to trace */
/* SPPM's photon pass, which has the slots to itself once the camera pass of
 * its iteration has drained (docs/architecture.md, "Photon mapping"). */
#define WP_QUEUE_PHOTON_FREE 4u /* slots without a photon */
#define WP_QUEUE_PHOTON_RAY 5u  /* photons with a ray to trace */
#define WP_QUEUE_PHOTON_HIT 6u  /* photons whose ray hit a surface */
#define WP_QUEUE_COUNT 7u
/* With scan compaction (-DWP_COMPACT_SCAN) the queues buffer also holds, after the queues, one
 * array of marks (0 or 1 per slot) per queue, from which kernels/compact.cl
 * builds the queue with a prefix sum. */
#define WP_QUEUE_MARKS(queue) (WP_QUEUE_COUNT + (queue))
/* Slots each work item of the compaction kernels handles, in order. */
#define WP_COMPACT_BLOCK 256u

/* work items of the pass (photons of the iteration) handed out before this generate (emit_photons), set by the host */
#define WP_COUNTER_WORK (WP_QUEUE_COUNT + 0u)
/* Non-finite values dropped, one counter per stage where one can arise, in
 * the order of wp::nonfinite_stage_names (src/core/render.h). The megakernel
 * adds to these; the wavefront stages keep one counter per slot and stage
 * instead (count_nonfinite in kernels/device/guards.h), which the host sums. */
#define WP_COUNTER_NONFINITE_EMISSION (WP_QUEUE_COUNT + 1u) /* emission or background added to the radiance */
#define WP_COUNTER_NONFINITE_DIRECT (WP_QUEUE_COUNT + 2u)   /* a light sample's contribution added to the radiance */
#define WP_COUNTER_NONFINITE_SCATTER (WP_QUEUE_COUNT + 3u)  /* throughput after BSDF sampling and roulette (ends it) */
#define WP_NONFINITE_STAGE_COUNT 3u
/* megakernel only: rays traced (the wavefront counts its queues) */
#define WP_COUNTER_EXTENSION_RAYS (WP_QUEUE_COUNT + 4u)
#define WP_COUNTER_SHADOW_RAYS (WP_QUEUE_COUNT + 5u)
/* SPPM: photons added to visible points in the iteration (sppm_update.cl sums them) */
#define WP_COUNTER_PHOTON_DEPOSITS (WP_QUEUE_COUNT + 6u)
#define WP_COUNTS_SIZE (WP_QUEUE_COUNT + 7u)

/* With --profile, count_depths.cl counts rays per path depth in two
 * histograms after the counters (the last bin takes every deeper ray). */
#define WP_PROFILE_DEPTHS 64u
#define WP_PROFILE_EXTENSION_BY_DEPTH WP_COUNTS_SIZE
#define WP_PROFILE_SHADOW_BY_DEPTH (WP_COUNTS_SIZE + WP_PROFILE_DEPTHS)
#define WP_COUNTS_PROFILED_SIZE (WP_COUNTS_SIZE + 2u * WP_PROFILE_DEPTHS)

/* Paths each lane of the megakernel traces one after another, each started
 * as soon as the one before ends: a work item's lanes run until the last of
 * their paths ends, so with one path each half of them idle on average (the
 * room's and the cornell box's path lengths); with several, fewer. One lane
 * (GPUs, meshes) traces one. */
#define WP_MEGAKERNEL_PATHS_PER_LANE(lanes) ((lanes) > 1 ? 8u : 1u)

/* Work-group size of the stage kernels (the aggregated queue push uses local memory). */
#define WP_GROUP_SIZE 64

#endif
