/* Stage 2: closest hit of each extension ray. Hits go to shade_direct;
 * misses take the background and end. */
#include "wavefront.h"
#include "profile.h"

__kernel __attribute__((reqd_work_group_size(WP_GROUP_SIZE, 1, 1))) void intersect(WP_STAGE_PARAMS) {
    WP_STAGE_INPUT(WP_QUEUE_RAY);
    WP_DEPTH_HISTOGRAM_SCRATCH;
    int hit_something = 0, missed = 0;
    if (k != ~0u) {
        Hit hit = closest_hit(WP_SCENE_ARGS, LOAD_XYZ(origin, slot), LOAD_XYZ(direction, slot));
        hit_t[slot] = hit.t;
        hit_shape[slot] = hit.shape;
        hit_something = hit.shape != WP_NO_HIT;
        missed = !hit_something;
        if (missed) {
            vec3 radiance = LOAD_RGB(radiance, slot);
#ifdef WP_HAS_BACKGROUND
            radiance = add_finite(radiance, LOAD_RGB(throughput, slot) * vec3_at(scene->background), counts,
                                  WP_COUNTER_NONFINITE_EMISSION);
#endif
            finish_path(pass_radiance, pass_item[slot], radiance);
        }
    }
    queue_push(queues, counts, capacity, WP_QUEUE_HIT, hit_something, slot, &group_count, &group_base);
    queue_push(queues, counts, capacity, WP_QUEUE_FREE, missed, slot, &group_count, &group_base);
    COUNT_BY_DEPTH(WP_PROFILE_EXTENSION_BY_DEPTH, k != ~0u, depth[slot]);
}
