/* Stage 4, where shadow rays have a stage of their own (WP_SHADOW_STAGE:
 * where the host traces them, and on GPUs; interface/stages.h): any hit
 * along each shadow ray, WP_LANES rays per work item (device/lanes.h), or,
 * where the host traced them (WP_HOST_TRACED), its verdict; an unoccluded
 * one adds the light sample's contribution to its path. A path that ended
 * at the vertex that cast the ray (shade's depth cap, roulette or invalid
 * direction; `shadow_ends_path`) is finished here, its contribution added
 * after its emission as at every vertex. */
#include "device/guards.h"
#include "device/lanes.h"
#include "device/parameters.h"
#include "device/path_queues.h"
#include "device/path_vertex.h"

__kernel __attribute__((reqd_work_group_size(WP_GROUP_SIZE, 1, 1))) void intersect_shadow(WP_STAGE_PARAMS) {
    STAGE_QUEUES(intersect_shadow, SHADOW, WP_PUSHES_NOTHING);
#if defined(WP_NEE) && defined(WP_SHADOW_STAGE)
    Lanes lanes = queue_lanes(queues, counts, capacity, stage_consumes);
#ifdef WP_HOST_TRACED
    lane_int unoccluded = lanes.active && PATH_READ(shadow_occluded, lanes) == 0u;
#else
    ShadowRay shadow;
    shadow.origin = PATH_READ(shadow_origin, lanes);
    shadow.direction = PATH_READ(shadow_direction, lanes);
    shadow.distance = PATH_READ(shadow_distance, lanes);
    lane_int unoccluded = shadow_ray_reaches_light(WP_SCENE_ARGS, lanes.active, shadow);
#endif
    lane_uint dropped = 0u;
    vec3 radiance =
        add_light_sample(PATH_READ(radiance, lanes), unoccluded, PATH_READ(shadow_radiance, lanes), &dropped);
    count_nonfinite(slot_nonfinite, WP_COUNTER_NONFINITE_DIRECT, lanes, dropped);
    lane_int ended = lanes.active && PATH_READ(shadow_ends_path, lanes) != 0u;
    PATH_WRITE(radiance, lanes, unoccluded && !ended, radiance);
    finish_paths(pass_radiance, PATH_READ(pass_item, lanes), ended, radiance);
#endif
}
