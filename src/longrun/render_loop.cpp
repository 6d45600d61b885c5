#include "longrun/render_loop.h"

#include <algorithm>
#include <chrono>

#include "longrun/error_estimate.h"
#include "longrun/film_file.h"

namespace wp {

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

// The progress of one pass, as a fraction of the whole plan.
Progress pass_progress(const Progress& progress, const ItemRange& plan, const ItemRange& pass) {
    Progress mapped;
    mapped.step = progress.step;
    if (progress.samples)
        mapped.samples = [&progress, plan, pass](double fraction) {
            progress.report((double(pass.begin - plan.begin) + fraction * double(pass.size())) / double(plan.size()));
        };
    return mapped;
}

}  // namespace

const char* stop_reason_name(StopReason reason) {
    switch (reason) {
        case StopReason::Done:
            return "done";
        case StopReason::TimeBudget:
            return "time budget";
        case StopReason::TargetError:
            return "target error";
        case StopReason::Interrupted:
            return "interrupted";
    }
    return "done";
}

LongRunResult run_long_render(FilmRenderer& renderer, const LongRunPlan& plan, const Progress& progress) {
    const auto start = Clock::now();
    if (plan.start) renderer.load(*plan.start);
    LongRunResult result;
    auto checkpoint = [&] {
        write_film_file(plan.checkpoint_path, {plan.identity, renderer.film()});
        ++result.checkpoints;
    };
    auto last_checkpoint = start;
    double longest_pass_s = 0.0;
    std::uint64_t at = plan.start ? plan.start->items.end : plan.items.begin;
    const std::uint64_t first = at;
    // Work items at which the error is next estimated (none without a target).
    const std::uint64_t pixels = plan.pixels;
    std::uint64_t next_check = plan.target_error > 0.0 ? next_error_check(at / pixels) * pixels : UINT64_MAX;
    progress.report(double(at - plan.items.begin) / double(std::max<std::uint64_t>(plan.items.size(), 1)));
    while (at < plan.items.end) {
        // The next pass is assumed to take as long as the longest so far.
        if (plan.time_budget_s > 0.0 && at > first && seconds_since(start) + longest_pass_s > plan.time_budget_s) {
            result.reason = StopReason::TimeBudget;
            break;
        }
        const ItemRange pass{at, std::min({plan.items.end, at + renderer.pass_items(), next_check})};
        const auto pass_start = Clock::now();
        renderer.render(pass, pass_progress(progress, plan.items, pass));
        longest_pass_s = std::max(longest_pass_s, seconds_since(pass_start));
        at = pass.end;
        if (at == next_check) {
            result.error = relative_standard_error(renderer.film());
            if (result.error <= plan.target_error) {
                result.reason = at < plan.items.end ? StopReason::TargetError : StopReason::Done;
                break;
            }
            next_check = next_error_check(at / pixels) * pixels;
        }
        if (plan.stop_requested && plan.stop_requested->load()) {
            result.reason = at < plan.items.end ? StopReason::Interrupted : StopReason::Done;
            break;
        }
        if (!plan.checkpoint_path.empty() && at < plan.items.end &&
            std::chrono::duration<double>(Clock::now() - last_checkpoint).count() >= plan.checkpoint_every_s) {
            checkpoint();
            last_checkpoint = Clock::now();
        }
    }
    if (!plan.checkpoint_path.empty()) checkpoint();
    result.film = renderer.film();
    result.stats = renderer.stats();
    result.stats.samples = at - first;
    result.stats.time_s = seconds_since(start);
    renderer.finish(result.stats.time_s);
    return result;
}

}  // namespace wp
