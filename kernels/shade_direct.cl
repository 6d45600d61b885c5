/* Stage 3: what the path sees at its hit, WP_LANES paths per work item
 * (device/lanes.h). Emission (at depth 0 or after a specular bounce; at every hit
 * without next-event estimation; after a diffuse bounce, weighted by multiple
 * importance sampling against the light sample), the max_depth cap and emitter materials (which end
 * the path), and next-event estimation at diffuse vertices: one light sample
 * whose shadow ray goes to intersect_shadow with its would-be contribution. */
#include "device/guards.h"
#include "device/lanes.h"
#include "device/parameters.h"
#include "device/path_queues.h"
#include "device/path_vertex.h"
#include "device/surface.h"

__kernel __attribute__((reqd_work_group_size(WP_GROUP_SIZE, 1, 1))) void shade_direct(WP_STAGE_PARAMS) {
    STAGE_QUEUES(shade_direct, HIT, WP_PUSHES(SHADOW, SCATTER, FREE));
    __local uint group_count, group_base; /* queue_push's scratch (atomic compaction) */
    Lanes lanes = queue_lanes(queues, counts, capacity, stage_consumes);
    lane_uint shape = PATH_READ(hit_shape, lanes);
    vec3 origin = PATH_READ(origin, lanes);
    Vertex v = vertex_at(WP_SCENE_ARGS, shape, origin, PATH_READ(direction, lanes), PATH_READ(hit_t, lanes));
    Material m = v.material;
    lane_uint bounce = PATH_READ(depth, lanes);
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
    real weight = hit_emission_weight(WP_SCENE_ARGS, shape, origin, v, after_specular, bsdf_pdf);
    lane_uint dropped = 0u;
    vec3 radiance = add_finite(PATH_READ(radiance, lanes),
                               emission_seen(m.emission, m.two_sided, v.front, weight, throughput), &dropped);
    count_nonfinite(slot_nonfinite, WP_COUNTER_NONFINITE_EMISSION, lanes, dropped);
    lane_int ends = lanes.active && (bounce >= scene->max_depth || m.type == WP_MATERIAL_EMITTER);
    lane_int scatters = lanes.active && !ends;
    finish_paths(pass_radiance, PATH_READ(pass_item, lanes), ends, radiance);
    PATH_WRITE(radiance, lanes, scatters, radiance);
    lane_int casts_shadow = 0;
#if defined(WP_NEE) && defined(WP_HAS_DIFFUSE)
    DirectLight direct;
    lane_int carries = sample_direct_light(WP_SCENE_ARGS, PATH_READ(pixel, lanes), PATH_READ(sample, lanes), bounce,
                                           v.surface.point, v.surface.error, v.nf, v.ns, throughput, m.albedo, &direct);
    casts_shadow = scatters && m.type == WP_MATERIAL_DIFFUSE && carries;
    PATH_WRITE(shadow_origin, lanes, casts_shadow, direct.shadow.origin);
    PATH_WRITE(shadow_direction, lanes, casts_shadow, direct.shadow.direction);
    PATH_WRITE(shadow_distance, lanes, casts_shadow, direct.shadow.distance);
    PATH_WRITE(shadow_radiance, lanes, casts_shadow, direct.contribution);
#endif
    STAGE_PUSH(SHADOW, lanes, casts_shadow);
    STAGE_PUSH(SCATTER, lanes, scatters);
    STAGE_PUSH(FREE, lanes, ends);
}
