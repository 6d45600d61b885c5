#include "longrun/render_loop.h"

#include <algorithm>
#include <chrono>

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

// This rank's shares of the rounds, rendered into its renderer's film. That
// film holds one range of work items, so a share that does not continue it
// (on several ranks, every round's) first moves its sums aside.
class Shares {
 public:
    explicit Shares(FilmRenderer& renderer) : renderer_(renderer) {}

    void render(const ItemRange& share, const Progress& progress) {
        if (share.size() == 0) return;
        if (renderer_.items().size() != 0 && share.begin != renderer_.items().end) {
            Film film = renderer_.film();
            if (earlier_)
                earlier_->add_sums(film);
            else
                earlier_ = film;
            renderer_.load(Film::empty(film.width, film.height, share.begin, !film.squares.empty()));
        }
        const auto start = Clock::now();
        renderer_.render(share, progress);
        busy_s_ += seconds_since(start);
        rendered_ += share.size();
    }

    // The sums of every share so far (with the film this rank started from).
    Film sums() {
        Film film = renderer_.film();
        if (earlier_) film.add_sums(*earlier_);
        return film;
    }

    std::uint64_t rendered() const { return rendered_; }
    // Seconds spent rendering shares (not waiting for other ranks).
    double busy_s() const { return busy_s_; }

 private:
    FilmRenderer& renderer_;
    std::optional<Film> earlier_;
    std::uint64_t rendered_ = 0;
    double busy_s_ = 0.0;
};

// Rays and non-finite values summed over the ranks, and each rank's work
// items and busy time, into `result` on the root (time_s is the caller's).
void gather_stats(const RenderStats& mine, const Shares& shares, Ranks& ranks, LongRunResult& result) {
    std::vector<std::uint64_t> figures{shares.rendered(), std::uint64_t(shares.busy_s() * 1e9), mine.extension_rays,
                                       mine.shadow_rays};
    figures.insert(figures.end(), mine.nonfinite_by_stage.begin(), mine.nonfinite_by_stage.end());
    const std::vector<std::uint64_t> all = ranks.gather(figures);
    for (std::size_t at = 0; at < all.size(); at += figures.size()) {
        result.samples_per_rank.push_back(all[at]);
        result.busy_s_per_rank.push_back(double(all[at + 1]) * 1e-9);
        result.stats.extension_rays += all[at + 2];
        result.stats.shadow_rays += all[at + 3];
        NonfiniteCounts counts{};
        std::copy_n(all.begin() + std::ptrdiff_t(at + 4), counts.size(), counts.begin());
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
    // A round is a pass of the root's renderer on every rank.
    std::uint64_t round_items = renderer.pass_items() * std::uint64_t(ranks.size());
    ranks.broadcast(round_items);
    Shares shares(renderer);
    LongRunResult result;
    // Every rank's sums so far, on the root (every rank must call it).
    auto film_so_far = [&] {
        Film film = shares.sums();
        ranks.sum_films_to_root(film);
        film.items = {plan.items.begin, at};
        return film;
    };
    auto checkpoint = [&](const Film& film) {
        if (ranks.is_root()) write_film_file(plan.checkpoint_path, {plan.identity, film});
        ++result.checkpoints;
    };
    auto last_checkpoint = start;
    double longest_round_s = 0.0;
    const std::uint64_t first = at;
    // Work items at which the error is next estimated (none without a target).
    const std::uint64_t pixels = plan.pixels;
    std::uint64_t next_check = plan.target_error > 0.0 ? next_error_check(at / pixels) * pixels : UINT64_MAX;
    progress.report(double(at - plan.items.begin) / double(std::max<std::uint64_t>(plan.items.size(), 1)));
    while (at < plan.items.end) {
        // The next round is assumed to take as long as the longest so far.
        if (plan.time_budget_s > 0.0 && at > first) {
            bool out_of_time = seconds_since(start) + longest_round_s > plan.time_budget_s;
            ranks.broadcast(out_of_time);
            if (out_of_time) {
                result.reason = StopReason::TimeBudget;
                break;
            }
        }
        const ItemRange round{at, std::min({plan.items.end, at + round_items, next_check})};
        const auto round_start = Clock::now();
        shares.render(share_of(round, ranks.rank(), ranks.size()), round_progress(progress, plan.items, round));
        at = round.end;
        if (at == next_check) {
            const Film film = film_so_far();
            double error = ranks.is_root() ? relative_standard_error(film) : 0.0;
            ranks.broadcast(error);
            result.error = error;
            if (result.error <= plan.target_error) {
                result.reason = at < plan.items.end ? StopReason::TargetError : StopReason::Done;
                break;
            }
            next_check = next_error_check(at / pixels) * pixels;
        }
        // After waiting for every rank: the round of the slowest.
        const bool stop = ranks.any(plan.stop_requested && plan.stop_requested->load());
        longest_round_s = std::max(longest_round_s, seconds_since(round_start));
        if (stop) {
            result.reason = at < plan.items.end ? StopReason::Interrupted : StopReason::Done;
            break;
        }
        if (!plan.checkpoint_path.empty() && at < plan.items.end) {
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
    result.stats.samples = at - first;
    result.stats.time_s = seconds_since(start);
    renderer.finish(result.stats.time_s);
    return result;
}

LongRunResult run_long_render(FilmRenderer& renderer, const LongRunPlan& plan, const Progress& progress) {
    SingleProcess one;
    return run_long_render(renderer, plan, progress, one);
}

}  // namespace wp
