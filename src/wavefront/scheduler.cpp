#include "wavefront/scheduler.h"

#include <algorithm>

namespace wp {
namespace {

// One iteration of the stage loop, in which generate starts `generated` new
// paths and `traced` paths (those and the ones continuing) trace a ray: each
// stage is launched over what its queue can hold, no more (a pass's last
// iterations then cost what their few paths do): the stage that takes free
// slots over the paths it starts, every other one over the rays traced, at
// most one entry each. The queue bookkeeping around each stage leaves the
// lengths of this iteration at the end: FREE the paths ended, HIT the hits,
// SHADOW the shadow rays, RAY the paths continuing next iteration.
DeviceCounts run_iteration(Pipeline& p, std::uint32_t generated, std::uint32_t traced) {
    for (Stage stage : p.iteration()) {
        p.start_stage(stage);
        p.run(stage, declaration(stage).consumes == WP_QUEUE_FREE ? generated : traced);
        p.finish_stage(stage);
    }
    return p.read_counts();
}

}  // namespace

void run_schedule(Pipeline& pipeline, const ItemRange& items, const Progress& progress, ScheduleTotals& totals,
                  std::vector<IterationRecord>& iterations) {
    std::uint64_t finished = 0;
    for (std::uint64_t start = items.begin; start < items.end; start += pipeline.pass_capacity()) {
        auto size = static_cast<std::uint32_t>(std::min<std::uint64_t>(pipeline.pass_capacity(), items.end - start));
        pipeline.begin_pass(start, size);
        std::uint32_t continuing = 0, issued = 0, free_slots = static_cast<std::uint32_t>(pipeline.capacity());
        for (;;) {
            pipeline.set_issued(issued);
            IterationRecord r;
            r.generated = std::min(free_slots, size - issued);  // generate's rule
            r.traced = continuing + r.generated;
            DeviceCounts counts = run_iteration(pipeline, r.generated, r.traced);
            r.hits = counts[WP_QUEUE_HIT];
            r.shadow = counts[WP_QUEUE_SHADOW];  // 0 without next-event estimation
            r.continuing = counts[WP_QUEUE_RAY];
            r.finished = counts[WP_QUEUE_FREE];
            iterations.push_back(r);
            totals.extension_rays += r.traced;
            totals.shadow_rays += r.shadow;
            finished += r.finished;
            issued += r.generated;
            free_slots = r.finished;
            continuing = r.continuing;
            progress.report(double(finished) / double(items.size()));
            if (issued == size && continuing == 0) {
                NonfiniteCounts pass_nonfinite = pipeline.take_nonfinite();
                for (std::size_t i = 0; i < pass_nonfinite.size(); ++i) totals.nonfinite[i] += pass_nonfinite[i];
                break;
            }
        }
        pipeline.accumulate();
    }
}

}  // namespace wp
