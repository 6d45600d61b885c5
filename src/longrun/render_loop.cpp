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

// The progress of one round, as a fraction of the whole plan (a rank's share
// of the round stands for the round).
Progress round_progress(const Progress& progress, const ItemRange& plan, const ItemRange& round) {
    Progress mapped;
    mapped.step = progress.step;
    if (progress.samples)
        mapped.samples = [&progress, plan, round](double fraction) {
            progress.report((double(round.begin - plan.begin) + fraction * double(round.size())) / double(plan.size()));
        };
    return mapped;
}

// An empty film like `film` (size, squares, adaptive round) at work item `at`.
Film empty_like(const Film& film, std::uint64_t at) {
    Film empty = Film::empty(film.width, film.height, at, !film.squares.empty());
    empty.round_pixels = film.round_pixels;
    empty.samples_before = film.samples_before;
    return empty;
}

// This rank's shares of the rounds, rendered into its renderer's film. That
// film holds one range of work items, so a share that does not continue it
// (on several ranks, every round's) first moves its sums aside; so does an
// adaptive round over fewer pixels, which every rank begins.
class Shares {
 public:
    explicit Shares(FilmRenderer& renderer) : renderer_(renderer) {}

    void render(const ItemRange& share, const Progress& progress) {
        if (share.size() == 0) return;
        if (renderer_.items().size() != 0 && share.begin != renderer_.items().end) {
            const Film film = set_aside();
            renderer_.load(empty_like(film, share.begin));
        }
        const auto start = Clock::now();
        renderer_.render(share, progress);
        busy_s_ += seconds_since(start);
        rendered_ += share.size();
    }

    // Begins adaptive sampling's round over `pixels` after `done`, the work
    // items all ranks have rendered in the current round (or since the start).
    void begin_round(std::vector<std::uint32_t> pixels, const ItemRange& done) {
        Film round = empty_like(set_aside(), 0);
        round.items = done;
        round.begin_round(std::move(pixels));
        renderer_.load(round);
    }

    // The sums of every share so far (with the film this rank started from),
    // in the renderer's round.
    Film sums() {
        Film film = renderer_.film();
        if (earlier_) film.add_sums(*earlier_);
        return film;
    }

    std::uint64_t rendered() const { return rendered_; }
    // Seconds spent rendering shares (not waiting for other ranks).
    double busy_s() const { return busy_s_; }

 private:
    // Adds the renderer's film to the sums moved aside, and returns it.
    Film set_aside() {
        Film film = renderer_.film();
        if (earlier_)
            earlier_->add_sums(film);
        else
            earlier_ = film;
        return film;
    }

    FilmRenderer& renderer_;
    std::optional<Film> earlier_;
    std::uint64_t rendered_ = 0;
    double busy_s_ = 0.0;
};

// The root's adaptive round of the film it resumes, taken by every other
// rank (their renderers start empty at work item `at`).
void join_round(FilmRenderer& renderer, Ranks& ranks, std::uint64_t at) {
    std::vector<std::uint32_t> pixels = renderer.round_pixels(), before;
    if (ranks.is_root() && !pixels.empty()) before = renderer.film().samples_before;
    ranks.broadcast(pixels);
    ranks.broadcast(before);
    if (ranks.is_root() || pixels.empty()) return;
    Film round = empty_like(renderer.film(), at);
    round.round_pixels = std::move(pixels);
    round.samples_before = std::move(before);
    renderer.load(round);
}

// At a check (a whole sample count of the round's pixels), on the root's
// `film` (every rank's sums): the image's error estimate against the target,
// then, if it `decide`s there, adaptive sampling's decision, which may begin
// a round over fewer pixels on every rank. Returns why the render stops
// there, if it does (`last`: it ends there anyway); every rank returns the same.
std::optional<StopReason> check(Shares& shares, const LongRunPlan& plan, const Film& film, std::uint64_t pixels,
                                bool decide, bool last, Ranks& ranks, LongRunResult& result) {
    if (plan.target_error > 0.0) {
        double error = ranks.is_root() ? relative_standard_error(film) : 0.0;
        ranks.broadcast(error);
        result.error = error;
        if (error <= plan.target_error) return last ? StopReason::Done : StopReason::TargetError;
    }
    if (decide) {
        std::vector<std::uint32_t> active;
        if (ranks.is_root()) active = pixels_still_active(film, plan.adaptive.threshold);
        ranks.broadcast(active);
        if (active.empty()) return last ? StopReason::Done : StopReason::Converged;
        if (active.size() < pixels) shares.begin_round(std::move(active), film.items);
    }
    return std::nullopt;
}

