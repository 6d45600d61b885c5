// The long render: a backend's film advanced pass by pass towards a range of
// work items, with a time budget, periodic checkpoints and a stop request
// (a signal) checked between passes. Where it stops never changes the bits
// of what it has summed: film sums are exact.
//
// On several ranks (MPI) the work goes in rounds: a round is the next range
// of work items, as many as a pass on every rank, split among the ranks in
// contiguous shares (share_of). After each round every rank has rendered
// its share, so what the ranks have rendered together is always one range
// of work items from the start: the root (rank 0) decides, for all, whether
// to stop or checkpoint, and sums the films in rank order to check the
// error, write a checkpoint or end. Adaptive sampling's decisions are the
// root's too: it sends every rank the pixels still active, and all begin the
// same round over them. On one rank a round is a pass.
#pragma once

#include <atomic>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/film_renderer.h"
#include "distributed/ranks.h"
#include "longrun/adaptive.h"
#include "longrun/render_identity.h"

namespace wp {

enum class StopReason { Done, TimeBudget, TargetError, Converged, Interrupted };
// "done", "time budget", "target error", "converged" (adaptive sampling
// stopped every pixel), "interrupted".
const char* stop_reason_name(StopReason reason);

struct LongRunPlan {
    ItemRange items;  // render up to items.end; an empty film starts at items.begin
    // Continue this film (a checkpoint), whose range starts at items.begin;
    // on several ranks, given to the root only.
    std::optional<Film> start;
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
    Film film;  // on several ranks, on the root only
    // samples: those rendered by this run (on all ranks); time_s: its wall
    // time (a film in an adaptive round)
    RenderStats stats;
    std::vector<std::uint64_t> samples_per_rank;  // rendered by this run, in rank order (on the root)
    std::vector<double> busy_s_per_rank;          // seconds each spent rendering, not waiting (on the root)
    StopReason reason = StopReason::Done;
    int checkpoints = 0;  // checkpoint files written
    double error = -1.0;  // the last error estimate (target_error), -1: none made
};

// Renders as planned. Reports the fraction of plan.items done. A checkpoint
// is written every checkpoint_every_s and once more at the end (by the root).
// Every rank calls it with the same plan (but `start`) and its own renderer.
LongRunResult run_long_render(FilmRenderer& renderer, const LongRunPlan& plan, const Progress& progress, Ranks& ranks);
// In one process.
LongRunResult run_long_render(FilmRenderer& renderer, const LongRunPlan& plan, const Progress& progress);

}  // namespace wp
