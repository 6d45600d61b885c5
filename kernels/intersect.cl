/* Stage 2: closest hit of each extension ray. Hits go to shade_direct;
 * misses take the background and end. */
#include "wavefront.h"

__kernel __attribute__((reqd_work_group_size(WP_GROUP_SIZE, 1, 1))) void intersect(WP_STAGE_PARAMS) {
    WP_STAGE_INPUT(WP_QUEUE_RAY);
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
            uint dropped = 0u;
            radiance = add_finite(radiance, v3_mul(LOAD_RGB(throughput, slot), vec3_at(scene->background)), &dropped);
            count_nonfinite(slot_nonfinite, capacity, WP_COUNTER_NONFINITE_EMISSION, slot, dropped);
#endif
            finish_path(pass_radiance, pass_item[slot], radiance);
        }
    }
    queue_push(queues, counts, capacity, WP_QUEUE_HIT, hit_something, slot, &group_count, &group_base);
    queue_push(queues, counts, capacity, WP_QUEUE_FREE, missed, slot, &group_count, &group_base);
}
