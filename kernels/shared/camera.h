/* The pinhole camera: its basis, built on the host (in double) from the
 * scene's camera, and the direction of a ray through a point of the film. */
#ifndef WP_SHARED_CAMERA_H
#define WP_SHARED_CAMERA_H

#include "shared/prelude.h"

typedef struct {
    vec3 right, up, forward; /* orthonormal; forward towards look_at, up in the plane of forward and the scene's up */
    real tan_half_fov_y;     /* tan(fov_y / 2) */
    real aspect;             /* film width / height */
} CameraFrame;

/* The camera at `position` looking at `look_at`, with `up` roughly up. */
WP_FN CameraFrame camera_frame(vec3 position, vec3 look_at, vec3 up, real tan_half_fov_y, real aspect) {
    CameraFrame c;
    c.forward = v3_normalize(v3_sub(look_at, position));
    c.right = v3_normalize(v3_cross(c.forward, up));
    c.up = v3_cross(c.right, c.forward);
    c.tan_half_fov_y = tan_half_fov_y;
    c.aspect = aspect;
    return c;
}

/* Unit direction through the film point (x, y) in [0,1]^2 (y down). */
WP_FN vec3 camera_direction(CameraFrame c, real x, real y) {
    real sx = (REAL(2.0) * x - REAL(1.0)) * c.tan_half_fov_y * c.aspect;
    real sy = (REAL(1.0) - REAL(2.0) * y) * c.tan_half_fov_y;
    return v3_normalize(v3_add_scaled(v3_add_scaled(c.forward, sx, c.right), sy, c.up));
}

/* Unit direction through the point (column + u, row + v) of a film of
 * width x height pixels: (u, v) is the pixel's jitter in [0, 1)^2, or the
 * point a pixel filter drew (shared/pixel_filter.h), which may lie outside. */
WP_FN vec3 pixel_direction(CameraFrame c, real column, real row, real width, real height, real u, real v) {
    return camera_direction(c, (column + u) / width, (row + v) / height);
}

#endif
