/* Stage 3: everything a path does at its hit, WP_LANES paths per work item
 * (device/lanes.h), in the order of a vertex (device/path_vertex.h, as the
 * megakernel): the emission it sees (at depth 0 or after a specular bounce; at
 * every hit without next-event estimation; after a diffuse bounce, weighted
 * by multiple importance sampling against the light sample), the max_depth
 * cap and emitter materials (which end the path), the light sample of
 * next-event estimation at a diffuse vertex (its shadow ray goes to
 * intersect_shadow with its would-be contribution), then BSDF sampling, the
 * throughput and Russian roulette. The path state is read once and written
 * once. A path that ends here with a shadow ray to trace is finished by
 * intersect_shadow, which adds the light sample after the emission, as the
 * megakernel does. */
#include "device/guards.h"
#include "device/lanes.h"
#include "device/parameters.h"
#include "device/path_queues.h"
#include "device/path_vertex.h"
#include "device/surface.h"

__kernel __attribute__((reqd_work_group_size(WP_GROUP_SIZE, 1, 1))) void shade(WP_STAGE_PARAMS) {
    STAGE_QUEUES(shade, HIT, WP_PUSHES(SHADOW, RAY, FREE));
    __local uint group_count, group_base; /* queue_push's scratch (atomic compaction) */
    Lanes lanes = queue_lanes(queues, counts, capacity, stage_consumes);
    lane_uint shape = PATH_READ(hit_shape, lanes);
    vec3 origin = PATH_READ(origin, lanes), d = PATH_READ(direction, lanes);
    lane_uint px = PATH_READ(pixel, lanes), s = PATH_READ(sample, lanes), bounce = PATH_READ(depth, lanes);
    vec3 throughput = PATH_READ(throughput, lanes);
#ifdef WP_HAS_SPECULAR
    lane_int after_specular = PATH_READ(specular, lanes) != 0u;
#else
    lane_int after_specular = bounce == 0u;
#endif
#ifdef WP_MIS
    real bsdf_pdf = PATH_READ(bsdf_pdf, lanes);
#else
    real bsdf_pdf = REAL(0.0);
#endif
#ifdef WP_HAS_GLASS
    real eta_scale = PATH_READ(eta_scale, lanes);
#else
    real eta_scale = REAL(1.0);
#endif
    Vertex v = vertex_at(WP_SCENE_ARGS, shape, origin, d, PATH_READ(hit_t, lanes));

    lane_uint dropped = 0u;
    vec3 radiance =
        add_finite(PATH_READ(radiance, lanes),
                   hit_emission(WP_SCENE_ARGS, shape, origin, v, after_specular, bsdf_pdf, throughput), &dropped);
    count_nonfinite(slot_nonfinite, WP_COUNTER_NONFINITE_EMISSION, lanes, dropped);
    lane_int scatters = lanes.active && !vertex_ends_path(v, bounce, scene->max_depth);

    lane_int casts_shadow = 0;
#if defined(WP_NEE) && defined(WP_HAS_DIFFUSE)
    DirectLight direct;
    casts_shadow = vertex_light_sample(WP_SCENE_ARGS, scatters, v, px, s, bounce, throughput, &direct);
    PATH_WRITE(shadow_origin, lanes, casts_shadow, direct.shadow.origin);
    PATH_WRITE(shadow_direction, lanes, casts_shadow, direct.shadow.direction);
    PATH_WRITE(shadow_distance, lanes, casts_shadow, direct.shadow.distance);
    PATH_WRITE(shadow_radiance, lanes, casts_shadow, direct.contribution);
#endif

    PathStep step = step_from_vertex(v, d, throughput, eta_scale, scene->seed, px, s, bounce, scene->rr_depth);
    count_nonfinite(slot_nonfinite, WP_COUNTER_NONFINITE_SCATTER, lanes, scatters ? step.nonfinite : (lane_uint)0u);
    lane_int continues = scatters && step.continues, ends = lanes.active && !continues;
    PATH_WRITE(origin, lanes, continues, step.origin);
    PATH_WRITE(direction, lanes, continues, step.scattered.direction);
    PATH_WRITE(throughput, lanes, continues, step.throughput);
    /* every shaded path, so that count_depths finds a shadow ray's vertex at depth - 1 */
    PATH_WRITE(depth, lanes, lanes.active, bounce + 1u);
#ifdef WP_HAS_SPECULAR
    PATH_WRITE(specular, lanes, continues, step.scattered.specular);
#endif
#ifdef WP_MIS
    PATH_WRITE(bsdf_pdf, lanes, continues, step.scattered.pdf);
#endif
#ifdef WP_HAS_GLASS
    PATH_WRITE(eta_scale, lanes, continues, step.eta_scale);
#endif
#ifdef WP_NEE
    PATH_WRITE(shadow_ends_path, lanes, casts_shadow, ends ? (lane_uint)1u : (lane_uint)0u);
#endif
    PATH_WRITE(radiance, lanes, continues || casts_shadow, radiance);
    finish_paths(pass_radiance, PATH_READ(pass_item, lanes), ends && !casts_shadow, radiance);
    STAGE_PUSH(SHADOW, lanes, casts_shadow);
    STAGE_PUSH(RAY, lanes, continues);
    STAGE_PUSH(FREE, lanes, ends);
}
