/* Stage 1: camera rays, WP_LANES per work item (device/lanes.h). The k-th free
 * slot takes work item issued + k of the pass (work item w: pixel
 * round_pixels[w % round_pixel_count], sample w / round_pixel_count), where `issued` (counts[WP_COUNTER_WORK],
 * written by the host before the launch) is how many the pass has handed out
 * so far; no atomics. This is also path regeneration, since slots freed by
 * finished paths come back through the free queue every iteration. */
#include "device/lanes.h"
#include "device/parameters.h"
#include "device/pass_radiance.h"
#include "device/path_queues.h"
#include "device/path_vertex.h"

__kernel __attribute__((reqd_work_group_size(WP_GROUP_SIZE, 1, 1))) void generate(WP_STAGE_PARAMS) {
    STAGE_QUEUES(generate, FREE, WP_PUSHES(RAY));
    __local uint group_count, group_base; /* queue_push's scratch (atomic compaction) */
    Lanes lanes = queue_lanes(queues, counts, capacity, stage_consumes);
    uint issued = counts[WP_COUNTER_WORK];
    lane_uint k = lane_positions();
    lane_int started = lanes.active && k < pass_size - issued;
    lane_uint item = issued + k;
    PassSample work = pass_item_sample(round_pixels, round_pixel_count, pass_start, item, started);
    lane_uint px = work.pixel, s = work.sample;
    PATH_WRITE(pixel, lanes, started, px);
    PATH_WRITE(sample, lanes, started, s);
    PATH_WRITE(pass_item, lanes, started, item);
    PATH_WRITE(depth, lanes, started, (lane_uint)0u);
    PATH_WRITE(origin, lanes, started, make_vec3(REAL(0.0), REAL(0.0), REAL(0.0))); /* the camera, after loading */
    PATH_WRITE(direction, lanes, started, camera_ray_direction(scene, px, s));
    PATH_WRITE(throughput, lanes, started, make_vec3(REAL(1.0), REAL(1.0), REAL(1.0)));
    PATH_WRITE(radiance, lanes, started, make_vec3(REAL(0.0), REAL(0.0), REAL(0.0)));
#ifdef WP_HAS_SPECULAR
    PATH_WRITE(specular, lanes, started, (lane_uint)1u);
#endif
#ifdef WP_HAS_REFRACTION
    PATH_WRITE(eta_scale, lanes, started, (real)REAL(1.0));
#endif
#ifdef WP_SPPM
    PATH_WRITE(travelled, lanes, started, (real)REAL(0.0));
#endif
    STAGE_PUSH(RAY, lanes, started);
}
