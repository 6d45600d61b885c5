/* Stage 4: any hit along each shadow ray, WP_LANES rays per work item
 * (device/lanes.h), or, where the host traced them (WP_HOST_TRACED), its
 * verdict; an unoccluded one adds the light sample's contribution to its
 * path. A path that ended at the vertex that cast the ray (shade's depth
 * cap, roulette or invalid direction; `shadow_ends_path`) is finished here,
 * its contribution added after its emission as at every vertex. */
#include "device/guards.h"
#include "device/lanes.h"
#include "device/parameters.h"
#include "device/path_queues.h"
#include "device/scene_hits.h"

__kernel __attribute__((reqd_work_group_size(WP_GROUP_SIZE, 1, 1))) void intersect_shadow(WP_STAGE_PARAMS) {
    STAGE_QUEUES(intersect_shadow, SHADOW, WP_PUSHES_NOTHING);
#ifdef WP_NEE
    Lanes lanes = queue_lanes(queues, counts, capacity, stage_consumes);
#ifdef WP_HOST_TRACED
    lane_int unoccluded = lanes.active && PATH_READ(shadow_occluded, lanes) == 0u;
#else
    lane_int unoccluded =
        lanes.active && !any_hit(WP_SCENE_ARGS, PATH_READ(shadow_origin, lanes), PATH_READ(shadow_direction, lanes),
                                 PATH_READ(shadow_distance, lanes));
#endif
    lane_uint dropped = 0u;
    vec3 before = PATH_READ(radiance, lanes);
    vec3 radiance = v3_select(unoccluded, add_finite(before, PATH_READ(shadow_radiance, lanes), &dropped), before);
    count_nonfinite(slot_nonfinite, WP_COUNTER_NONFINITE_DIRECT, lanes, unoccluded ? dropped : (lane_uint)0u);
    lane_int ended = lanes.active && PATH_READ(shadow_ends_path, lanes) != 0u;
    PATH_WRITE(radiance, lanes, unoccluded && !ended, radiance);
    finish_paths(pass_radiance, PATH_READ(pass_item, lanes), ended, radiance);
#endif
}
