/* Stage 3, where the hits have a stage of their own (without
 * WP_INTERSECT_AND_SHADE: on GPUs, and with atomic compaction;
 * interface/stages.h): everything a path does where its ray ended, WP_LANES
 * paths per work item, at the hits intersect traced or the host did
 * (device/shade_hits.h). */
#include "device/shade_hits.h"

__kernel __attribute__((reqd_work_group_size(WP_GROUP_SIZE, 1, 1))) void shade(WP_STAGE_PARAMS) {
    STAGE_QUEUES(shade, HIT, WP_PUSHES(SHADOW, RAY, FREE));
#ifndef WP_INTERSECT_AND_SHADE
    __local uint group_count, group_base; /* queue_push's scratch (atomic compaction) */
    Lanes lanes = queue_lanes(queues, counts, capacity, stage_consumes);
    ShadedPaths next = shade_hits(WP_STAGE_ARGS, lanes, hits_in_path_state(state_hit_t, state_hit_shape, lanes));
    STAGE_PUSH(SHADOW, lanes, next.casts_shadow); /* traced by intersect_shadow, or only counted */
    STAGE_PUSH(RAY, lanes, next.continues);
    STAGE_PUSH(FREE, lanes, next.ends);
#endif
}
