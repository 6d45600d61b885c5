#include "wavefront/intersector_choice.h"

namespace wp {

IntersectorChoice default_intersector(const DeviceInfo& device, const FeatureSet& features) {
    if (device.type != "CPU")
        return {Intersector::Bvh, "the OpenCL BVH: Embree traces on the host, which only a CPU device shares"};
    if (features.sppm)
        return {Intersector::Bvh, "the OpenCL BVH: the sppm integrator's photon stages trace on the device"};
    if (!features.meshes)
        return {Intersector::Bvh,
                "the OpenCL BVH: without meshes the kernels test every shape in turn, faster than a trip to the host "
                "(bench/results/wavefront_embree.md)"};
    return {Intersector::Embree,
            "Embree on the host: faster on meshes on a CPU device (bench/results/wavefront_embree.md)"};
}

std::string intersector_name(Intersector intersector) { return intersector == Intersector::Embree ? "embree" : "bvh"; }

}  // namespace wp
