/* Stage 1: camera rays. The k-th free slot takes work item issued + k of
 * the pass (work item w: pixel w % pixels, sample w / pixels), where `issued`
 * (counts[WP_COUNTER_WORK], written by the host before the launch) is how
 * many the pass has handed out so far; no atomics. This is also path
 * regeneration, since slots freed by finished paths come back through the
 * free queue every iteration. */
#include "wavefront.h"
#include "vertex.h"

__kernel __attribute__((reqd_work_group_size(WP_GROUP_SIZE, 1, 1))) void generate(WP_STAGE_PARAMS) {
    WP_STAGE_INPUT(WP_QUEUE_FREE);
    uint issued = counts[WP_COUNTER_WORK];
    int started = k != ~0u && k < pass_size - issued;
    if (started) {
        uint item = issued + k;
        ulong work = pass_start + item;
        uint pixel_count = scene->width * scene->height;
        uint px = (uint)(work % pixel_count);
        uint s = (uint)(work / pixel_count);
        vec3 direction = camera_ray_direction(scene, px, s);
        pixel[slot] = px;
        sample[slot] = s;
        pass_item[slot] = item;
        depth[slot] = 0u;
        STORE_XYZ(origin, slot, make_vec3(REAL(0.0), REAL(0.0), REAL(0.0))); /* the camera, after loading */
        STORE_XYZ(direction, slot, direction);
        STORE_RGB(throughput, slot, make_vec3(REAL(1.0), REAL(1.0), REAL(1.0)));
        STORE_RGB(radiance, slot, make_vec3(REAL(0.0), REAL(0.0), REAL(0.0)));
#ifdef WP_HAS_SPECULAR
        specular[slot] = 1u;
#endif
    }
    queue_push(queues, counts, capacity, WP_QUEUE_RAY, started, slot, &group_count, &group_base);
}
