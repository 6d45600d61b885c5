#include "longrun/render_loop.h"

#include <algorithm>
#include <chrono>
#include <optional>

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

// At a check (a whole sample count of the round's pixels): the image's
// error estimate against the target, then, if it `decide`s there, adaptive
// sampling's decision, which may begin a round over fewer pixels. Returns
// why the render stops there, if it does (`last`: it ends there anyway).
std::optional<StopReason> check(FilmRenderer& renderer, const LongRunPlan& plan, bool decide, bool last,
                                LongRunResult& result) {
    const Film film = renderer.film();
    if (plan.target_error > 0.0) {
        result.error = relative_standard_error(film);
        if (result.error <= plan.target_error) return last ? StopReason::Done : StopReason::TargetError;
    }
    if (decide) {
        std::vector<std::uint32_t> active = pixels_still_active(film, plan.adaptive.threshold);
        if (active.empty()) return last ? StopReason::Done : StopReason::Converged;
        if (active.size() < film.round_pixel_count()) renderer.begin_round(std::move(active));
    }
    return std::nullopt;
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
    auto round_pixel_count = [&] {
        return renderer.round_pixels().empty() ? plan.pixels : std::uint64_t(renderer.round_pixels().size());
    };
    std::uint64_t pixels = round_pixel_count();
    auto planned_in_round = [&] {
        if (pixels == plan.pixels) return plan.items;
        return ItemRange{plan.items.begin / plan.pixels * pixels, plan.items.end / plan.pixels * pixels};
    };
    ItemRange planned = planned_in_round();
    std::uint64_t at = plan.start ? plan.start->items.end : plan.items.begin;
    std::uint64_t samples = 0;
    // The samples per pixel at which the round began (a checkpoint's film
    // starts there). Adaptive sampling decides at the checks from its minimum
    // on that lie at least a whole image's worth of work items after that, so
    // that a round over few pixels is not cut into passes too small to fill
    // the device (a wavefront pass costs some iterations over all its slots).
    std::uint64_t round_start = renderer.round_pixels().empty() ? 0 : renderer.items().begin / pixels;
    auto decides_at = [&](std::uint64_t spp) {
        return plan.adaptive.on() && spp >= plan.adaptive.min_spp && (spp - round_start) * pixels >= plan.pixels;
    };
    // Work items at which the error is next estimated (none without a target
    // or adaptive sampling); adaptive sampling alone at its decisions only.
    const bool checks = plan.target_error > 0.0 || plan.adaptive.on();
    auto next_check_spp = [&](std::uint64_t spp) {
        std::uint64_t next = next_error_check(spp);
        while (plan.target_error <= 0.0 && !decides_at(next)) next = next_error_check(next);
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
            if (const auto stop = check(renderer, plan, decides_at(spp), at == planned.end, result)) {
                result.reason = *stop;
                break;
            }
            if (round_pixel_count() != pixels) {  // a round over fewer pixels began
                pixels = round_pixel_count();
                planned = planned_in_round();
                at = renderer.items().end;
                round_start = spp;
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
