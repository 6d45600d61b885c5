// The reference's SPPM (docs/architecture.md, "Photon mapping"): the
// estimator the wavefront's photon stages compute, as plain loops over the
// pixels and photons of each iteration, on the CPU threads.
#pragma once

#include <memory>

#include "core/film_renderer.h"
#include "reference/reference_renderer.h"
#include "scene/scene.h"

namespace wp {

// A FilmRenderer whose work items are whole SPPM iterations (every pixel's
// sample s is iteration s); its film carries the photons' estimate.
std::unique_ptr<FilmRenderer> make_reference_sppm_renderer(const Scene& scene, const ReferenceOptions& options);

}  // namespace wp
