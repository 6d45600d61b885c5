// Which intersector the wavefront traces with by default, per device and
// scene, from the bench's measurements (bench/results/wavefront_embree.md):
// what the `--backend auto` chooser and the wavefront's default consult.
#pragma once

#include <string>

#include "accel/embree_intersector.h"
#include "opencl/device.h"
#include "scene/scene.h"

namespace wp {

struct IntersectorChoice {
    Intersector intersector = Intersector::Bvh;
    std::string reason;  // one line, for --explain
};

IntersectorChoice default_intersector(const DeviceInfo& device, const FeatureSet& features);

// "embree" or "bvh", as --intersector names them.
std::string intersector_name(Intersector intersector);

}  // namespace wp
