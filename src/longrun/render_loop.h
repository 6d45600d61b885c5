// The long render: a backend's film advanced pass by pass towards a range of
// work items, with a time budget, periodic checkpoints and a stop request
// (a signal) checked between passes. Where it stops never changes the bits
// of what it has summed: film sums are exact.
#pragma once

#include <atomic>
#include <cstdint>
#include <optional>
#include <string>

#include "core/film_renderer.h"
#include "longrun/adaptive.h"
#include "longrun/render_identity.h"

namespace wp {

enum class StopReason { Done, TimeBudget, TargetError, Converged, Interrupted };
// "done", "time budget", "target error", "converged" (adaptive sampling
// stopped every pixel), "interrupted".
const char* stop_reason_name(StopReason reason);

struct LongRunPlan {
    ItemRange items;             // render up to items.end; an empty film starts at items.begin
    std::optional<Film> start;   // continue this film (a checkpoint), whose range starts at items.begin
    double time_budget_s = 0.0;  // 0: none. Stops before a pass that would end past it.
    // 0: none. Else the film must keep squares and start at work item 0; the
    // error is estimated at the sample counts of next_error_check, and the
    // render stops at the first where it is at most target_error.
    double target_error = 0.0;
    // Off, or: the film must keep squares and start at work item 0, items must
    // be whole samples per pixel; pixels stop at the checks of next_error_check
    // from adaptive.min_spp on (longrun/adaptive.h), and the render ends when
    // none is left.
    AdaptiveSampling adaptive;
    std::uint64_t pixels = 1;     // width x height: a sample per pixel is this many work items
    std::string checkpoint_path;  // "": none
    double checkpoint_every_s = 0.0;
    RenderIdentity identity;                            // written into checkpoints
    const std::atomic<bool>* stop_requested = nullptr;  // checked after every pass
};

struct LongRunResult {
    Film film;
    RenderStats stats;  // samples: those rendered by this run; time_s: its wall time (a film in an adaptive round)
    StopReason reason = StopReason::Done;
    int checkpoints = 0;  // checkpoint files written
    double error = -1.0;  // the last error estimate (target_error), -1: none made
};

// Renders as planned. Reports the fraction of plan.items done. A checkpoint
// is written every checkpoint_every_s and once more at the end.
LongRunResult run_long_render(FilmRenderer& renderer, const LongRunPlan& plan, const Progress& progress);

}  // namespace wp
