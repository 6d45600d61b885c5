/* Stage 2, where the hits have a stage of their own (without
 * WP_INTERSECT_AND_SHADE: on GPUs, and with atomic compaction; elsewhere intersect_and_shade.cl does this and
 * shade's work in one kernel, interface/stages.h): closest hit of each
 * extension ray, WP_LANES rays per work item (device/lanes.h), into hit_t
 * and hit_shape, or, where the host traced them (WP_HOST_TRACED), nothing
 * more to find. Every path goes on to shade, a miss too (its hit_shape
 * WP_NO_HIT): shade adds the background it sees. So the hit queue is the ray
 * queue, whole runs of consecutive slots, which shade reads and writes as
 * whole vectors (measured in docs/architecture.md, "Misses"). */
#include "device/lanes.h"
#include "device/parameters.h"
#include "device/path_queues.h"
#include "device/scene_hits.h"

__kernel __attribute__((reqd_work_group_size(WP_GROUP_SIZE, 1, 1))) void intersect(WP_STAGE_PARAMS) {
    STAGE_QUEUES(intersect, RAY, WP_PUSHES(HIT));
#ifndef WP_INTERSECT_AND_SHADE
    __local uint group_count, group_base; /* queue_push's scratch (atomic compaction) */
    Lanes lanes = queue_lanes(queues, counts, capacity, stage_consumes);
#ifndef WP_HOST_TRACED
    Hit hit = closest_hit(WP_SCENE_ARGS, PATH_READ(origin, lanes), PATH_READ(direction, lanes));
    PATH_WRITE(hit_t, lanes, lanes.active, hit.t);
    PATH_WRITE(hit_shape, lanes, lanes.active, hit.shape);
#endif
    STAGE_PUSH(HIT, lanes, lanes.active);
#endif
}
