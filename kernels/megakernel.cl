/* The megakernel baseline (--backend megakernel): one work item traces one
 * work item of the pass (pixel w % pixels, sample w / pixels) from the camera
 * to its end, with the same per-vertex functions (device/path_vertex.h) and random
 * numbers as the wavefront's stages, and writes its radiance to its pass
 * entry for accumulate.cl. It keeps the whole path in registers: no path
 * state, no queues, but divergent loops. */
#include "device/guards.h"
#include "device/parameters.h"
#include "device/path_queues.h"
#include "device/path_vertex.h"
#include "device/scene_hits.h"
#include "device/surface.h"
#include "interface/queues.h"

/* Traces one path; returns its radiance, adds its rays to extension_rays and
 * shadow_rays and the non-finite values it drops to dropped[stage]. */
WP_FN vec3 trace_path(WP_SCENE_PARAMS, uint px, uint s, uint *extension_rays, uint *shadow_rays,
                      uint dropped[WP_NONFINITE_STAGE_COUNT]) {
    uint seed = scene->seed;
    vec3 origin = make_vec3(REAL(0.0), REAL(0.0), REAL(0.0)); /* the camera, after loading */
    vec3 d = camera_ray_direction(scene, px, s);
    vec3 throughput = make_vec3(REAL(1.0), REAL(1.0), REAL(1.0));
    vec3 radiance = make_vec3(REAL(0.0), REAL(0.0), REAL(0.0));
    int after_specular = 1;
    real bsdf_pdf = REAL(0.0); /* of the last diffuse bounce's direction */
    for (uint depth = 0u;; ++depth) {
        ++*extension_rays;
        Hit hit = closest_hit(WP_SCENE_ARGS, origin, d);
        if (hit.shape == WP_NO_HIT) {
#ifdef WP_HAS_BACKGROUND
            radiance = add_finite(radiance, v3_mul(throughput, uniform_vec3(scene->background)), &dropped[0]);
#endif
            return radiance;
        }
        Vertex v = vertex_at(WP_SCENE_ARGS, hit.shape, origin, d, hit.t);
        Material m = v.material;
        real weight = emission_weight(WP_SCENE_ARGS, hit.shape, origin, v, after_specular, bsdf_pdf);
        radiance = add_finite(radiance, emission_seen(m, v.front, weight, throughput), &dropped[0]);
        if (depth >= scene->max_depth || m.type == WP_MATERIAL_EMITTER) return radiance;
#if defined(WP_NEE) && defined(WP_HAS_DIFFUSE)
        vec3 shadow_origin, shadow_direction, contribution;
        real distance;
        if (m.type == WP_MATERIAL_DIFFUSE &&
            sample_direct_light(WP_SCENE_ARGS, px, s, depth, v.surface.point, v.surface.error, v.nf, v.ns,
                                v3_mul(throughput, m.albedo), &shadow_origin, &shadow_direction, &distance,
                                &contribution)) {
            ++*shadow_rays;
            if (!any_hit(WP_SCENE_ARGS, shadow_origin, shadow_direction, distance))
                radiance = add_finite(radiance, contribution, &dropped[1]);
        }
#endif
        Scattered scattered = scatter_vertex(v, d, seed, px, s, depth);
        throughput = v3_mul(throughput, scattered.weight);
        if (!scattered.valid || !survives_roulette(&throughput, seed, px, s, depth, depth + 1u, scene->rr_depth) ||
            !throughput_is_finite(throughput, &dropped[2]))
            return radiance;
        origin = offset_ray_origin(v.surface.point, scattered.leave_side, v.surface.error);
        d = scattered.direction;
        after_specular = scattered.specular;
        bsdf_pdf = scattered.pdf;
    }
}

__kernel __attribute__((reqd_work_group_size(WP_GROUP_SIZE, 1, 1))) void megakernel(
    WP_PARAMETERS(WP_MEGAKERNEL_PARAMETERS)) {
    __local uint group_extension_rays, group_shadow_rays, group_dropped[WP_NONFINITE_STAGE_COUNT];
    if (get_local_id(0) == 0) {
        group_extension_rays = group_shadow_rays = 0u;
        for (uint i = 0u; i < WP_NONFINITE_STAGE_COUNT; ++i) group_dropped[i] = 0u;
    }
    barrier(CLK_LOCAL_MEM_FENCE);
    uint item = get_global_id(0);
    if (item < pass_size) {
        ulong work = pass_start + item;
        uint pixel_count = scene->width * scene->height;
        uint extension_rays = 0u, shadow_rays = 0u, dropped[WP_NONFINITE_STAGE_COUNT] = {0u, 0u, 0u};
        vec3 radiance = trace_path(WP_SCENE_ARGS, (uint)(work % pixel_count), (uint)(work / pixel_count),
                                   &extension_rays, &shadow_rays, dropped);
        finish_paths(pass_radiance, item, 1, radiance);
        atomic_add(&group_extension_rays, extension_rays);
        atomic_add(&group_shadow_rays, shadow_rays);
        for (uint i = 0u; i < WP_NONFINITE_STAGE_COUNT; ++i)
            if (dropped[i] != 0u) atomic_add(&group_dropped[i], dropped[i]);
    }
    /* One global atomic per counter and work group. */
    barrier(CLK_LOCAL_MEM_FENCE);
    if (get_local_id(0) == 0) {
        atomic_add(&counts[WP_COUNTER_EXTENSION_RAYS], group_extension_rays);
        atomic_add(&counts[WP_COUNTER_SHADOW_RAYS], group_shadow_rays);
        for (uint i = 0u; i < WP_NONFINITE_STAGE_COUNT; ++i)
            if (group_dropped[i] != 0u) atomic_add(&counts[WP_COUNTER_NONFINITE_EMISSION + i], group_dropped[i]);
    }
}
