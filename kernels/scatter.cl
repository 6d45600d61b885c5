/* Stage 5: BSDF sampling at the hit, the throughput update, and Russian
 * roulette: the path continues with a new extension ray or ends. */
#include "wavefront.h"
#include "vertex.h"

__kernel __attribute__((reqd_work_group_size(WP_GROUP_SIZE, 1, 1))) void scatter(WP_STAGE_PARAMS) {
    WP_STAGE_INPUT(WP_QUEUE_SCATTER);
    int continues = 0, ends = 0;
    if (k != ~0u) {
        vec3 d = LOAD_XYZ(direction, slot);
        Surface surface = surface_at(WP_SCENE_ARGS, hit_shape[slot], LOAD_XYZ(origin, slot), d, hit_t[slot]);
        __global const DeviceMaterial *m = &materials[surface.material];
        int entering = v3_dot(d, surface.normal) < REAL(0.0);
        vec3 nf = v3_select(entering, surface.normal, v3_neg(surface.normal));
        uint seed = scene->seed, px = pixel[slot], s = sample[slot], bounce = depth[slot];
        Scattered scattered = scatter_vertex(m, d, nf, entering, seed, px, s, bounce);
        vec3 throughput = v3_mul(LOAD_RGB(throughput, slot), scattered.weight);
        uint new_depth = bounce + 1u, dropped = 0u;
        continues = survives_roulette(&throughput, seed, px, s, bounce, new_depth, scene->rr_depth) &&
                    throughput_is_finite(throughput, &dropped);
        count_nonfinite(slot_nonfinite, capacity, WP_COUNTER_NONFINITE_SCATTER, slot, dropped);
        if (continues) {
            STORE_XYZ(origin, slot, offset_ray_origin(surface.point, scattered.leave_side, surface.error));
            STORE_XYZ(direction, slot, scattered.direction);
            STORE_RGB(throughput, slot, throughput);
            depth[slot] = new_depth;
#ifdef WP_HAS_SPECULAR
            specular[slot] = scattered.specular;
#endif
        } else {
            finish_path(pass_radiance, pass_item[slot], LOAD_RGB(radiance, slot));
        }
        ends = !continues;
    }
    queue_push(queues, counts, capacity, WP_QUEUE_RAY, continues, slot, &group_count, &group_base);
    queue_push(queues, counts, capacity, WP_QUEUE_FREE, ends, slot, &group_count, &group_base);
}
