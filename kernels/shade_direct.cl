/* Stage 3: what the path sees at its hit, WP_LANES paths per work item
 * (lanes.h). Emission (at depth 0 or after a specular bounce; at every hit
 * with -DWP_NEE_OFF), the max_depth cap and emitter materials (which end
 * the path), and next-event estimation at diffuse vertices: one light sample
 * whose shadow ray goes to intersect_shadow with its would-be contribution. */
#include "wavefront.h"
#include "vertex.h"

__kernel __attribute__((reqd_work_group_size(WP_GROUP_SIZE, 1, 1))) void shade_direct(WP_STAGE_PARAMS) {
    __local uint group_count, group_base; /* queue_push's scratch (atomic compaction) */
    Lanes lanes = queue_lanes(queues, counts, capacity, WP_QUEUE_HIT);
    Vertex v = vertex_at(WP_SCENE_ARGS, lanes_load_uint(hit_shape, lanes), LOAD_LANES_XYZ(origin, lanes),
                         LOAD_LANES_XYZ(direction, lanes), lanes_load_real(hit_t, lanes));
    Material m = v.material;
    lane_uint bounce = lanes_load_uint(depth, lanes);
    vec3 throughput = LOAD_LANES_RGB(throughput, lanes);
#ifdef WP_HAS_SPECULAR
    lane_int after_specular = lanes_load_uint(specular, lanes) != 0u;
#else
    lane_int after_specular = bounce == 0u;
#endif
    lane_uint dropped = 0u;
    vec3 radiance =
        add_finite(LOAD_LANES_RGB(radiance, lanes), emission_seen(m, v.front, after_specular, throughput), &dropped);
    count_nonfinite(slot_nonfinite, capacity, WP_COUNTER_NONFINITE_EMISSION, lanes, dropped);
    lane_int ends = lanes.active && (bounce >= scene->max_depth || m.type == WP_MATERIAL_EMITTER);
    lane_int scatters = lanes.active && !ends;
    finish_paths(pass_radiance, lanes_load_uint(pass_item, lanes), ends, radiance);
    STORE_LANES_RGB(radiance, lanes, scatters, radiance);
    lane_int casts_shadow = 0;
#if defined(WP_HAS_NEE) && defined(WP_HAS_DIFFUSE)
    vec3 shadow_from, shadow_towards, contribution;
    real distance;
    lane_int carries = sample_direct_light(WP_SCENE_ARGS, lanes_load_uint(pixel, lanes), lanes_load_uint(sample, lanes), bounce,
                                           v.surface.point, v.surface.error, v.nf, v3_mul(throughput, m.albedo),
                                           &shadow_from,
                                           &shadow_towards, &distance, &contribution);
    casts_shadow = scatters && m.type == WP_MATERIAL_DIFFUSE && carries;
    STORE_LANES_XYZ(shadow_origin, lanes, casts_shadow, shadow_from);
    STORE_LANES_XYZ(shadow_direction, lanes, casts_shadow, shadow_towards);
    lanes_store_real(shadow_distance, lanes, casts_shadow, distance);
    STORE_LANES_RGB(shadow_radiance, lanes, casts_shadow, contribution);
#endif
    push_lanes(queues, counts, capacity, WP_QUEUE_SHADOW, lanes, casts_shadow, &group_count, &group_base);
    push_lanes(queues, counts, capacity, WP_QUEUE_SCATTER, lanes, scatters, &group_count, &group_base);
    push_lanes(queues, counts, capacity, WP_QUEUE_FREE, lanes, ends, &group_count, &group_base);
}
