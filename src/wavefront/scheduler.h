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
    NonfiniteCounts nonfinite{};  // per NonfiniteStage
};

// Renders `items` (w: pixel w % pixels, sample w / pixels) in passes of at
// most pipeline.pass_capacity(): per pass, iterations of the stages
// (pipeline.iteration()) until every item is issued and every path has
// ended, then accumulate. Adds to `totals` and appends one record per
// iteration.
void run_schedule(Pipeline& pipeline, const ItemRange& items, const Progress& progress, ScheduleTotals& totals,
                  std::vector<IterationRecord>& iterations);

}  // namespace wp
