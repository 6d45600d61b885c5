/* The megakernel baseline (--backend megakernel): one work item traces
 * WP_LANES work items of the pass (work item w: pixel
 * round_pixels[w % round_pixel_count], sample w / round_pixel_count) from the camera to their ends, with the same
 * per-vertex functions (device/path_vertex.h) and random numbers as the wavefront's stages, and writes their radiance
 * to their pass entries for accumulate.cl. It keeps the whole path in registers: no path state, no queues, but
 * divergent loops. With several lanes (-DWP_LANES=4, 8 or 16 on CPUs, as
 * the wavefront's stages) the lanes run as vector code until the last of their
 * paths ends: the single-kernel design at its best on a CPU, the like-for-like
 * baseline for the wavefront. */
#include "device/guards.h"
#include "device/lanes.h"
#include "device/parameters.h"
#include "device/pass_radiance.h"
#include "device/path_vertex.h"
#include "device/scene_hits.h"
#include "device/surface.h"
#include "interface/queues.h"

/* t where `where` holds, else nothing: a term added only in some lanes. */
WP_FN vec3 only_where(lane_int where, vec3 term) {
    return v3_select(where, term, make_vec3(REAL(0.0), REAL(0.0), REAL(0.0)));
}

/* Traces the lanes' paths (where `alive`); returns their radiance, adds their
 * rays to extension_rays and shadow_rays and the non-finite values they drop
 * to dropped[stage]. */
WP_FN vec3 trace_paths(WP_SCENE_PARAMS, lane_int alive, lane_uint px, lane_uint s, lane_uint *extension_rays,
                       lane_uint *shadow_rays, lane_uint dropped[WP_NONFINITE_STAGE_COUNT]) {
    uint seed = scene->seed;
    vec3 origin = make_vec3(REAL(0.0), REAL(0.0), REAL(0.0)); /* the camera, after loading */
    vec3 d = camera_ray_direction(scene, px, s);
    vec3 throughput = make_vec3(REAL(1.0), REAL(1.0), REAL(1.0));
    vec3 radiance = make_vec3(REAL(0.0), REAL(0.0), REAL(0.0));
    lane_int after_specular = alive;
    real bsdf_pdf = REAL(0.0);  /* of the last diffuse bounce's direction */
    real eta_scale = REAL(1.0); /* eta^2 over the refractions so far (roulette_survival) */
    for (uint depth = 0u; lanes_any(alive); ++depth) {
        *extension_rays += alive ? (lane_uint)1u : (lane_uint)0u;
        Hit hit = closest_hit(WP_SCENE_ARGS, origin, d);
        lane_int missed = alive && hit.shape == WP_NO_HIT;
#ifdef WP_HAS_BACKGROUND
        radiance = add_finite(
            radiance, only_where(missed, background_seen(throughput, uniform_vec3(scene->background))), &dropped[0]);
#endif
        alive = alive && !missed;
        Vertex v = vertex_at(WP_SCENE_ARGS, hit.shape, origin, d, hit.t);
        vec3 emitted = hit_emission(WP_SCENE_ARGS, hit.shape, origin, v, after_specular, bsdf_pdf, throughput);
        radiance = add_finite(radiance, only_where(alive, emitted), &dropped[0]);
        alive = alive && !vertex_ends_path(v, depth, scene->max_depth);
#if defined(WP_NEE) && defined(WP_HAS_DIFFUSE)
        DirectLight direct;
        lane_int casts_shadow = vertex_light_sample(WP_SCENE_ARGS, alive, v, px, s, depth, throughput, &direct);
        *shadow_rays += casts_shadow ? (lane_uint)1u : (lane_uint)0u;
        lane_int lit = casts_shadow;
        if (lanes_any(casts_shadow))
            lit = casts_shadow &&
                  !any_hit(WP_SCENE_ARGS, direct.shadow.origin, direct.shadow.direction, direct.shadow.distance);
        radiance = add_finite(radiance, only_where(lit, direct.contribution), &dropped[1]);
#endif
        PathStep step = step_from_vertex(v, d, throughput, eta_scale, seed, px, s, depth, scene->rr_depth);
        dropped[2] += alive ? step.nonfinite : (lane_uint)0u;
        alive = alive && step.continues;
        throughput = v3_select(alive, step.throughput, throughput);
        eta_scale = alive ? step.eta_scale : eta_scale;
        origin = v3_select(alive, step.origin, origin);
        d = v3_select(alive, step.scattered.direction, d);
        after_specular = step.scattered.specular != 0u;
        bsdf_pdf = step.scattered.pdf;
    }
    return radiance;
}

__kernel __attribute__((reqd_work_group_size(WP_GROUP_SIZE, 1, 1))) void megakernel(
    WP_PARAMETERS(WP_MEGAKERNEL_PARAMETERS)) {
    __local uint group_extension_rays, group_shadow_rays, group_dropped[WP_NONFINITE_STAGE_COUNT];
    if (get_local_id(0) == 0) {
        group_extension_rays = group_shadow_rays = 0u;
        for (uint i = 0u; i < WP_NONFINITE_STAGE_COUNT; ++i) group_dropped[i] = 0u;
    }
    barrier(CLK_LOCAL_MEM_FENCE);
    lane_uint item = lane_positions();
    lane_int active = item < pass_size;
    if (lanes_any(active)) {
        PassSample work = pass_item_sample(round_pixels, round_pixel_count, pass_start, item, active);
        lane_uint extension_rays = 0u, shadow_rays = 0u, dropped[WP_NONFINITE_STAGE_COUNT] = {0u, 0u, 0u};
        vec3 radiance =
            trace_paths(WP_SCENE_ARGS, active, work.pixel, work.sample, &extension_rays, &shadow_rays, dropped);
        finish_paths(pass_radiance, item, active, radiance);
        atomic_add(&group_extension_rays, lanes_sum(extension_rays));
        atomic_add(&group_shadow_rays, lanes_sum(shadow_rays));
        for (uint i = 0u; i < WP_NONFINITE_STAGE_COUNT; ++i) {
            uint stage_dropped = lanes_sum(dropped[i]);
            if (stage_dropped != 0u) atomic_add(&group_dropped[i], stage_dropped);
        }
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
