/* shade's work at WP_LANES paths' hits (device/lanes.h), whichever kernel
 * traced them: shade.cl, after intersect traced them in a stage of its own,
 * or intersect_and_shade.cl, which traces and shades in one launch
 * (interface/stages.h). In the order of a vertex (device/path_vertex.h, as
 * the megakernel): a miss takes the background and ends; at a hit, the
 * emission it sees (at depth 0 or after a specular bounce; at every hit
 * without next-event estimation; after a diffuse bounce, weighted by
 * multiple importance sampling against the light sample), the max_depth cap
 * and emitter materials (which end the path), the light sample of
 * next-event estimation at a diffuse vertex, then BSDF sampling, the
 * throughput and Russian roulette. The path state is read once and written
 * once. The light sample's shadow ray is traced here (on CPUs that trace on
 * the device) or goes to intersect_shadow with its would-be contribution
 * (WP_SHADOW_STAGE, interface/stages.h), which then adds it after the
 * emission, as the megakernel does, and finishes a path that ends here.
 * SPPM's camera pass (-DWP_SPPM): the first non-specular vertex is the
 * pixel's visible point (vertex_is_visible_point), stored for the photon pass (the pixel's first one also
 * sets its radius from the distance the path travelled to it,
 * sppm_first_radius); the path bounces on from it
 * only where an emission it may see there still counts
 * (camera_pass_bounces_from_visible_point), and the hit after it ends the
 * path once its emission counted. */
#ifndef WP_DEVICE_SHADE_HITS_H
#define WP_DEVICE_SHADE_HITS_H

#include "device/guards.h"
#include "device/lanes.h"
#include "device/parameters.h"
#include "device/path_queues.h"
#include "device/path_vertex.h"
#include "device/scene_hits.h"
#include "device/sppm_pixels.h"
#include "device/surface.h"
#include "shared/sppm.h"

/* Where each shaded path goes next: the queues of a shading kernel's
 * declaration, WP_PUSHES(SHADOW, RAY, FREE). */
typedef struct {
    lane_int casts_shadow; /* SHADOW: traced by intersect_shadow, or only counted */
    lane_int continues;    /* RAY */
    lane_int ends;         /* FREE */
} ShadedPaths;

/* The hits intersect, or the host (WP_HOST_TRACED), wrote into the path state. */
WP_FN Hit hits_in_path_state(__global const float *restrict state_hit_t, __global const uint *restrict state_hit_shape,
                             Lanes lanes) {
    Hit hit;
    hit.t = PATH_READ(hit_t, lanes);
    hit.shape = PATH_READ(hit_shape, lanes);
    return hit;
}

