/* Stage 2: closest hit of each extension ray, WP_LANES rays per work item
 * (lanes.h). Hits go to shade_direct; misses take the background and end. */
#include "lanes.h"

__kernel __attribute__((reqd_work_group_size(WP_GROUP_SIZE, 1, 1))) void intersect(WP_STAGE_PARAMS) {
    __local uint group_count, group_base; /* queue_push's scratch (atomic compaction) */
    Lanes lanes = queue_lanes(queues, counts, capacity, WP_QUEUE_RAY);
    lane_int active = lanes_active(lanes);
    Hit hit = closest_hit(WP_SCENE_ARGS, GATHER_XYZ(origin, lanes), GATHER_XYZ(direction, lanes));
    scatter_real(hit_t, 1u, 0u, lanes, active, hit.t);
    scatter_uint(hit_shape, lanes, active, hit.shape);
    lane_int hit_something = hit.shape != WP_NO_HIT;
    lane_int missed = !hit_something;
    vec3 radiance = GATHER_RGB(radiance, lanes);
#ifdef WP_HAS_BACKGROUND
    lane_uint dropped = 0u;
    radiance = add_finite(radiance, v3_mul(GATHER_RGB(throughput, lanes), vec3_at(scene->background)), &dropped);
    count_nonfinite_lanes(slot_nonfinite, capacity, WP_COUNTER_NONFINITE_EMISSION, lanes,
                          missed ? dropped : (lane_uint)0u);
#endif
    finish_lanes(pass_radiance, lanes_at(lanes, gather_uint(pass_item, lanes)), missed, radiance);
    push_lanes(queues, counts, capacity, WP_QUEUE_HIT, lanes, hit_something, &group_count, &group_base);
    push_lanes(queues, counts, capacity, WP_QUEUE_FREE, lanes, missed, &group_count, &group_base);
}
