#include "wavefront/scheduler.h"

#include <algorithm>

namespace wp {
namespace {

// One iteration of the stage loop. Each queue's length is cleared just
// before the first stage that pushes to it, and after its consumer has run,
// so at the end the lengths are this iteration's: FREE the paths ended, HIT
// the hits, SHADOW the shadow rays, RAY the paths continuing next iteration.
DeviceCounts run_iteration(Pipeline& p, bool has_lights) {
    p.run(Stage::Generate);
    p.clear_counts(WP_QUEUE_FREE, 2);  // FREE consumed; HIT filled next
    p.run(Stage::Intersect);
    p.clear_counts(WP_QUEUE_RAY, 3);  // RAY consumed; SHADOW and SCATTER filled next
    p.run(Stage::ShadeDirect);
    if (has_lights) p.run(Stage::IntersectShadow);
    p.run(Stage::Scatter);
    return p.read_counts();
}

}  // namespace

ScheduleTotals run_schedule(Pipeline& pipeline, std::uint64_t total, bool has_lights, const ProgressFn& progress,
                            std::vector<IterationRecord>& iterations) {
    ScheduleTotals totals;
    std::uint64_t finished = 0;
    for (std::uint64_t start = 0; start < total; start += pipeline.pass_capacity()) {
        auto size = static_cast<std::uint32_t>(std::min<std::uint64_t>(pipeline.pass_capacity(), total - start));
        pipeline.begin_pass(start, size);
        std::uint32_t continuing = 0, issued = 0, free_slots = static_cast<std::uint32_t>(pipeline.capacity());
        for (;;) {
            DeviceCounts counts = run_iteration(pipeline, has_lights);
            std::uint32_t now_issued = std::min(counts[WP_COUNTER_WORK], size);
            IterationRecord r;
            r.free_slots = free_slots;
            r.generated = now_issued - issued;
            r.traced = continuing + r.generated;
            r.hits = counts[WP_QUEUE_HIT];
            r.shadow = has_lights ? counts[WP_QUEUE_SHADOW] : 0;
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
            if (progress) progress(double(finished) / double(total));
            if (issued == size && continuing == 0) {
                totals.nonfinite += counts[WP_COUNTER_NONFINITE];  // reset by begin_pass
                break;
            }
        }
        pipeline.accumulate();
    }
    return totals;
}

}  // namespace wp
