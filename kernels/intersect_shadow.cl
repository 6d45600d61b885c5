/* Stage 4: any hit along each shadow ray; an unoccluded one adds the light
 * sample's contribution to its path. */
#include "wavefront.h"

__kernel __attribute__((reqd_work_group_size(WP_GROUP_SIZE, 1, 1))) void intersect_shadow(WP_STAGE_PARAMS) {
#ifdef WP_HAS_NEE
    uint k = queue_position(counts, WP_QUEUE_SHADOW);
    uint slot = k != ~0u ? queues[WP_QUEUE_SHADOW * capacity + k] : 0u;
    if (k != ~0u && !any_hit(WP_SCENE_ARGS, LOAD_XYZ(shadow_origin, slot), LOAD_XYZ(shadow_direction, slot),
                             shadow_distance[slot])) {
        uint dropped = 0u;
        /* Not inside STORE_RGB, which evaluates its value once per channel. */
        vec3 radiance_with_light = add_finite(LOAD_RGB(radiance, slot), LOAD_RGB(shadow_radiance, slot), &dropped);
        STORE_RGB(radiance, slot, radiance_with_light);
        count_nonfinite(slot_nonfinite, capacity, WP_COUNTER_NONFINITE_DIRECT, slot, dropped);
    }
#endif
}
