/* Stages 2 and 3 launched as one, where the hits need no stage of their own
 * (WP_INTERSECT_AND_SHADE: CPU devices with scan compaction;
 * interface/stages.h): each extension ray's closest hit, WP_LANES rays per
 * work item, as intersect finds it, or where the host traced them
 * (WP_HOST_TRACED) its hit, then shade's work there (device/shade_hits.h). The
 * hits stay in registers: no launch, no compaction and no hit_t/hit_shape
 * traffic between the two (measured in docs/architecture.md, "Intersect and
 * shade as one kernel"). The paths that continue go back to RAY, the queue
 * this stage takes its paths from: scan compaction builds it again from its
 * marks after the launch. */
#include "device/shade_hits.h"

__kernel __attribute__((reqd_work_group_size(WP_GROUP_SIZE, 1, 1))) void intersect_and_shade(WP_STAGE_PARAMS) {
    STAGE_QUEUES(intersect_and_shade, RAY, WP_PUSHES(SHADOW, RAY, FREE));
#ifdef WP_INTERSECT_AND_SHADE
#ifndef WP_COMPACT_SCAN
#error "intersect_and_shade pushes to the queue it takes: it needs scan compaction (src/wavefront/stage.h)"
#endif
    __local uint group_count, group_base; /* unused: scan compaction only */
    Lanes lanes = queue_lanes(queues, counts, capacity, stage_consumes);
#ifdef WP_HOST_TRACED
    Hit hit = hits_in_path_state(state_hit_t, state_hit_shape, lanes);
#else
    Hit hit = closest_hit(WP_SCENE_ARGS, PATH_READ(origin, lanes), PATH_READ(direction, lanes));
#endif
    ShadedPaths next = shade_hits(WP_STAGE_ARGS, lanes, hit);
    STAGE_PUSH(SHADOW, lanes, next.casts_shadow); /* traced by intersect_shadow, or only counted */
    STAGE_PUSH(RAY, lanes, next.continues);
    STAGE_PUSH(FREE, lanes, next.ends);
#endif
}
