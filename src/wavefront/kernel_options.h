// Which kernel code a scene needs: its FeatureSet as -D build options.
#pragma once

#include <string>

#include "scene/scene.h"

namespace wp {

// Whether next-event estimation runs (and its shadow-ray state exists): the
// scene has lights and render.nee is on.
bool uses_nee(const Scene& scene);

// "-DWP_HAS_SPHERES -DWP_HAS_DIFFUSE ...", one option per feature in use,
// plus -DWP_HAS_NEE when `nee` (see uses_nee), -DWP_NEE_OFF when the render
// settings turn NEE off (emission then counts at every hit),
// -DWP_UNIFORM_HEMISPHERE for uniform diffuse sampling and -DWP_FILM_DOUBLE
// when the device has fp64. Never fast-math options: the kernels must agree
// with the reference.
std::string kernel_build_options(const FeatureSet& features, bool nee, bool device_fp64,
                                 const RenderSettings& sampling = {});

// The features in use, space-separated ("spheres quads diffuse glass ..."), for --explain.
std::string describe_features(const FeatureSet& features);

}  // namespace wp
