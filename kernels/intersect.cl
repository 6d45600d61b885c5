/* Stage 2: closest hit of each extension ray, WP_LANES rays per work item
 * (device/lanes.h), or, where the host traced them (WP_HOST_TRACED), the
 * hits it wrote. Hits go to shade; misses take the background and end. */
#include "device/guards.h"
#include "device/lanes.h"
#include "device/parameters.h"
#include "device/path_queues.h"
#include "device/scene_hits.h"
#include "shared/estimator.h"

__kernel __attribute__((reqd_work_group_size(WP_GROUP_SIZE, 1, 1))) void intersect(WP_STAGE_PARAMS) {
    STAGE_QUEUES(intersect, RAY, WP_PUSHES(HIT, FREE));
    __local uint group_count, group_base; /* queue_push's scratch (atomic compaction) */
    Lanes lanes = queue_lanes(queues, counts, capacity, stage_consumes);
#ifdef WP_HOST_TRACED
    lane_uint shape = PATH_READ(hit_shape, lanes);
#else
    Hit hit = closest_hit(WP_SCENE_ARGS, PATH_READ(origin, lanes), PATH_READ(direction, lanes));
    PATH_WRITE(hit_t, lanes, lanes.active, hit.t);
    PATH_WRITE(hit_shape, lanes, lanes.active, hit.shape);
    lane_uint shape = hit.shape;
#endif
    lane_int hit_something = lanes.active && shape != WP_NO_HIT;
    lane_int missed = lanes.active && shape == WP_NO_HIT;
    vec3 radiance = PATH_READ(radiance, lanes);
#ifdef WP_HAS_BACKGROUND
    lane_uint dropped = 0u;
    radiance =
        add_finite(radiance, background_seen(PATH_READ(throughput, lanes), uniform_vec3(scene->background)), &dropped);
    count_nonfinite(slot_nonfinite, WP_COUNTER_NONFINITE_EMISSION, lanes, missed ? dropped : (lane_uint)0u);
#endif
    finish_paths(pass_radiance, PATH_READ(pass_item, lanes), missed, radiance);
    STAGE_PUSH(HIT, lanes, hit_something);
    STAGE_PUSH(FREE, lanes, missed);
}
