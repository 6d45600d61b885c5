/* Stage 1: camera rays. Each free slot takes the next work item of the pass
 * (work item w: pixel w % pixels, sample w / pixels) until the pass is
 * issued; this is also path regeneration, since slots freed by finished
 * paths come back through the free queue every iteration. */
#include "wavefront.h"
#include "vertex.h"

__kernel __attribute__((reqd_work_group_size(WP_GROUP_SIZE, 1, 1))) void generate(WP_STAGE_PARAMS) {
    WP_STAGE_INPUT(WP_QUEUE_FREE);
    int started = 0;
    /* Reading first keeps the counter from running far past the pass once it is issued. */
    if (k != ~0u && counts[WP_COUNTER_WORK] < pass_size) {
        uint item = atomic_inc(&counts[WP_COUNTER_WORK]);
        if (item < pass_size) {
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
            started = 1;
        }
    }
    queue_push(queues, counts, capacity, WP_QUEUE_RAY, started, slot, &group_count, &group_base);
}
