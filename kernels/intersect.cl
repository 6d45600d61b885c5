/* Stage 2: closest hit of each extension ray, WP_LANES rays per work item
 * (lanes.h). Hits go to shade_direct; misses take the background and end. */
#include "lanes.h"

__kernel __attribute__((reqd_work_group_size(WP_GROUP_SIZE, 1, 1))) void intersect(WP_STAGE_PARAMS) {
    __local uint group_count, group_base; /* queue_push's scratch (atomic compaction) */
    Lanes lanes = queue_lanes(queues, counts, capacity, WP_QUEUE_RAY);
    Hit hit = closest_hit(WP_SCENE_ARGS, LOAD_LANES_XYZ(origin, lanes), LOAD_LANES_XYZ(direction, lanes));
    lanes_store_real(hit_t, lanes, lanes.active, hit.t);
    lanes_store_uint(hit_shape, lanes, lanes.active, hit.shape);
    lane_int hit_something = lanes.active && hit.shape != WP_NO_HIT;
    lane_int missed = lanes.active && hit.shape == WP_NO_HIT;
    vec3 radiance = LOAD_LANES_RGB(radiance, lanes);
#ifdef WP_HAS_BACKGROUND
    lane_uint dropped = 0u;
    radiance = add_finite(radiance, v3_mul(LOAD_LANES_RGB(throughput, lanes), vec3_at(scene->background)), &dropped);
    count_nonfinite(slot_nonfinite, capacity, WP_COUNTER_NONFINITE_EMISSION, lanes, missed ? dropped : (lane_uint)0u);
#endif
    finish_paths(pass_radiance, lanes_load_uint(pass_item, lanes), missed, radiance);
    push_lanes(queues, counts, capacity, WP_QUEUE_HIT, lanes, hit_something, &group_count, &group_base);
    push_lanes(queues, counts, capacity, WP_QUEUE_FREE, lanes, missed, &group_count, &group_base);
}
