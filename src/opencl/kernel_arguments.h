// Kernel argument indices, from the parameter lists the kernels are declared
// with (kernels/interface/kernel_parameters.h): arg::Stage::pass_start is
// pass_start's index in every stage kernel, whatever comes before it, so no
// index is counted by hand.
#pragma once

#include <CL/opencl.hpp>

#include "interface/kernel_parameters.h"

namespace wp::arg {

#define WP_ARGUMENT_INDEX(type, name) name,
struct Scene {
    enum : cl_uint { WP_SCENE_PARAMETERS(WP_ARGUMENT_INDEX, WP_ARGUMENT_INDEX) count };
};
// The path state's fields follow these, from Stage::count on.
struct Stage {
    enum : cl_uint { WP_STAGE_PARAMETERS(WP_ARGUMENT_INDEX, WP_ARGUMENT_INDEX) count };
};
// SPPM's state (kernels/interface/sppm_state.h) follows these, from Sppm::count on.
struct Sppm {
    enum : cl_uint { WP_SPPM_KERNEL_PARAMETERS(WP_ARGUMENT_INDEX, WP_ARGUMENT_INDEX) count };
};
struct Megakernel {
    enum : cl_uint { WP_MEGAKERNEL_PARAMETERS(WP_ARGUMENT_INDEX, WP_ARGUMENT_INDEX) count };
};
struct IntersectBound {
    enum : cl_uint { WP_INTERSECT_BOUND_PARAMETERS(WP_ARGUMENT_INDEX, WP_ARGUMENT_INDEX) count };
};
struct Accumulate {
    enum : cl_uint { WP_ACCUMULATE_PARAMETERS(WP_ARGUMENT_INDEX, WP_ARGUMENT_INDEX) count };
};
struct CompactCount {
    enum : cl_uint { WP_COMPACT_COUNT_PARAMETERS(WP_ARGUMENT_INDEX, WP_ARGUMENT_INDEX) count };
};
struct CompactScan {
    enum : cl_uint { WP_COMPACT_SCAN_PARAMETERS(WP_ARGUMENT_INDEX, WP_ARGUMENT_INDEX) count };
};
struct CompactWrite {
    enum : cl_uint { WP_COMPACT_WRITE_PARAMETERS(WP_ARGUMENT_INDEX, WP_ARGUMENT_INDEX) count };
};
struct CountDepths {
    enum : cl_uint { WP_COUNT_DEPTHS_PARAMETERS(WP_ARGUMENT_INDEX, WP_ARGUMENT_INDEX) count };
};
#undef WP_ARGUMENT_INDEX

// The kernels that trace take the scene's buffers first, so DeviceScene binds
// them at the same indices in all of them.
constexpr cl_uint kSceneArgumentCount = Scene::count;
static_assert(cl_uint(Stage::environment_map) + 1 == kSceneArgumentCount &&
              cl_uint(Megakernel::environment_map) + 1 == kSceneArgumentCount &&
              cl_uint(IntersectBound::environment_map) + 1 == kSceneArgumentCount);

}  // namespace wp::arg
