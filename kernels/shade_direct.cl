/* Stage 3: what the path sees at its hit. Emission (at depth 0 or after a
 * specular bounce; at every hit with -DWP_NEE_OFF), the max_depth cap and emitter materials (which end the
 * path), and next-event estimation at diffuse vertices: one light sample
 * whose shadow ray goes to intersect_shadow with its would-be contribution. */
#include "wavefront.h"
#include "vertex.h"

__kernel __attribute__((reqd_work_group_size(WP_GROUP_SIZE, 1, 1))) void shade_direct(WP_STAGE_PARAMS) {
    WP_STAGE_INPUT(WP_QUEUE_HIT);
    int ends = 0, scatters = 0, casts_shadow = 0;
    if (k != ~0u) {
        vec3 d = LOAD_XYZ(direction, slot);
        Surface s = surface_at(WP_SCENE_ARGS, hit_shape[slot], LOAD_XYZ(origin, slot), d, hit_t[slot]);
        __global const DeviceMaterial *m = &materials[s.material];
        real cos_incident = v3_dot(d, s.normal);
        vec3 nf = v3_select(cos_incident < REAL(0.0), s.normal, v3_neg(s.normal));
        uint bounce = depth[slot];
        vec3 throughput = LOAD_RGB(throughput, slot);
        vec3 radiance = LOAD_RGB(radiance, slot);
        int after_specular = bounce == 0u;
#ifdef WP_HAS_SPECULAR
        after_specular = specular[slot] != 0u;
#endif
        uint dropped = 0u;
        radiance = add_finite(radiance, emission_seen(m, cos_incident, after_specular, throughput), &dropped);
        count_nonfinite(slot_nonfinite, capacity, WP_COUNTER_NONFINITE_EMISSION, slot, dropped);
        ends = bounce >= scene->max_depth || m->type == WP_MATERIAL_EMITTER;
        if (ends) {
            finish_path(pass_radiance, pass_item[slot], radiance);
        } else {
            STORE_RGB(radiance, slot, radiance);
            scatters = 1;
#ifdef WP_HAS_NEE
            vec3 shadow_origin, shadow_direction, contribution;
            real distance;
            if (m->type == WP_MATERIAL_DIFFUSE &&
                sample_direct_light(WP_SCENE_ARGS, pixel[slot], sample[slot], bounce, s.point, s.error, nf,
                                    v3_mul(throughput, vec3_at(m->albedo)), &shadow_origin, &shadow_direction, &distance,
                                    &contribution)) {
                STORE_XYZ(shadow_origin, slot, shadow_origin);
                STORE_XYZ(shadow_direction, slot, shadow_direction);
                shadow_distance[slot] = distance;
                STORE_RGB(shadow_radiance, slot, contribution);
                casts_shadow = 1;
            }
#endif
        }
    }
    queue_push(queues, counts, capacity, WP_QUEUE_SHADOW, casts_shadow, slot, &group_count, &group_base);
    queue_push(queues, counts, capacity, WP_QUEUE_SCATTER, scatters, slot, &group_count, &group_base);
    queue_push(queues, counts, capacity, WP_QUEUE_FREE, ends, slot, &group_count, &group_base);
}
