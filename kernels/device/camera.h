/* The scene's camera (shared/camera.h) as the kernels read it from the scene
 * header; the camera is at the origin (the scene is rebased to it). */
#ifndef WP_DEVICE_CAMERA_H
#define WP_DEVICE_CAMERA_H

#include "device/lane_memory.h"
#include "interface/scene_layout.h"
#include "shared/camera.h"
#include "shared/pixel_filter.h"
#include "shared/prelude.h"

WP_FN CameraFrame scene_camera(__global const SceneHeader *scene) {
    CameraFrame c;
    c.right = uniform_vec3(scene->camera_right);
    c.up = uniform_vec3(scene->camera_up);
    c.forward = uniform_vec3(scene->camera_forward);
    c.tan_half_fov_y = scene->tan_half_fov_y;
    c.aspect = scene->aspect;
    return c;
}

/* The camera's pixel filter, its constants as the host computed them. */
WP_FN PixelFilter scene_pixel_filter(__global const SceneHeader *scene) {
    PixelFilter f;
    f.type = scene->filter_type;
    f.radius = scene->filter_radius;
    f.scale = scene->filter_scale;
    f.erf_radius = scene->filter_erf_radius;
    return f;
}

/* The direction through the point (u, v) of pixel `pixel` (row by row from the
 * top left), in pixels from its top left corner: in [0, 1)^2 but where a filter
 * reaches into the neighbours. */
WP_FN vec3 pixel_ray_direction(__global const SceneHeader *scene, lane_uint pixel, real u, real v) {
    return pixel_direction(scene_camera(scene), TO_REAL(pixel % scene->width), TO_REAL(pixel / scene->width),
                           (real)scene->width, (real)scene->height, u, v);
}

#endif
