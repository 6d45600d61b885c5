/* SPPM's photon pass, stage 3: everything a photon does at its hit,
 * WP_LANES photons per work item, reading the hit once (as shade.cl does for
 * camera paths). First the deposit: a photon that lands on a non-specular
 * surface adds to every visible point within reach, which evaluates its
 * material's f for it (visible_point_bsdf, shared/sppm.h), the visible
 * points of its cell's bucket of the grid (shared/photon_grid.h, built by
 * photon_grid.cl), each lane looping over its own bucket until the longest
 * is done; a pixel's photon count and flux take atomic integer adds
 * (device/sppm_pixels.h), so what it gathers is exact and the same in any
 * order. Then the scatter: BSDF sampling with the shared materials, as flux
 * (WP_TRANSPORT_IMPORTANCE, with the adjoint correction for shading normals:
 * photon_bsdf_sample), its throughput and Russian roulette as camera paths
 * play it. Photons that hit an emitter or have scattered as often as
 * max_depth lets any visible point take them end, as do those the sample or
 * the roulette ends. */
#include "device/guards.h"
#include "device/lanes.h"
#include "device/parameters.h"
#include "device/path_queues.h"
#include "device/photon_vertex.h"
#include "device/sppm_pixels.h"
#include "device/surface.h"

__kernel __attribute__((reqd_work_group_size(WP_GROUP_SIZE, 1, 1))) void shade_photons(WP_STAGE_PARAMS) {
    STAGE_QUEUES(shade_photons, PHOTON_HIT, WP_PUSHES(PHOTON_RAY, PHOTON_FREE));
    __local uint group_count, group_base; /* queue_push's scratch (atomic compaction) */
    Lanes lanes = queue_lanes(queues, counts, capacity, stage_consumes);
#ifdef WP_SPPM
    vec3 d = PATH_READ(direction, lanes), throughput = PATH_READ(throughput, lanes);
    Vertex v =
        vertex_at(WP_SCENE_ARGS, PATH_READ(hit_shape, lanes), PATH_READ(origin, lanes), d, PATH_READ(hit_t, lanes));
    lane_uint photon = PATH_READ(photon, lanes), depth = PATH_READ(depth, lanes);

#ifdef WP_HAS_NON_SPECULAR
    /* the deposit */
    uint pixels = scene_pixel_count(scene), buckets = photon_grid_buckets(pixels);
    vec3 x = v.surface.point, wi = v.wo;
    vec3 power = v3_mul(PATH_READ(photon_flux, lanes), throughput);
    lane_int lands = lanes.active && vertex_is_non_specular(v);
    lane_uint bucket = lands ? grid_bucket_of(read_grid_frame(SPPM_IN(grid_frame)), x, buckets) : (lane_uint)0u;
    lane_uint first = gather(SPPM_IN(grid_starts), bucket);
    lane_uint count = lands ? gather(SPPM_IN(grid_starts), bucket + 1u) - first : (lane_uint)0u;
    for (uint e = 0u; lanes_any(e < count); ++e) {
        lane_int candidate = e < count;
        Lanes near =
            pixel_lanes(gather(SPPM_IN(grid_entries), candidate ? first + e : (lane_uint)0u), candidate, pixels);
        lane_int takes = candidate && photon_depth_counts(SPPM_READ(visible_depth, near), depth, scene->max_depth) &&
                         photon_within(SPPM_READ(visible_point, near), SPPM_READ(sppm_radius, near), x);
        vec3 nf = SPPM_READ(visible_geometric_normal, near), ns = SPPM_READ(visible_normal, near);
#ifdef WP_HAS_GLOSSY
        /* a listed pixel's visible point is this iteration's; the other lanes read material 0 */
        lane_uint material_word = candidate ? SPPM_READ(visible_material, near) : (lane_uint)0u;
        vec3 wo = SPPM_READ(visible_wo, near);
#else
        lane_uint material_word = 0u;
        vec3 wo = wi;
#endif
#if defined(WP_HAS_GLOSSY) && defined(WP_HAS_TEXTURES)
        real u = SPPM_READ(visible_u, near), v = SPPM_READ(visible_v, near);
#else
        real u = REAL(0.0), v = REAL(0.0);
#endif
        VisibleBsdf bsdf =
            visible_point_bsdf(WP_SCENE_ARGS, material_word, u, v, wo, nf, ns, SPPM_READ(visible_weight, near), wi);
        vec3 flux = photon_deposit(bsdf.throughput_f, nf, ns, bsdf.transmits, d, power, WP_USES_SHADING_NORMALS);
        atomic_increment_where(SPPM_OUT(iteration_photons), near.slot, takes);
        add_flux_where(SPPM_OUT(iteration_flux), near.slot, takes, flux);
    }
#endif

    /* the scatter */
    lane_int scatters =
        lanes.active && v.material.type != WP_MATERIAL_EMITTER && photon_may_scatter(depth, scene->max_depth);
    uint seed = scene->seed, iteration = photon_pass_iteration(scene, pass_start);
    BsdfSample scattered = photon_bsdf_sample(
        scatter_vertex(v, d, photon_bsdf_random(seed, iteration, photon, depth), WP_TRANSPORT_IMPORTANCE), v3_neg(d),
        v.nf, v.ns, WP_USES_SHADING_NORMALS);
    lane_uint new_depth = depth + 1u, dropped = 0u;
    RouletteOutcome roulette =
        russian_roulette(v3_mul(throughput, scattered.weight), REAL(1.0), new_depth >= scene->rr_depth,
                         photon_uniform(seed, iteration, photon, depth, DIM_PHOTON_ROULETTE));
    lane_int sampled = scatters && scattered.valid && roulette.survives;
    lane_int continues = sampled && throughput_is_finite(roulette.throughput, &dropped);
    count_nonfinite(slot_nonfinite, WP_COUNTER_NONFINITE_SCATTER, lanes, sampled ? dropped : (lane_uint)0u);
    lane_int ends = lanes.active && !continues;
    PATH_WRITE(origin, lanes, continues, offset_ray_origin(v.surface.point, scattered.leave_side, v.surface.error));
    PATH_WRITE(direction, lanes, continues, scattered.direction);
    PATH_WRITE(throughput, lanes, continues, roulette.throughput);
    PATH_WRITE(depth, lanes, continues, new_depth);
#else
    lane_int continues = 0, ends = 0;
#endif
    STAGE_PUSH(PHOTON_RAY, lanes, continues);
    STAGE_PUSH(PHOTON_FREE, lanes, ends);
}
