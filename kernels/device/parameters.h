/* Kernel parameter lists from their declarations (interface/kernel_parameters.h
 * and, for the stage kernels, the path state, interface/path_state.h):
 * WP_PARAMETERS(list) is a kernel's or function's parameter list, and
 * WP_SCENE_PARAMS / WP_SCENE_ARGS pass the scene's buffers on to functions,
 * WP_STAGE_PARAMS / WP_STAGE_ARGS a stage kernel's parameters. */
#ifndef WP_DEVICE_PARAMETERS_H
#define WP_DEVICE_PARAMETERS_H

#include "device/features.h"
#include "interface/kernel_parameters.h"
#include "interface/path_state.h"
#include "interface/scene_layout.h"
#include "interface/sppm_state.h"
#include "shared/bvh.h"
#include "shared/environment_map.h"
#include "shared/texture.h"
#include "shared/triangle.h"

#define WP_PARAMETER_FIRST(type, name) type name
#define WP_PARAMETER_NEXT(type, name) , type name
#define WP_ARGUMENT_FIRST(type, name) name
#define WP_ARGUMENT_NEXT(type, name) , name
#define WP_PARAMETERS(list) list(WP_PARAMETER_FIRST, WP_PARAMETER_NEXT)

#define WP_SCENE_PARAMS WP_PARAMETERS(WP_SCENE_PARAMETERS)
#define WP_SCENE_ARGS WP_SCENE_PARAMETERS(WP_ARGUMENT_FIRST, WP_ARGUMENT_NEXT)

/* A vec3 path state field's element type: its buffer holds three planes of
 * `capacity` floats (x, y, z). A struct of its own, so that slot_read and
 * slot_write (device/lanes.h) can be overloaded on it. */
typedef struct {
    float x_plane_start;
} PlanarVec3;

/* The device type of a path state field of each X-macro type. */
#define WP_STATE_ELEMENT_uint uint
#define WP_STATE_ELEMENT_float float
#define WP_STATE_ELEMENT_vec3 PlanarVec3

/* ", __global float* restrict state_hit_t, ..." for the fields of the
 * compiled features, after WP_STAGE_PARAMETERS in every stage kernel, so the host
 * binds the same buffers at the same positions for every stage. */
#define WP_PATH_STATE_PARAM(type, name, feature, writers, readers) \
    WP_IF_##feature(, __global WP_STATE_ELEMENT_##type *restrict state_##name)
/* SPPM's state (interface/sppm_state.h) after the path state, only with the
 * sppm integrator and the entry's feature; in the grid and update kernels
 * after their own. */
#define WP_SPPM_STATE_PARAM(type, name, size, feature, writers, readers) \
    WP_IF_SPPM(WP_IF_##feature(, __global WP_STATE_ELEMENT_##type *restrict state_##name))
#define WP_STAGE_PARAMS \
    WP_PARAMETERS(WP_STAGE_PARAMETERS) WP_PATH_STATE(WP_PATH_STATE_PARAM) WP_SPPM_STATE(WP_SPPM_STATE_PARAM)
#define WP_PATH_STATE_ARG(type, name, feature, writers, readers) WP_IF_##feature(, state_##name)
#define WP_SPPM_STATE_ARG(type, name, size, feature, writers, readers) WP_IF_SPPM(WP_IF_##feature(, state_##name))
#define WP_STAGE_ARGS                                        \
    WP_STAGE_PARAMETERS(WP_ARGUMENT_FIRST, WP_ARGUMENT_NEXT) \
    WP_PATH_STATE(WP_PATH_STATE_ARG) WP_SPPM_STATE(WP_SPPM_STATE_ARG)
#define WP_SPPM_PARAMS WP_PARAMETERS(WP_SPPM_KERNEL_PARAMETERS) WP_SPPM_STATE(WP_SPPM_STATE_PARAM)

#endif
