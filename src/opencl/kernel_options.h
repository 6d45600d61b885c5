// Which kernel code a scene needs: its FeatureSet as -D build options.
#pragma once

#include <cstddef>
#include <string>

#include "scene/scene.h"

namespace wp {

// "-DWP_HAS_SPHERES -DWP_HAS_DIFFUSE ...", one option per shape, material
// and light kind in use, -DWP_NEE when next-event estimation runs (without
// it emission counts at every hit), -DWP_UNIFORM_HEMISPHERE for uniform
// diffuse sampling and -DWP_INDEPENDENT_SAMPLER for render.sampler
// "independent". Never fast-math options: the kernels must agree with the
// reference.
std::string kernel_build_options(const FeatureSet& features, const RenderSettings& render);

// Shapes and lights of each kind per type a kernel unrolls its loops over.
inline constexpr std::size_t kMaxUnrolledCount = 32;

// " -DWP_SPHERE_COUNT=4 -DWP_QUAD_COUNT=7 -DWP_LIGHT_COUNT=1 ...": the scene's
// counts of each kind, as compile-time constants, for the kinds with at most
// kMaxUnrolledCount (larger ones are read at run time). Constant counts let
// the loops over shapes and lights unroll into straight-line vector code
// (kernels/shared/prelude.h, "Lanes").
std::string shape_count_options(const Scene& scene);

// The build options of a renderer's program, for `kernel_features` (normally
// scene.features()): kernel_build_options, the film's (film_build_options),
// shape_count_options, the backend's own `backend_options` (each with a
// space before it) and " -DWP_LANES=<lanes>".
std::string program_build_options(const Scene& scene, const FeatureSet& kernel_features, bool film_squares,
                                  const std::string& backend_options, unsigned lanes);

// The features in use, space-separated ("spheres quads diffuse glass ..."), for --explain.
std::string describe_features(const FeatureSet& features);

}  // namespace wp
