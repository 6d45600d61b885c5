/* Stage 5: BSDF sampling at the hit, the throughput update and Russian
 * roulette, WP_LANES paths per work item (device/lanes.h): each path continues
 * with a new extension ray or ends. */
#include "device/guards.h"
#include "device/lanes.h"
#include "device/parameters.h"
#include "device/path_queues.h"
#include "device/path_vertex.h"
#include "device/surface.h"

__kernel __attribute__((reqd_work_group_size(WP_GROUP_SIZE, 1, 1))) void scatter(WP_STAGE_PARAMS) {
    STAGE_QUEUES(scatter, SCATTER, WP_PUSHES(RAY, FREE));
    __local uint group_count, group_base; /* queue_push's scratch (atomic compaction) */
    Lanes lanes = queue_lanes(queues, counts, capacity, stage_consumes);
    vec3 d = PATH_READ(direction, lanes);
    Vertex v =
        vertex_at(WP_SCENE_ARGS, PATH_READ(hit_shape, lanes), PATH_READ(origin, lanes), d, PATH_READ(hit_t, lanes));
    uint seed = scene->seed;
    lane_uint px = PATH_READ(pixel, lanes), s = PATH_READ(sample, lanes), bounce = PATH_READ(depth, lanes);
    BsdfSample scattered = scatter_vertex(v, d, seed, px, s, bounce);
    vec3 throughput = v3_mul(PATH_READ(throughput, lanes), scattered.weight);
    lane_uint new_depth = bounce + 1u, dropped = 0u;
#ifdef WP_HAS_GLASS
    real eta_scale = PATH_READ(eta_scale, lanes) * scattered.eta_squared;
#else
    real eta_scale = REAL(1.0);
#endif
    lane_int survives = survives_roulette(&throughput, eta_scale, seed, px, s, bounce, new_depth, scene->rr_depth);
    lane_int continues = lanes.active && scattered.valid && survives && throughput_is_finite(throughput, &dropped);
    /* only paths that left validly and survived roulette count a non-finite throughput (as with one lane, where
     * && stops early) */
    count_nonfinite(slot_nonfinite, WP_COUNTER_NONFINITE_SCATTER, lanes,
                    scattered.valid && survives ? dropped : (lane_uint)0u);
    lane_int ends = lanes.active && !continues;
    PATH_WRITE(origin, lanes, continues, offset_ray_origin(v.surface.point, scattered.leave_side, v.surface.error));
    PATH_WRITE(direction, lanes, continues, scattered.direction);
    PATH_WRITE(throughput, lanes, continues, throughput);
    PATH_WRITE(depth, lanes, continues, new_depth);
#ifdef WP_HAS_SPECULAR
    PATH_WRITE(specular, lanes, continues, scattered.specular);
#endif
#ifdef WP_MIS
    PATH_WRITE(bsdf_pdf, lanes, continues, scattered.pdf);
#endif
#ifdef WP_HAS_GLASS
    PATH_WRITE(eta_scale, lanes, continues, eta_scale);
#endif
    finish_paths(pass_radiance, PATH_READ(pass_item, lanes), ends, PATH_READ(radiance, lanes));
    STAGE_PUSH(RAY, lanes, continues);
    STAGE_PUSH(FREE, lanes, ends);
}
