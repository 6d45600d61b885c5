#include "wavefront/scheduler.h"

#include <algorithm>

namespace wp {
namespace {

// One iteration of the stage loop. Pipeline::finish_stage readies the queues
// each stage filled, so at the end the lengths are this iteration's: FREE
// the paths ended, HIT the hits, SHADOW the shadow rays, SCATTER the paths
// scatter sampled, RAY the paths continuing next iteration.
DeviceCounts run_iteration(Pipeline& p, bool nee) {
    std::vector<Stage> stages{Stage::Generate, Stage::Intersect, Stage::ShadeDirect, Stage::IntersectShadow,
                              Stage::Scatter};
    for (Stage stage : stages) {
        if (stage == Stage::IntersectShadow && !nee) continue;
        p.run(stage);
        p.finish_stage(stage);
    }
    return p.read_counts();
}

}  // namespace

void run_schedule(Pipeline& pipeline, const ItemRange& items, bool nee, const Progress& progress,
                  ScheduleTotals& totals, std::vector<IterationRecord>& iterations) {
    std::uint64_t finished = 0;
    for (std::uint64_t start = items.begin; start < items.end; start += pipeline.pass_capacity()) {
        auto size = static_cast<std::uint32_t>(std::min<std::uint64_t>(pipeline.pass_capacity(), items.end - start));
        pipeline.begin_pass(start, size);
        std::uint32_t continuing = 0, issued = 0, free_slots = static_cast<std::uint32_t>(pipeline.capacity());
        for (;;) {
            pipeline.set_issued(issued);
            DeviceCounts counts = run_iteration(pipeline, nee);
            std::uint32_t now_issued = std::min(issued + free_slots, size);  // generate's rule
            IterationRecord r;
            r.free_slots = free_slots;
            r.generated = now_issued - issued;
            r.traced = continuing + r.generated;
            r.hits = counts[WP_QUEUE_HIT];
            r.shadow = nee ? counts[WP_QUEUE_SHADOW] : 0;
            r.scattered = counts[WP_QUEUE_SCATTER];
            r.continuing = counts[WP_QUEUE_RAY];
            r.finished = counts[WP_QUEUE_FREE];
            iterations.push_back(r);
            totals.extension_rays += r.traced;
            totals.shadow_rays += r.shadow;
            finished += r.finished;
            issued = now_issued;
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
