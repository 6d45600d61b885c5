/* The megakernel baseline (--backend megakernel): one work item traces
 * WP_LANES x WP_MEGAKERNEL_PATHS_PER_LANE items of the pass (item w: pixel
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

/* The path a lane traces: its sample and where the path stands. */
typedef struct {
    lane_uint pixel, sample, depth;
    vec3 origin, direction, throughput, radiance;
    lane_int after_specular;
    real bsdf_pdf;  /* of the last diffuse bounce's direction */
    real eta_scale; /* eta^2 over the refractions so far (roulette_survival) */
} CameraPath;

/* The paths of pass items `item` at the camera (lanes not `active` start
 * round_pixels[0]'s, so that every lane holds a path it can trace). */
WP_FN CameraPath camera_paths(__global const SceneHeader *scene, __global const uint *round_pixels,
                              uint round_pixel_count, ulong pass_start, lane_uint item, lane_int active) {
    PassSample work = pass_item_sample(round_pixels, round_pixel_count, pass_start, item, active);
    CameraPath path;
    path.pixel = work.pixel;
    path.sample = work.sample;
    path.depth = 0u;
    path.origin = make_vec3(REAL(0.0), REAL(0.0), REAL(0.0)); /* the camera */
    path.direction = camera_ray_direction(scene, work.pixel, work.sample);
    path.throughput = make_vec3(REAL(1.0), REAL(1.0), REAL(1.0));
    path.radiance = make_vec3(REAL(0.0), REAL(0.0), REAL(0.0));
    path.after_specular = active;
    path.bsdf_pdf = REAL(0.0);
    path.eta_scale = REAL(1.0);
    return path;
}

/* `fresh` where `where` holds, else `path`. */
WP_FN CameraPath select_paths(lane_int where, CameraPath fresh, CameraPath path) {
    path.pixel = where ? fresh.pixel : path.pixel;
    path.sample = where ? fresh.sample : path.sample;
    path.depth = where ? fresh.depth : path.depth;
    path.origin = v3_select(where, fresh.origin, path.origin);
    path.direction = v3_select(where, fresh.direction, path.direction);
    path.throughput = v3_select(where, fresh.throughput, path.throughput);
    path.radiance = v3_select(where, fresh.radiance, path.radiance);
    path.after_specular = where ? fresh.after_specular : path.after_specular;
    path.bsdf_pdf = where ? fresh.bsdf_pdf : path.bsdf_pdf;
    path.eta_scale = where ? fresh.eta_scale : path.eta_scale;
    return path;
}

/* One bounce of the lanes' paths where `alive`: the hit, its emission, the
 * light sample and its shadow ray, the BSDF sample and the roulette. Returns
 * where the paths go on; adds their rays to extension_rays and shadow_rays
 * and the non-finite values they drop to dropped[stage]. */
WP_FN lane_int trace_bounce(WP_SCENE_PARAMS, lane_int alive, CameraPath *path, lane_uint *extension_rays,
                            lane_uint *shadow_rays, lane_uint dropped[WP_NONFINITE_STAGE_COUNT]) {
    *extension_rays += alive ? (lane_uint)1u : (lane_uint)0u;
    Hit hit = closest_hit(WP_SCENE_ARGS, path->origin, path->direction);
    lane_int missed = alive && hit.shape == WP_NO_HIT;
    alive = alive && !missed;
    Vertex v = vertex_at(WP_SCENE_ARGS, hit.shape, path->origin, path->direction, hit.t);
    path->radiance =
        add_radiance_seen(WP_SCENE_ARGS, path->radiance, missed, alive, hit.shape, path->origin, path->direction, v,
                          path->after_specular, path->bsdf_pdf, path->throughput, &dropped[0]);
    alive = alive && !vertex_ends_path(v, path->depth, scene->max_depth);
#if defined(WP_NEE) && defined(WP_HAS_NON_SPECULAR)
    DirectLight direct;
    lane_int casts_shadow =
        vertex_light_sample(WP_SCENE_ARGS, alive, v, path->pixel, path->sample, path->depth, path->throughput, &direct);
    *shadow_rays += casts_shadow ? (lane_uint)1u : (lane_uint)0u;
    path->radiance =
        add_light_sample(path->radiance, shadow_ray_reaches_light(WP_SCENE_ARGS, casts_shadow, direct.shadow),
                         direct.contribution, &dropped[1]);
#endif
    PathStep step = step_from_vertex(v, path->direction, path->throughput, path->eta_scale, scene->seed, path->pixel,
                                     path->sample, path->depth, scene->rr_depth);
    dropped[2] += alive ? step.nonfinite : (lane_uint)0u;
    alive = alive && step.continues;
    path->throughput = v3_select(alive, step.throughput, path->throughput);
    path->eta_scale = alive ? step.eta_scale : path->eta_scale;
    path->origin = v3_select(alive, step.origin, path->origin);
    path->direction = v3_select(alive, step.scattered.direction, path->direction);
    path->after_specular = step.scattered.specular != 0u;
    path->bsdf_pdf = step.scattered.pdf;
    path->depth += (lane_uint)1u;
    return alive;
}

__kernel __attribute__((reqd_work_group_size(WP_GROUP_SIZE, 1, 1))) void megakernel(
    WP_PARAMETERS(WP_MEGAKERNEL_PARAMETERS)) {
    __local uint group_extension_rays, group_shadow_rays, group_dropped[WP_NONFINITE_STAGE_COUNT];
    if (get_local_id(0) == 0) {
        group_extension_rays = group_shadow_rays = 0u;
        for (uint i = 0u; i < WP_NONFINITE_STAGE_COUNT; ++i) group_dropped[i] = 0u;
    }
    barrier(CLK_LOCAL_MEM_FENCE);
    /* Lane l of work item w traces items first, first + WP_LANES, ... (WP_MEGAKERNEL_PATHS_PER_LANE of them,
     * first = w * WP_LANES * that + l) one after another, each started as soon as the one before ends: the
     * lanes run until the last of their paths ends, and several paths per lane keep more of them busy than one. */
    lane_uint item = (uint)get_global_id(0) * (WP_LANES * WP_MEGAKERNEL_PATHS_PER_LANE(WP_LANES)) + lane_numbers();
    lane_uint last_item = item + (WP_LANES * (WP_MEGAKERNEL_PATHS_PER_LANE(WP_LANES) - 1u));
    lane_int alive = item < pass_size;
    if (lanes_any(alive)) {
        lane_uint extension_rays = 0u, shadow_rays = 0u, dropped[WP_NONFINITE_STAGE_COUNT] = {0u, 0u, 0u};
        CameraPath path = camera_paths(scene, round_pixels, round_pixel_count, pass_start, item, alive);
        while (lanes_any(alive)) {
            lane_int tracing = alive;
            alive = trace_bounce(WP_SCENE_ARGS, alive, &path, &extension_rays, &shadow_rays, dropped);
            lane_int ended = tracing && !alive;
            if (!lanes_any(ended)) continue;
            finish_paths(pass_radiance, item, ended, path.radiance);
            lane_int next = ended && item < last_item && item + (lane_uint)WP_LANES < pass_size;
            item = next ? item + (lane_uint)WP_LANES : item;
            if (lanes_any(next))
                path = select_paths(next, camera_paths(scene, round_pixels, round_pixel_count, pass_start, item, next),
                                    path);
            alive = alive || next;
        }
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