/* Shades the lanes' paths where their rays ended, `traced` (a miss: shape WP_NO_HIT). */
WP_FN ShadedPaths shade_hits(WP_STAGE_PARAMS, Lanes lanes, Hit traced) {
    lane_uint shape = traced.shape;
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
#ifdef WP_HAS_REFRACTION
    real eta_scale = PATH_READ(eta_scale, lanes);
#else
    real eta_scale = REAL(1.0);
#endif
    Vertex v = vertex_at(WP_SCENE_ARGS, shape, origin, d, traced.t);
    lane_int missed = lanes.active && shape == WP_NO_HIT, hit = lanes.active && !missed;

    lane_uint dropped = 0u;
    vec3 radiance = add_radiance_seen(WP_SCENE_ARGS, PATH_READ(radiance, lanes), missed, hit, shape, origin, d, v,
                                      after_specular, bsdf_pdf, throughput, &dropped);
    count_nonfinite(slot_nonfinite, WP_COUNTER_NONFINITE_EMISSION, lanes, dropped);
    lane_int scatters = hit && !vertex_ends_path(v, bounce, scene->max_depth);
#ifdef WP_SPPM
    scatters = scatters && after_specular;                   /* the hit after the visible point ends the path */
    real travelled = PATH_READ(travelled, lanes) + traced.t; /* from the camera, through mirrors and glass */
#endif

    lane_int casts_shadow = 0;
    lane_int shadow_pending = 0; /* the light sample waits for intersect_shadow, which finishes the path */
#if defined(WP_NEE) && defined(WP_HAS_NON_SPECULAR)
    DirectLight direct;
    casts_shadow = vertex_light_sample(WP_SCENE_ARGS, scatters, v, px, s, bounce, throughput, &direct);
#ifdef WP_SHADOW_STAGE
    shadow_pending = casts_shadow;
    PATH_WRITE(shadow_origin, lanes, casts_shadow, direct.shadow.origin);
    PATH_WRITE(shadow_direction, lanes, casts_shadow, direct.shadow.direction);
    PATH_WRITE(shadow_distance, lanes, casts_shadow, direct.shadow.distance);
    PATH_WRITE(shadow_radiance, lanes, casts_shadow, direct.contribution);
#else
    lane_uint dropped_direct = 0u;
    radiance = add_light_sample(radiance, shadow_ray_reaches_light(WP_SCENE_ARGS, casts_shadow, direct.shadow),
                                direct.contribution, &dropped_direct);
    count_nonfinite(slot_nonfinite, WP_COUNTER_NONFINITE_DIRECT, lanes, dropped_direct);
#endif
#endif

    PathStep step = step_from_vertex(v, d, throughput, eta_scale, scene->seed, px, s, bounce, scene->rr_depth);
    lane_int bounces = scatters; /* BSDF sampling and roulette decide whether it goes on */
#if defined(WP_SPPM) && defined(WP_HAS_NON_SPECULAR)
    /* SPPM's camera pass: the pixel's visible point */
    lane_int visible = scatters && vertex_is_visible_point(v, step.scattered);
    Lanes pixels = pixel_lanes(px, visible, scene_pixel_count(scene));
    SPPM_WRITE(visible_point, pixels, visible, v.surface.point);
    SPPM_WRITE(visible_normal, pixels, visible, v.ns);
    SPPM_WRITE(visible_geometric_normal, pixels, visible, v.nf);
    SPPM_WRITE(visible_weight, pixels, visible, visible_point_weight(v, throughput));
    SPPM_WRITE(visible_depth, pixels, visible, bounce);
#ifdef WP_HAS_GLOSSY
    SPPM_WRITE(visible_material, pixels, visible, visible_material_word(v.surface.material, v.front));
    SPPM_WRITE(visible_wo, pixels, visible, v.wo);
#ifdef WP_HAS_TEXTURES
    SPPM_WRITE(visible_u, pixels, visible, v.surface.uv.u);
    SPPM_WRITE(visible_v, pixels, visible, v.surface.uv.v);
#endif
#endif
    /* the pixel's first visible point sets its radius (0 until then) */
    lane_int first = visible && SPPM_READ(sppm_radius, pixels) == REAL(0.0);
    real footprint = sppm_footprint(scene->sppm_pixel_spread, travelled);
    SPPM_WRITE(sppm_footprint, pixels, first, footprint);
    SPPM_WRITE(sppm_radius, pixels, first, sppm_first_radius(scene->sppm_radius, footprint));
    bounces = scatters && (!visible || camera_pass_bounces_from_visible_point(WP_USES_NEE, WP_USES_MIS));
#endif

    count_nonfinite(slot_nonfinite, WP_COUNTER_NONFINITE_SCATTER, lanes, bounces ? step.nonfinite : (lane_uint)0u);
    lane_int continues = bounces && step.continues, ends = lanes.active && !continues;
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
#ifdef WP_HAS_REFRACTION
    PATH_WRITE(eta_scale, lanes, continues, step.eta_scale);
#endif
#ifdef WP_SPPM
    PATH_WRITE(travelled, lanes, continues, travelled);
#endif
#if defined(WP_NEE) && defined(WP_SHADOW_STAGE)
    PATH_WRITE(shadow_ends_path, lanes, shadow_pending, ends ? (lane_uint)1u : (lane_uint)0u);
#endif
    PATH_WRITE(radiance, lanes, continues || shadow_pending, radiance);
    finish_paths(pass_radiance, PATH_READ(pass_item, lanes), ends && !shadow_pending, radiance);
    ShadedPaths next;
    next.casts_shadow = casts_shadow;
    next.continues = continues;
    next.ends = ends;
    return next;
}

#endif
