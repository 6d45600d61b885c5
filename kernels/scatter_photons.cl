/* SPPM's photon pass, stage 4: BSDF sampling at the photon's hit with the
 * shared materials, as flux (WP_TRANSPORT_IMPORTANCE, with the adjoint
 * correction for shading normals: photon_bsdf_sample), its throughput and
 * Russian roulette as camera paths play it, WP_LANES photons per work item:
 * each goes on with a new ray or ends. */
#include "device/guards.h"
#include "device/lanes.h"
#include "device/parameters.h"
#include "device/path_queues.h"
#include "device/photon_vertex.h"
#include "device/surface.h"

__kernel __attribute__((reqd_work_group_size(WP_GROUP_SIZE, 1, 1))) void scatter_photons(WP_STAGE_PARAMS) {
    STAGE_QUEUES(scatter_photons, PHOTON_SCATTER, WP_PUSHES(PHOTON_RAY, PHOTON_FREE));
    __local uint group_count, group_base; /* queue_push's scratch (atomic compaction) */
    Lanes lanes = queue_lanes(queues, counts, capacity, stage_consumes);
#ifdef WP_SPPM
    vec3 d = PATH_READ(direction, lanes);
    Vertex v =
        vertex_at(WP_SCENE_ARGS, PATH_READ(hit_shape, lanes), PATH_READ(origin, lanes), d, PATH_READ(hit_t, lanes));
    uint seed = scene->seed, iteration = photon_pass_iteration(scene, pass_start);
    lane_uint photon = PATH_READ(photon, lanes), depth = PATH_READ(depth, lanes);
    BsdfSample scattered = photon_bsdf_sample(
        scatter_vertex(v, d, photon_bsdf_random(seed, iteration, photon, depth), WP_TRANSPORT_IMPORTANCE), v3_neg(d),
        v.nf, v.ns, WP_USES_SHADING_NORMALS);
    lane_uint new_depth = depth + 1u, dropped = 0u;
    RouletteOutcome roulette = russian_roulette(v3_mul(PATH_READ(throughput, lanes), scattered.weight), REAL(1.0),
                                                new_depth >= scene->rr_depth,
                                                photon_uniform(seed, iteration, photon, depth, DIM_PHOTON_ROULETTE));
    lane_int continues =
        lanes.active && scattered.valid && roulette.survives && throughput_is_finite(roulette.throughput, &dropped);
    count_nonfinite(slot_nonfinite, WP_COUNTER_NONFINITE_SCATTER, lanes,
                    scattered.valid && roulette.survives ? dropped : (lane_uint)0u);
    lane_int ends = lanes.active && !continues;
    PATH_WRITE(origin, lanes, continues, offset_ray_origin(v.surface.point, scattered.leave_side, v.surface.error));
    PATH_WRITE(direction, lanes, continues, scattered.direction);
    PATH_WRITE(throughput, lanes, continues, roulette.throughput);
    PATH_WRITE(depth, lanes, continues, new_depth);
#else
    lane_int continues = 0, ends = 0;
#endif
    STAGE_PUSH(PHOTON_RAY, lanes, continues);
    STAGE_PUSH(PHOTON_FREE, lanes, ends);
}
