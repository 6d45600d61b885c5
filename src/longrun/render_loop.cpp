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
        case StopReason::Converged:
            return "converged";
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
    // Work items count in the round's pixels (all of them unless adaptive
    // sampling has stopped some): the planned range in those items, and
    // where the render is in it.
    std::uint64_t pixels = plan.start && plan.start->in_round() ? plan.start->round_pixels.size() : plan.pixels;
    auto planned_in_round = [&] {
        if (pixels == plan.pixels) return plan.items;
        return ItemRange{plan.items.begin / plan.pixels * pixels, plan.items.end / plan.pixels * pixels};
    };
    ItemRange planned = planned_in_round();
    std::uint64_t at = plan.start ? plan.start->items.end : plan.items.begin;
    std::uint64_t samples = 0;
    // Work items at which the error is next estimated (none without a target
    // or adaptive sampling); adaptive sampling alone starts at its minimum.
    const bool checks = plan.target_error > 0.0 || plan.adaptive.on();
    auto next_check_spp = [&](std::uint64_t spp) {
        std::uint64_t next = next_error_check(spp);
        while (plan.target_error <= 0.0 && next < plan.adaptive.min_spp) next = next_error_check(next);
        return next;
    };
    std::uint64_t next_check = checks ? next_check_spp(at / pixels) * pixels : UINT64_MAX;
    progress.report(double(at - planned.begin) / double(std::max<std::uint64_t>(planned.size(), 1)));
    while (at < planned.end) {
        // The next pass is assumed to take as long as the longest so far.
        if (plan.time_budget_s > 0.0 && samples > 0 && seconds_since(start) + longest_pass_s > plan.time_budget_s) {
            result.reason = StopReason::TimeBudget;
            break;
        }
        const ItemRange pass{at, std::min({planned.end, at + renderer.pass_items(), next_check})};
        const auto pass_start = Clock::now();
        renderer.render(pass, pass_progress(progress, planned, pass));
        longest_pass_s = std::max(longest_pass_s, seconds_since(pass_start));
        samples += pass.size();
        at = pass.end;
        if (at == next_check) {
            const std::uint64_t spp = at / pixels;
            const Film film = renderer.film();
            if (plan.target_error > 0.0) {
                result.error = relative_standard_error(film);
                if (result.error <= plan.target_error) {
                    result.reason = at < planned.end ? StopReason::TargetError : StopReason::Done;
                    break;
                }
            }
            if (plan.adaptive.on() && spp >= plan.adaptive.min_spp) {
                std::vector<std::uint32_t> active = pixels_still_active(film, plan.adaptive.threshold);
                if (active.empty()) {
                    result.reason = at < planned.end ? StopReason::Converged : StopReason::Done;
                    break;
                }
                if (active.size() < pixels) {
                    pixels = active.size();
                    renderer.begin_round(std::move(active));
                    planned = planned_in_round();
                    at = spp * pixels;
                }
            }
            next_check = next_check_spp(spp) * pixels;
        }
        if (plan.stop_requested && plan.stop_requested->load()) {
            result.reason = at < planned.end ? StopReason::Interrupted : StopReason::Done;
            break;
        }
        if (!plan.checkpoint_path.empty() && at < planned.end &&
            std::chrono::duration<double>(Clock::now() - last_checkpoint).count() >= plan.checkpoint_every_s) {
            checkpoint();
            last_checkpoint = Clock::now();
        }
    }
    if (!plan.checkpoint_path.empty()) checkpoint();
    result.film = renderer.film();
    result.stats = renderer.stats();
    result.stats.samples = samples;
    result.stats.time_s = seconds_since(start);
    renderer.finish(result.stats.time_s);
    return result;
}

}  // namespace wp
