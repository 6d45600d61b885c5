/* The roofline of the tracing stages (wavepath render --profile): camera rays
 * traced with closest_hit and nothing else, no queue and no path state read
 * or written, so that its rays/s is what the ray-primitive tests alone reach
 * on this device and each stage's rays/s reads as a fraction of it. WP_LANES
 * rays per work item, as in intersect.cl. Ray r goes through the centre of
 * pixel r % (width * height); each work item writes the sum of its rays' hit
 * distances, so that the tests are not optimised away (and can be checked). */
#include "trace.h"

/* A real's lanes one by one (with one lane, the real itself). */
typedef union {
    real value;
    float lane[WP_LANES];
} RealLanes;

__kernel __attribute__((reqd_work_group_size(WP_GROUP_SIZE, 1, 1))) void intersect_bound(WP_SCENE_PARAMS, uint count,
                                                                                         __global float *sums) {
    uint width = scene->width, height = scene->height;
    RealLanes film_x, film_y, hit_t;
    int counted[WP_LANES]; /* rays past `count` add nothing */
    for (uint i = 0u; i < WP_LANES; ++i) {
        uint ray = get_global_id(0) * WP_LANES + i, pixel = ray % (width * height);
        counted[i] = ray < count;
        film_x.lane[i] = ((float)(pixel % width) + 0.5f) / (float)width;
        film_y.lane[i] = ((float)(pixel / width) + 0.5f) / (float)height;
    }
    /* camera_direction (sampling.h) at the film point; the camera is at the origin. */
    real sx = (REAL(2.0) * film_x.value - REAL(1.0)) * scene->tan_half_fov_y * scene->aspect;
    real sy = (REAL(1.0) - REAL(2.0) * film_y.value) * scene->tan_half_fov_y;
    vec3 forward = vec3_at(scene->camera_forward), right = vec3_at(scene->camera_right), up = vec3_at(scene->camera_up);
    vec3 direction = v3_normalize(v3_add_scaled(v3_add_scaled(forward, sx, right), sy, up));
    Hit hit = closest_hit(WP_SCENE_ARGS, make_vec3(REAL(0.0), REAL(0.0), REAL(0.0)), direction);
    hit_t.value = hit.shape != WP_NO_HIT ? hit.t : (real)REAL(0.0);
    float sum = 0.0f;
    for (uint i = 0u; i < WP_LANES; ++i) sum += counted[i] ? hit_t.lane[i] : 0.0f;
    sums[get_global_id(0)] = sum;
}
