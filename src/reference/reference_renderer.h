// The scalar reference renderer: plain C++ on the CPU, float or double,
// computing exactly the estimator the OpenCL kernels compute
// (docs/architecture.md, "Conventions").
// It validates the wavefront backend, path for path.
#pragma once

#include <glm/vec3.hpp>
#include <memory>

#include "accel/embree_intersector.h"
#include "core/film_renderer.h"
#include "core/render.h"
#include "scene/scene.h"

namespace wp {

struct ReferenceOptions {
    int threads = 0;  // 0 = hardware concurrency
    bool double_precision = false;
    bool film_squares = false;  // the film keeps sums of squares (per-pixel variance)
    // The BVH is the OpenCL backends' (the reference retraces their paths);
    // Embree is float only.
    Intersector intersector = Intersector::Bvh;
};

// The faster intersector the precision allows, which `wavepath render
// --backend reference` picks by default (bench/results/embree_intersector.md,
// section f): Embree in float, the BVH in double.
Intersector fastest_reference_intersector(bool double_precision);

// Renders the scene with its own render settings and camera resolution. The
// image is bit-identical for any thread count. Throws std::invalid_argument
// for a resolution or spp below 1, a negative max_depth or Embree in double.
RenderResult render_reference(const Scene& scene, const ReferenceOptions& options, const Progress& progress = {});

// The reference as a FilmRenderer: its film sums each sample as the float
// (or double) it computed. Throws as render_reference does.
std::unique_ptr<FilmRenderer> make_reference_renderer(const Scene& scene, const ReferenceOptions& options);

// Radiance of one camera sample, exactly as render_reference computes it
// (its non-finite values dropped); Real is float or double.
template <class Real>
glm::dvec3 trace_reference_sample(const Scene& scene, int px, int py, int sample);

extern template glm::dvec3 trace_reference_sample<float>(const Scene&, int, int, int);
extern template glm::dvec3 trace_reference_sample<double>(const Scene&, int, int, int);

}  // namespace wp