// Rays, threads and non-finite values summed over the ranks, and each rank's
// work items and busy time, into `result` on the root (time_s is the caller's).
void gather_stats(const RenderStats& mine, const Shares& shares, Ranks& ranks, LongRunResult& result) {
    std::vector<std::uint64_t> figures{shares.rendered(), std::uint64_t(shares.busy_s() * 1e9), mine.extension_rays,
                                       mine.shadow_rays, mine.threads};
    figures.insert(figures.end(), mine.nonfinite_by_stage.begin(), mine.nonfinite_by_stage.end());
    const std::vector<std::uint64_t> all = ranks.gather(figures);
    for (std::size_t at = 0; at < all.size(); at += figures.size()) {
        result.samples_per_rank.push_back(all[at]);
        result.busy_s_per_rank.push_back(double(all[at + 1]) * 1e-9);
        result.stats.extension_rays += all[at + 2];
        result.stats.shadow_rays += all[at + 3];
        result.stats.threads += all[at + 4];
        NonfiniteCounts counts{};
        std::copy_n(all.begin() + std::ptrdiff_t(at + 5), counts.size(), counts.begin());
        result.stats.add_nonfinite(counts);
    }
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

LongRunResult run_long_render(FilmRenderer& renderer, const LongRunPlan& plan, const Progress& progress, Ranks& ranks) {
    const auto start = Clock::now();
    if (plan.start) renderer.load(*plan.start);
    std::uint64_t at = plan.start ? plan.start->items.end : plan.items.begin;
    ranks.broadcast(at);
    // Where the film's range begins: plan.items.begin, or the adaptive round's first work item.
    std::uint64_t film_begin = plan.start ? plan.start->items.begin : plan.items.begin;
    ranks.broadcast(film_begin);
    join_round(renderer, ranks, at);
    // A round is a pass of the root's renderer on every rank.
    std::uint64_t round_items = renderer.pass_items() * std::uint64_t(ranks.size());
    ranks.broadcast(round_items);
    Shares shares(renderer);
    LongRunResult result;
    // Every rank's sums so far, on the root (every rank must call it).
    auto film_so_far = [&] {
        Film film = shares.sums();
        ranks.sum_films_to_root(film);
        film.items = {film_begin, at};
        return film;
    };
    auto checkpoint = [&](const Film& film) {
        if (ranks.is_root()) write_film_file(plan.checkpoint_path, {plan.identity, film});
        ++result.checkpoints;
    };
    auto last_checkpoint = start;
    double longest_round_s = 0.0;
    // Work items count in the adaptive round's pixels (all of them unless
    // adaptive sampling has stopped some; the same on every rank): the
    // planned range in those items, and where the render is in it.
    auto round_pixel_count = [&] {
        return renderer.round_pixels().empty() ? plan.pixels : std::uint64_t(renderer.round_pixels().size());
    };
    std::uint64_t pixels = round_pixel_count();
    auto planned_in_round = [&] {
        if (pixels == plan.pixels) return plan.items;
        return ItemRange{plan.items.begin / plan.pixels * pixels, plan.items.end / plan.pixels * pixels};
    };
    ItemRange planned = planned_in_round();
    std::uint64_t samples = 0;
    // The samples per pixel at which the round began (a checkpoint's film
    // starts there). Adaptive sampling decides at the checks from its minimum
    // on that lie at least a whole image's worth of work items after that, so
    // that a round over few pixels is not cut into passes too small to fill
    // the device (a wavefront pass costs some iterations over all its slots).
    std::uint64_t round_start = renderer.round_pixels().empty() ? 0 : film_begin / pixels;
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
        // The next round is assumed to take as long as the longest so far.
        if (plan.time_budget_s > 0.0 && samples > 0) {
            bool out_of_time = seconds_since(start) + longest_round_s > plan.time_budget_s;
            ranks.broadcast(out_of_time);
            if (out_of_time) {
                result.reason = StopReason::TimeBudget;
                break;
            }
        }
        const ItemRange round{at, std::min({planned.end, at + round_items, next_check})};
        const auto round_began = Clock::now();
        shares.render(share_of(round, ranks.rank(), ranks.size()), round_progress(progress, planned, round));
        samples += round.size();
        at = round.end;
        if (at == next_check) {
            const std::uint64_t spp = at / pixels;
            if (const auto stop =
                    check(shares, plan, film_so_far(), pixels, decides_at(spp), at == planned.end, ranks, result)) {
                result.reason = *stop;
                break;
            }
            if (round_pixel_count() != pixels) {  // a round over fewer pixels began
                pixels = round_pixel_count();
                planned = planned_in_round();
                at = renderer.items().end;
                film_begin = at;
                round_start = spp;
            }
            next_check = next_check_spp(spp) * pixels;
        }
        // After waiting for every rank: the round of the slowest.
        const bool stop = ranks.any(plan.stop_requested && plan.stop_requested->load());
        longest_round_s = std::max(longest_round_s, seconds_since(round_began));
        if (stop) {
            result.reason = at < planned.end ? StopReason::Interrupted : StopReason::Done;
            break;
        }
        if (!plan.checkpoint_path.empty() && at < planned.end) {
            bool due = seconds_since(last_checkpoint) >= plan.checkpoint_every_s;
            ranks.broadcast(due);
            if (due) {
                checkpoint(film_so_far());
                last_checkpoint = Clock::now();
            }
        }
    }
    result.film = film_so_far();
    if (!plan.checkpoint_path.empty()) checkpoint(result.film);
    gather_stats(renderer.stats(), shares, ranks, result);
    result.stats.samples = samples;
    result.stats.time_s = seconds_since(start);
    renderer.finish(result.stats.time_s);
    return result;
}

LongRunResult run_long_render(FilmRenderer& renderer, const LongRunPlan& plan, const Progress& progress) {
    SingleProcess one;
    return run_long_render(renderer, plan, progress, one);
}

}  // namespace wp
