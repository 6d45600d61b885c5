// The scene as the flat device buffers of kernels/interface/scene_layout.h.
#pragma once

#include <CL/opencl.hpp>
#include <array>
#include <cstdint>
#include <vector>

#include "core/shared_math.h"
#include "opencl/kernel_arguments.h"
#include "scene/scene.h"

namespace wp {

namespace device_layout {
using uint = std::uint32_t;
#include "interface/scene_layout.h"
}  // namespace device_layout

// Host copies of the device structs, converted from the scene's doubles once
// (the camera basis computed in double, then rounded, as the reference does).
struct SceneLayout {
    device_layout::SceneHeader header{};
    std::vector<device_layout::DeviceSphere> spheres;
    std::vector<device_layout::DevicePlane> planes;
    std::vector<device_layout::DeviceQuad> quads;
    std::vector<SharedMath<float>::MeshTriangle> triangles;  // in the BVH's leaf order
    std::vector<SharedMath<float>::BvhNode> bvh_nodes;
    std::vector<device_layout::DeviceMaterial> materials;
    std::vector<device_layout::DeviceLight> lights;
    std::vector<float> light_cdf;
    std::vector<SharedMath<float>::MeshTriangle> light_triangles;  // scene/mesh_lights.h
    std::vector<float> light_triangle_cdf;
};

SceneLayout flatten_scene(const Scene& scene);

// The scene's buffers on the device. Empty arrays get one zeroed element
// (OpenCL has no empty buffers); the counts say what is real.
class DeviceScene {
 public:
    DeviceScene(const cl::Context& context, const SceneLayout& layout);
    // Sets a kernel's scene arguments (WP_SCENE_PARAMETERS, first in every kernel that traces).
    void bind(cl::Kernel& kernel) const;

 private:
    std::array<cl::Buffer, arg::Scene::count> buffers_;
};

}  // namespace wp
