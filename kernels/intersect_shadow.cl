/* Stage 4: any hit along each shadow ray, WP_LANES rays per work item
 * (lanes.h); an unoccluded one adds the light sample's contribution to its path. */
#include "lanes.h"

__kernel __attribute__((reqd_work_group_size(WP_GROUP_SIZE, 1, 1))) void intersect_shadow(WP_STAGE_PARAMS) {
#ifdef WP_HAS_NEE
    Lanes lanes = queue_lanes(queues, counts, capacity, WP_QUEUE_SHADOW);
    lane_int unoccluded = lanes.active && !any_hit(WP_SCENE_ARGS, LOAD_LANES_XYZ(shadow_origin, lanes),
                                                   LOAD_LANES_XYZ(shadow_direction, lanes),
                                                   lanes_load_real(shadow_distance, lanes));
    lane_uint dropped = 0u;
    vec3 radiance = add_finite(LOAD_LANES_RGB(radiance, lanes), LOAD_LANES_RGB(shadow_radiance, lanes), &dropped);
    STORE_LANES_RGB(radiance, lanes, unoccluded, radiance);
    count_nonfinite(slot_nonfinite, capacity, WP_COUNTER_NONFINITE_DIRECT, lanes,
                    unoccluded ? dropped : (lane_uint)0u);
#endif
}
