/* Stage 5: BSDF sampling at the hit, the throughput update and Russian
 * roulette, WP_LANES paths per work item (lanes.h): each path continues
 * with a new extension ray or ends. */
#include "wavefront.h"
#include "vertex.h"

__kernel __attribute__((reqd_work_group_size(WP_GROUP_SIZE, 1, 1))) void scatter(WP_STAGE_PARAMS) {
    __local uint group_count, group_base; /* queue_push's scratch (atomic compaction) */
    Lanes lanes = queue_lanes(queues, counts, capacity, WP_QUEUE_SCATTER);
    vec3 d = LOAD_LANES_XYZ(direction, lanes);
    Vertex v = vertex_at(WP_SCENE_ARGS, lanes_load_uint(hit_shape, lanes), LOAD_LANES_XYZ(origin, lanes), d,
                         lanes_load_real(hit_t, lanes));
    uint seed = scene->seed;
    lane_uint px = lanes_load_uint(pixel, lanes), s = lanes_load_uint(sample, lanes), bounce = lanes_load_uint(depth, lanes);
    Scattered scattered = scatter_vertex(v.material, d, v.nf, v.front, seed, px, s, bounce);
    vec3 throughput = v3_mul(LOAD_LANES_RGB(throughput, lanes), scattered.weight);
    lane_uint new_depth = bounce + 1u, dropped = 0u;
    lane_int survives = survives_roulette(&throughput, seed, px, s, bounce, new_depth, scene->rr_depth);
    lane_int continues = lanes.active && survives && throughput_is_finite(throughput, &dropped);
    /* only paths that survived roulette count a non-finite throughput (as with one lane, where && stops early) */
    count_nonfinite(slot_nonfinite, capacity, WP_COUNTER_NONFINITE_SCATTER, lanes, survives ? dropped : (lane_uint)0u);
    lane_int ends = lanes.active && !continues;
    STORE_LANES_XYZ(origin, lanes, continues, offset_ray_origin(v.surface.point, scattered.leave_side, v.surface.error));
    STORE_LANES_XYZ(direction, lanes, continues, scattered.direction);
    STORE_LANES_RGB(throughput, lanes, continues, throughput);
    lanes_store_uint(depth, lanes, continues, new_depth);
#ifdef WP_HAS_SPECULAR
    lanes_store_uint(specular, lanes, continues, scattered.specular);
#endif
    finish_paths(pass_radiance, lanes_load_uint(pass_item, lanes), ends, LOAD_LANES_RGB(radiance, lanes));
    push_lanes(queues, counts, capacity, WP_QUEUE_RAY, lanes, continues, &group_count, &group_base);
    push_lanes(queues, counts, capacity, WP_QUEUE_FREE, lanes, ends, &group_count, &group_base);
}
