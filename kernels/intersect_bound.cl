/* The roofline of the tracing stages (wavepath render --profile): camera rays
 * traced with closest_hit and nothing else, no queue and no path state read
 * or written, so that its rays/s is what the ray-primitive tests alone reach
 * on this device and each stage's rays/s reads as a fraction of it. WP_LANES
 * rays per work item, as in the stages. Ray r goes through the centre of
 * pixel r % (width * height); each ray writes its hit distance (0 for a miss
 * or past `ray_count`), so that the tests are not optimised away (and can be checked). */
#include "device/camera.h"
#include "device/lane_memory.h"
#include "device/lanes.h"
#include "device/parameters.h"
#include "device/scene_hits.h"
#include "interface/queues.h"

__kernel __attribute__((reqd_work_group_size(WP_GROUP_SIZE, 1, 1))) void intersect_bound(
    WP_PARAMETERS(WP_INTERSECT_BOUND_PARAMETERS)) {
    lane_uint ray = lane_positions(), pixel = ray % (scene->width * scene->height);
    vec3 direction = pixel_ray_direction(scene, pixel, REAL(0.5), REAL(0.5));
    Hit hit = closest_hit(WP_SCENE_ARGS, make_vec3(REAL(0.0), REAL(0.0), REAL(0.0)), direction);
    store_where(hit_t, ray, ray < ray_count, hit.shape != WP_NO_HIT ? hit.t : (real)REAL(0.0));
}
