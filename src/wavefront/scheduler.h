// The host loop that drives the stage kernels over passes of work items.
#pragma once

#include <cstdint>
#include <vector>

#include "core/film.h"
#include "core/render.h"
#include "wavefront/pipeline.h"
#include "wavefront/wavefront_renderer.h"

namespace wp {

struct ScheduleTotals {
    std::uint64_t extension_rays = 0;
    std::uint64_t shadow_rays = 0;
    std::uint64_t photons = 0;          // SPPM: photons emitted
    std::uint64_t photon_rays = 0;      // their rays
    std::uint64_t photon_deposits = 0;  // photons added to visible points
    NonfiniteCounts nonfinite{};        // per NonfiniteStage
};

// Renders `items` (w: pixel w % pixels, sample w / pixels) in passes of at
// most pipeline.pass_capacity(): per pass, iterations of the stages
// (pipeline.iteration()) until every item is issued and every path has
// ended, then accumulate. Adds to `totals` and appends one record per
// iteration.
void run_schedule(Pipeline& pipeline, const ItemRange& items, const Progress& progress, ScheduleTotals& totals,
                  std::vector<IterationRecord>& iterations);

// SPPM's iteration `iteration` (docs/architecture.md, "Photon mapping"): the
// camera pass of its work items (run_schedule: every pixel's sample
// `iteration`, its emission and direct light into the film, its visible
// point), the grid over the visible points, the photon pass (iterations of
// the photon stages until all the iteration's photons have ended), then
// every pixel's update. Adds to `totals` and appends one record per
// iteration of either loop.
void run_sppm_iteration(Pipeline& pipeline, std::uint32_t iteration, const Progress& progress, ScheduleTotals& totals,
                        std::vector<IterationRecord>& iterations);

}  // namespace wp
