/* SPPM's photon pass, stage 2: the closest hit of each photon's ray
 * (device/scene_hits.h, as camera rays'), WP_LANES per work item. A photon
 * that leaves the scene ends. */
#include "device/lanes.h"
#include "device/parameters.h"
#include "device/path_queues.h"
#include "device/scene_hits.h"

__kernel __attribute__((reqd_work_group_size(WP_GROUP_SIZE, 1, 1))) void intersect_photons(WP_STAGE_PARAMS) {
    STAGE_QUEUES(intersect_photons, PHOTON_RAY, WP_PUSHES(PHOTON_HIT, PHOTON_FREE));
    __local uint group_count, group_base; /* queue_push's scratch (atomic compaction) */
    Lanes lanes = queue_lanes(queues, counts, capacity, stage_consumes);
#ifdef WP_SPPM
    Hit hit = closest_hit(WP_SCENE_ARGS, PATH_READ(origin, lanes), PATH_READ(direction, lanes));
    PATH_WRITE(hit_t, lanes, lanes.active, hit.t);
    PATH_WRITE(hit_shape, lanes, lanes.active, hit.shape);
    lane_int hit_something = lanes.active && hit.shape != WP_NO_HIT;
    lane_int missed = lanes.active && hit.shape == WP_NO_HIT;
#else
    lane_int hit_something = 0, missed = 0;
#endif
    STAGE_PUSH(PHOTON_HIT, lanes, hit_something);
    STAGE_PUSH(PHOTON_FREE, lanes, missed);
}
