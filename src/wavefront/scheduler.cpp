#include "wavefront/scheduler.h"

#include <algorithm>
#include <functional>

namespace wp {
namespace {

// One iteration of the stage loop, in which generate starts `generated` new
// paths and `traced` paths (those and the ones continuing) trace a ray: each
// stage is launched over what its queue can hold, no more (a pass's last
// iterations then cost what their few paths do): the stage that takes free
// slots over the paths it starts, every other one over the rays traced, at
// most one entry each. The queue bookkeeping around each stage leaves the
// lengths of this iteration at the end: FREE the paths ended, HIT the rays traced
// (none where intersect_and_shade shades them at once),
// SHADOW the shadow rays, RAY the paths continuing next iteration.
DeviceCounts run_iteration(Pipeline& p, const std::vector<Stage>& stages, std::uint32_t generated,
                           std::uint32_t traced) {
    for (Stage stage : stages) {
        p.start_stage(stage);
        const std::uint32_t consumes = declaration(stage).consumes;
        const std::uint32_t entries =
            consumes == WP_QUEUE_FREE || consumes == WP_QUEUE_PHOTON_FREE ? generated : traced;
        p.run(stage, entries);
        p.finish_stage(stage, entries);
    }
    return p.read_counts();
}

// The queues a loop's iteration leaves its lengths in (kernels/interface/queues.h).
struct LoopQueues {
    std::uint32_t free, ray, hit;
};
constexpr LoopQueues kCameraQueues{WP_QUEUE_FREE, WP_QUEUE_RAY, WP_QUEUE_HIT};
constexpr LoopQueues kPhotonQueues{WP_QUEUE_PHOTON_FREE, WP_QUEUE_PHOTON_RAY, WP_QUEUE_PHOTON_HIT};

// Iterations of `stages` until the pass's `size` work items are issued and
// every one has ended (the pipeline's pass begun); returns the items ended.
void drain_pass(Pipeline& pipeline, StageLoop loop, std::uint32_t size, const std::function<void(std::uint32_t)>& ended,
                ScheduleTotals& totals, std::vector<IterationRecord>& iterations) {
    const bool photons = loop == StageLoop::PHOTON;
    const std::vector<Stage>& stages = photons ? pipeline.photon_iteration() : pipeline.iteration();
    const LoopQueues& q = photons ? kPhotonQueues : kCameraQueues;
    std::uint32_t continuing = 0, issued = 0, free_slots = static_cast<std::uint32_t>(pipeline.capacity());
    for (;;) {
        pipeline.set_issued(issued);
        IterationRecord r;
        r.loop = loop;
        r.generated = std::min(free_slots, size - issued);  // generate's (emit_photons') rule
        r.traced = continuing + r.generated;
        DeviceCounts counts = run_iteration(pipeline, stages, r.generated, r.traced);
        r.hits = counts[q.hit];
        r.shadow = photons ? 0 : counts[WP_QUEUE_SHADOW];  // 0 without next-event estimation
        r.continuing = counts[q.ray];
        r.finished = counts[q.free];
        iterations.push_back(r);
        (photons ? totals.photon_rays : totals.extension_rays) += r.traced;
        totals.shadow_rays += r.shadow;
        if (photons) totals.photons += r.generated;
        issued += r.generated;
        free_slots = r.finished;
        continuing = r.continuing;
        ended(r.finished);
        if (issued == size && continuing == 0) {
            NonfiniteCounts pass_nonfinite = pipeline.take_nonfinite();
            for (std::size_t i = 0; i < pass_nonfinite.size(); ++i) totals.nonfinite[i] += pass_nonfinite[i];
            return;
        }
    }
}

}  // namespace

void run_schedule(Pipeline& pipeline, const ItemRange& items, const Progress& progress, ScheduleTotals& totals,
                  std::vector<IterationRecord>& iterations) {
    std::uint64_t finished = 0;
    for (std::uint64_t start = items.begin; start < items.end; start += pipeline.pass_capacity()) {
        auto size = static_cast<std::uint32_t>(std::min<std::uint64_t>(pipeline.pass_capacity(), items.end - start));
        pipeline.begin_pass(start, size);
        drain_pass(
            pipeline, StageLoop::CAMERA, size,
            [&](std::uint32_t ended) {
                finished += ended;
                progress.report(double(finished) / double(items.size()));
            },
            totals, iterations);
        pipeline.accumulate();
    }
}

void run_sppm_iteration(Pipeline& pipeline, std::uint32_t iteration, const Progress& progress, ScheduleTotals& totals,
                        std::vector<IterationRecord>& iterations) {
    SppmPass& sppm = *pipeline.sppm();
    const std::uint64_t pixels = sppm.state().pixels();
    sppm.begin_iteration();
    run_schedule(pipeline, {iteration * pixels, (iteration + 1) * pixels}, progress, totals, iterations);
    if (pipeline.photons_per_iteration() > 0 && sppm.build_grid(pipeline.launcher())) {
        pipeline.begin_photon_pass(iteration);
        drain_pass(
            pipeline, StageLoop::PHOTON, pipeline.photons_per_iteration(), [](std::uint32_t) {}, totals, iterations);
    }
    sppm.update(pipeline.launcher());
    totals.photon_deposits += pipeline.photon_deposits();
}

}  // namespace wp
