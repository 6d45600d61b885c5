/* Stage 4: any hit along each shadow ray; an unoccluded one adds the light
 * sample's contribution to its path. */
#include "wavefront.h"

__kernel __attribute__((reqd_work_group_size(WP_GROUP_SIZE, 1, 1))) void intersect_shadow(WP_STAGE_PARAMS) {
#ifdef WP_HAS_NEE
    uint k = queue_position(counts, WP_QUEUE_SHADOW);
    if (k == ~0u) return;
    uint slot = queues[WP_QUEUE_SHADOW * capacity + k];
    if (!any_hit(WP_SCENE_ARGS, LOAD_XYZ(shadow_origin, slot), LOAD_XYZ(shadow_direction, slot),
                 shadow_distance[slot]))
        STORE_RGB(radiance, slot, LOAD_RGB(radiance, slot) + LOAD_RGB(shadow_radiance, slot));
#endif
}
