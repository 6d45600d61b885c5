/* Stage 5: BSDF sampling at the hit, the throughput update, and Russian
 * roulette: the path continues with a new extension ray or ends. */
#include "wavefront.h"

typedef struct {
    vec3 direction;
    vec3 weight;      /* throughput factor */
    vec3 leave_side;  /* normal on the side the new ray leaves into */
    uint specular;
} Scattered;

WP_FN Scattered scatter_diffuse(__global const DeviceMaterial *m, vec3 nf, real u, real v) {
    Scattered s;
    s.direction = frame_to_world(frame_from_normal(nf), sample_cosine_hemisphere(u, v));
    s.weight = vec3_at(m->albedo);
    s.leave_side = nf;
    s.specular = 0u;
    return s;
}

#ifdef WP_HAS_MIRROR
WP_FN Scattered scatter_mirror(__global const DeviceMaterial *m, vec3 d, vec3 nf) {
    Scattered s;
    s.direction = reflect_direction(d, nf);
    s.weight = vec3_at(m->reflectance);
    s.leave_side = nf;
    s.specular = 1u;
    return s;
}
#endif

#ifdef WP_HAS_GLASS
/* Fresnel chooses reflection or refraction; refraction scales radiance by 1/eta^2. */
WP_FN Scattered scatter_glass(__global const DeviceMaterial *m, vec3 d, vec3 nf, int entering, real u_lobe) {
    Scattered s;
    real eta = entering ? m->ior : REAL(1.0) / m->ior;
    real reflectance = fresnel_dielectric(-dot(d, nf), eta);
    s.specular = 1u;
    s.weight = make_vec3(REAL(1.0), REAL(1.0), REAL(1.0));
    s.leave_side = nf;
    s.direction = reflect_direction(d, nf);
    vec3 refracted;
    if (u_lobe >= reflectance && refract_direction(d, nf, eta, &refracted)) {
        s.direction = refracted;
        s.weight = s.weight / (eta * eta);
        s.leave_side = -nf;
    }
    return s;
}
#endif

__kernel __attribute__((reqd_work_group_size(WP_GROUP_SIZE, 1, 1))) void scatter(WP_STAGE_PARAMS) {
    WP_STAGE_INPUT(WP_QUEUE_SCATTER);
    int continues = 0, ends = 0;
    if (k != ~0u) {
        vec3 d = LOAD_XYZ(direction, slot);
        Surface surface = surface_at(WP_SCENE_ARGS, hit_shape[slot], LOAD_XYZ(origin, slot), d, hit_t[slot]);
        __global const DeviceMaterial *m = &materials[surface.material];
        int entering = dot(d, surface.normal) < REAL(0.0);
        vec3 nf = entering ? surface.normal : -surface.normal;
        uint seed = scene->seed, px = pixel[slot], s = sample[slot], bounce = depth[slot];
        Scattered scattered;
#ifdef WP_HAS_DIFFUSE
        if (m->type == WP_MATERIAL_DIFFUSE)
            scattered = scatter_diffuse(m, nf, rng_uniform(seed, px, s, bounce, DIM_BSDF_U),
                                        rng_uniform(seed, px, s, bounce, DIM_BSDF_V));
#endif
#ifdef WP_HAS_MIRROR
        if (m->type == WP_MATERIAL_MIRROR) scattered = scatter_mirror(m, d, nf);
#endif
#ifdef WP_HAS_GLASS
        if (m->type == WP_MATERIAL_GLASS)
            scattered = scatter_glass(m, d, nf, entering, rng_uniform(seed, px, s, bounce, DIM_BSDF_LOBE));
#endif
        vec3 throughput = LOAD_RGB(throughput, slot) * scattered.weight;
        uint new_depth = bounce + 1u;
        continues = 1;
        if (new_depth >= scene->rr_depth) {
            real survival = wp_clamp(max_component(throughput), REAL(0.05), REAL(1.0));
            continues = rng_uniform(seed, px, s, bounce, DIM_ROULETTE) < survival;
            throughput = throughput / survival;
        }
        if (continues) {
            STORE_XYZ(origin, slot, offset_ray_origin(surface.point, scattered.leave_side, surface.error));
            STORE_XYZ(direction, slot, scattered.direction);
            STORE_RGB(throughput, slot, throughput);
            depth[slot] = new_depth;
#ifdef WP_HAS_SPECULAR
            specular[slot] = scattered.specular;
#endif
        } else {
            finish_path(pass_radiance, counts, pass_item[slot], LOAD_RGB(radiance, slot));
        }
        ends = !continues;
    }
    queue_push(queues, counts, capacity, WP_QUEUE_RAY, continues, slot, &group_count, &group_base);
    queue_push(queues, counts, capacity, WP_QUEUE_FREE, ends, slot, &group_count, &group_base);
}
