// The scene as the flat device buffers of kernels/common/scene_layout.h.
#pragma once

#include <CL/opencl.hpp>
#include <cstdint>
#include <vector>

#include "scene/scene.h"

namespace wp {

namespace device_layout {
using uint = std::uint32_t;
#include "common/scene_layout.h"
}  // namespace device_layout

// Host copies of the device structs, converted from the scene's doubles once
// (the camera basis computed in double, then rounded, as the reference does).
struct SceneLayout {
    device_layout::SceneHeader header{};
    std::vector<device_layout::DeviceSphere> spheres;
    std::vector<device_layout::DevicePlane> planes;
    std::vector<device_layout::DeviceQuad> quads;
    std::vector<device_layout::DeviceMaterial> materials;
    std::vector<device_layout::DeviceLight> lights;
    std::vector<float> light_cdf;
};

SceneLayout flatten_scene(const Scene& scene);

// The buffers, in the order of WP_SCENE_PARAMS. Empty arrays get one
// zeroed element (OpenCL has no empty buffers); the counts say what is real.
struct DeviceScene {
    DeviceScene(const cl::Context& context, const SceneLayout& layout);
    std::vector<cl::Buffer> buffers;
};

}  // namespace wp
