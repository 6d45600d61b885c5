// Which kernel code a scene needs: its FeatureSet as -D build options.
#pragma once

#include <string>

#include "scene/scene.h"

namespace wp {

// "-DWP_HAS_SPHERES -DWP_HAS_DIFFUSE ...", one option per feature in use,
// plus -DWP_HAS_NEE when the scene has lights and -DWP_FILM_DOUBLE when the
// device has fp64. Never fast-math options: the kernels must agree with the
// reference.
std::string kernel_build_options(const FeatureSet& features, bool has_lights, bool device_fp64);

// The features in use, space-separated ("spheres quads diffuse glass ..."), for --explain.
std::string describe_features(const FeatureSet& features);

}  // namespace wp
