/* SPPM's photon pass, stage 1 (interface/stages.h): photons leave the
 * lights, WP_LANES per work item (device/lanes.h). The k-th free slot takes
 * photon issued + k of the iteration, where `issued` (counts[WP_COUNTER_WORK],
 * written by the host) is how many the pass has handed out so far, as
 * generate hands out camera samples; a photon's random numbers are keyed by
 * the photon and the iteration alone. */
#include "device/lanes.h"
#include "device/parameters.h"
#include "device/path_queues.h"
#include "device/photon_vertex.h"

__kernel __attribute__((reqd_work_group_size(WP_GROUP_SIZE, 1, 1))) void emit_photons(WP_STAGE_PARAMS) {
    STAGE_QUEUES(emit_photons, PHOTON_FREE, WP_PUSHES(PHOTON_RAY));
    __local uint group_count, group_base; /* queue_push's scratch (atomic compaction) */
    Lanes lanes = queue_lanes(queues, counts, capacity, stage_consumes);
#ifdef WP_SPPM
    uint issued = counts[WP_COUNTER_WORK];
    lane_uint k = lane_positions();
    lane_int started = lanes.active && k < pass_size - issued;
    lane_uint photon = issued + k;
    EmittedPhoton emitted = emit_scene_photon(WP_SCENE_ARGS, photon_pass_iteration(scene, pass_start), photon);
    PATH_WRITE(photon, lanes, started, photon);
    PATH_WRITE(depth, lanes, started, (lane_uint)0u);
    PATH_WRITE(origin, lanes, started, emitted.origin);
    PATH_WRITE(direction, lanes, started, emitted.direction);
    PATH_WRITE(photon_flux, lanes, started, emitted.flux);
    PATH_WRITE(throughput, lanes, started, make_vec3(REAL(1.0), REAL(1.0), REAL(1.0)));
#else
    lane_int started = 0;
#endif
    STAGE_PUSH(PHOTON_RAY, lanes, started);
}
