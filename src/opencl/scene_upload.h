// The scene as the flat device buffers of kernels/interface/scene_layout.h.
#pragma once

#include <CL/opencl.hpp>
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "accel/embree_intersector.h"
#include "core/shared_math.h"
#include "opencl/kernel_arguments.h"
#include "scene/scene.h"

namespace wp {

namespace device_layout {
using uint = std::uint32_t;
#include "interface/scene_layout.h"
}  // namespace device_layout

// What --explain says of the meshes and their BVH.
struct MeshSummary {
    std::size_t meshes = 0, triangles = 0, degenerate_dropped = 0, bvh_nodes = 0;
    int bvh_depth = 0;
    double layout_seconds = 0.0;  // building and flattening the tree, or laying the triangles out without one

    // "2 meshes, 69666 triangles (3 degenerate dropped); BVH of 37650 nodes, depth 24, built in 0.061 s",
    // without the BVH "2 meshes, 69666 triangles (3 degenerate dropped); no BVH (the host traces), laid out in
    // 0.004 s", or "".
    std::string describe() const;
};

// Host copies of the device structs, converted from the scene's doubles once
// (the camera basis computed in double, then rounded, as the reference does).
struct SceneLayout {
    device_layout::SceneHeader header{};
    std::vector<device_layout::DeviceSphere> spheres;
    std::vector<device_layout::DevicePlane> planes;
    std::vector<device_layout::DeviceQuad> quads;
    std::vector<SharedMath<float>::MeshTriangle> triangles;            // in the BVH's leaf order
    std::vector<SharedMath<float>::TriangleNormals> triangle_normals;  // parallel, if FeatureSet::shading_normals
    std::vector<SharedMath<float>::BvhNode> bvh_nodes;                 // none where the host traces
    std::vector<device_layout::DeviceMaterial> materials;
    std::vector<device_layout::DeviceLight> lights;
    std::vector<float> light_cdf;
    std::vector<SharedMath<float>::MeshTriangle> light_triangles;  // scene/mesh_lights.h
    std::vector<float> light_triangle_cdf;
    std::vector<float> roughplastic_transmittance;                   // scene/plastic_constants.h
    std::vector<device_layout::MaterialTextures> material_textures;  // parallel to materials
    std::vector<SharedMath<float>::TextureDescriptor> textures;
    std::vector<float> texels;
    std::vector<SharedMath<float>::TriangleUVs> triangle_uvs;  // parallel to triangles, if FeatureSet::triangle_uvs()
    std::vector<float> environment;                            // scene/environment_layout.h
    MeshSummary meshes;
    std::string textures_summary;  // describe_textures
};

// `intersector`: what traces the kernels' rays. Intersector::Embree (the
// host traces: wavefront/host_trace.h) builds no BVH: the kernels only shade
// the hits, so the triangles are in the scene's order (accel/bvh_layout.h,
// mesh_layout) and bvh_nodes is empty.
SceneLayout flatten_scene(const Scene& scene, Intersector intersector = Intersector::Bvh);

// What --explain says of the textures: "2 textures (1 bitmap, 1
// checkerboard), 65536 texels, 768 KiB of device memory", or "".
std::string describe_textures(const Scene& scene, std::size_t device_bytes);

// The scene's buffers on the device. Empty arrays get one zeroed element
// (OpenCL has no empty buffers); the counts say what is real.
class DeviceScene {
 public:
    // `host_triangles`: where the host traces, the mesh triangles its
    // intersector holds (the bytes of layout.triangles, which is then
    // empty), which the triangle buffer uses in place (CL_MEM_USE_HOST_PTR:
    // on a CPU device, PoCL makes no copy); they must outlive this.
    DeviceScene(const cl::Context& context, const SceneLayout& layout, std::span<const std::byte> host_triangles = {});
    // Sets a kernel's scene arguments (WP_SCENE_PARAMETERS, first in every kernel that traces).
    void bind(cl::Kernel& kernel) const;
    // The scene header alone (kernels that take it without the rest).
    const cl::Buffer& header() const { return buffers_[arg::Scene::scene]; }
    const cl::Buffer& triangles() const { return buffers_[arg::Scene::triangles]; }
    const MeshSummary& meshes() const { return meshes_; }
    const std::string& textures() const { return textures_; }

 private:
    std::array<cl::Buffer, arg::Scene::count> buffers_;
    MeshSummary meshes_;
    std::string textures_;
};

}  // namespace wp
