/* Stage 3: what the path sees at its hit. Emission (at depth 0 or after a
 * specular bounce), the max_depth cap and emitter materials (which end the
 * path), and next-event estimation at diffuse vertices: one light sample
 * whose shadow ray goes to intersect_shadow with its would-be contribution. */
#include "wavefront.h"

/* Samples one light for the diffuse vertex (x, nf); returns 1 with the shadow
 * ray and the contribution it adds when unoccluded, 0 when the sample carries
 * nothing. */
#ifdef WP_HAS_NEE
WP_FN int sample_direct_light(WP_SCENE_PARAMS, uint pixel, uint sample, uint bounce, vec3 x, real x_error, vec3 nf,
                              vec3 weight,
                              vec3 *shadow_origin, vec3 *shadow_direction, real *shadow_distance,
                              vec3 *contribution) {
    uint seed = scene->seed;
    uint light = select_light(light_cdf, scene->light_count, rng_uniform(seed, pixel, sample, bounce, DIM_LIGHT_SELECT));
    real pmf = light_selection_pmf(light_cdf, light);
    real u = rng_uniform(seed, pixel, sample, bounce, DIM_LIGHT_U);
    real v = rng_uniform(seed, pixel, sample, bounce, DIM_LIGHT_V);
    uint index = lights[light].shape & WP_SHAPE_INDEX_MASK;
    LightSample ls;
    uint material = 0u;
    real magnitude = REAL(0.0);
#ifdef WP_HAS_SPHERE_LIGHTS
    if ((lights[light].shape >> WP_SHAPE_TYPE_SHIFT) == WP_SHAPE_SPHERE) {
        vec3 center = vec3_at(spheres[index].center);
        ls = sample_sphere(center, spheres[index].radius, x, u, v);
        material = spheres[index].material;
        magnitude = sphere_magnitude(center, spheres[index].radius);
    }
#endif
#ifdef WP_HAS_QUAD_LIGHTS
    if ((lights[light].shape >> WP_SHAPE_TYPE_SHIFT) == WP_SHAPE_QUAD) {
        vec3 corner = vec3_at(quads[index].corner), edge1 = vec3_at(quads[index].edge1);
        vec3 edge2 = vec3_at(quads[index].edge2);
        ls = sample_quad(corner, edge1, edge2, x, u, v);
        material = quads[index].material;
        magnitude = quad_magnitude(corner, edge1, edge2);
    }
#endif
    if (ls.pdf_solid_angle == REAL(0.0)) return 0;
    vec3 wi = normalize(ls.point - x);
    real cos_surface = dot(wi, nf);
    int light_faces_x = dot(ls.normal, x - ls.point) > REAL(0.0);
    if (!(cos_surface > REAL(0.0)) || !(materials[material].two_sided || light_faces_x)) return 0;
    vec3 from = offset_ray_origin(x, nf, x_error);
    vec3 to = offset_ray_origin(ls.point, light_faces_x ? ls.normal : -ls.normal,
                                shadow_target_error(x, ls.point, magnitude));
    *shadow_distance = length(to - from);
    *shadow_direction = (to - from) / *shadow_distance;
    *shadow_origin = from;
    *contribution = weight * WP_INV_PI * vec3_at(materials[material].emission) * cos_surface / (ls.pdf_solid_angle * pmf);
    return 1;
}
#endif

__kernel __attribute__((reqd_work_group_size(WP_GROUP_SIZE, 1, 1))) void shade_direct(WP_STAGE_PARAMS) {
    WP_STAGE_INPUT(WP_QUEUE_HIT);
    int ends = 0, scatters = 0, casts_shadow = 0;
    if (k != ~0u) {
        vec3 d = LOAD_XYZ(direction, slot);
        Surface s = surface_at(WP_SCENE_ARGS, hit_shape[slot], LOAD_XYZ(origin, slot), d, hit_t[slot]);
        __global const DeviceMaterial *m = &materials[s.material];
        real cos_incident = dot(d, s.normal);
        vec3 nf = cos_incident < REAL(0.0) ? s.normal : -s.normal;
        uint bounce = depth[slot];
        vec3 throughput = LOAD_RGB(throughput, slot);
        vec3 radiance = LOAD_RGB(radiance, slot);
        int after_specular = bounce == 0u;
#ifdef WP_HAS_SPECULAR
        after_specular = specular[slot] != 0u;
#endif
        vec3 emission = vec3_at(m->emission);
        int emits = emission.x > REAL(0.0) || emission.y > REAL(0.0) || emission.z > REAL(0.0);
        if (emits && (m->two_sided || cos_incident < REAL(0.0)) && after_specular) radiance += throughput * emission;
        ends = bounce >= scene->max_depth || m->type == WP_MATERIAL_EMITTER;
        if (ends) {
            finish_path(pass_radiance, counts, pass_item[slot], radiance);
        } else {
            STORE_RGB(radiance, slot, radiance);
            scatters = 1;
#ifdef WP_HAS_NEE
            vec3 shadow_origin, shadow_direction, contribution;
            real distance;
            if (m->type == WP_MATERIAL_DIFFUSE &&
                sample_direct_light(WP_SCENE_ARGS, pixel[slot], sample[slot], bounce, s.point, s.error, nf,
                                    throughput * vec3_at(m->albedo), &shadow_origin, &shadow_direction, &distance,
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
