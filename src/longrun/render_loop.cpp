#include "longrun/render_loop.h"

#include <algorithm>
#include <chrono>
#include <optional>
#include <utility>
#include <vector>

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

// Where the render is, in work items of adaptive sampling's round (over
// every pixel unless it has stopped some). Every rank holds the same values:
// each comes from the plan, from the root's decisions (Ranks::root_decides)
// or from the renderer's round, which every rank begins alike.
struct Position {
    std::uint64_t done = 0;        // every rank together has rendered [film_begin, done)
    std::uint64_t film_begin = 0;  // plan.items.begin, or the adaptive round's first work item
    std::uint64_t pixels = 0;      // the adaptive round's: a sample per pixel is this many work items
    ItemRange planned;             // plan.items, counted in the adaptive round's work items
    // The samples per pixel at which the adaptive round began (a
    // checkpoint's film starts there); 0 outside one.
    std::uint64_t round_start_spp = 0;
    std::uint64_t next_check = UINT64_MAX;  // where the error is next estimated; UINT64_MAX: never
    std::uint64_t round_items = 0;          // a round: a pass of the root's renderer on every rank
    std::uint64_t rendered = 0;             // work items rendered by this run, on all ranks
};

// One rank's part of run_long_render. The ranks work in lockstep: every rank
// makes the same collective calls (the methods marked "Collective") in the
// same order, so the root's decisions reach them all. A collective call is
// made unconditionally or behind a test of the plan, the Position or a
// decision of the root's; what one rank alone knows (its clock, its stop
// request, its sums) reaches the others only through such a call.
class LongRender {
 public:
    LongRender(FilmRenderer& renderer, const LongRunPlan& plan, const Progress& progress, Ranks& ranks)
        : renderer_(renderer), plan_(plan), progress_(progress), ranks_(ranks), shares_(renderer) {}

    // Collective: the whole render, every rank's from the same plan.
    LongRunResult run() {
        start();
        while (position_.done < position_.planned.end) {
            if (out_of_time()) return finish(StopReason::TimeBudget);
            const auto round_began = Clock::now();
            render_round();
            if (position_.done == position_.next_check)
                if (const std::optional<StopReason> stop = check()) return finish(*stop);
            const bool stop = stop_requested();
            // After waiting for every rank: the round of the slowest.
            longest_round_s_ = std::max(longest_round_s_, seconds_since(round_began));
            if (stop)
                return finish(position_.done < position_.planned.end ? StopReason::Interrupted : StopReason::Done);
            if (checkpoint_due()) write_checkpoint(film_so_far());
        }
        return finish(StopReason::Done);
    }

 private:
    // Collective: where the root's film starts (a checkpoint, with the
    // adaptive round it may be in, which every other rank's empty film
    // takes) and the round size, then the position they give.
    void start() {
        if (plan_.start) renderer_.load(*plan_.start);
        position_.done = ranks_.root_decides([&] { return plan_.start ? plan_.start->items.end : plan_.items.begin; });
        position_.film_begin =
            ranks_.root_decides([&] { return plan_.start ? plan_.start->items.begin : plan_.items.begin; });
        join_adaptive_round();
        position_.round_items =
            ranks_.root_decides([&] { return renderer_.pass_items() * std::uint64_t(ranks_.size()); });
        take_round_pixels();
        position_.round_start_spp = renderer_.round_pixels().empty() ? 0 : position_.film_begin / position_.pixels;
        const bool checks = plan_.target_error > 0.0 || plan_.adaptive.on();
        if (checks) position_.next_check = next_check_after(position_.done / position_.pixels) * position_.pixels;
        progress_.report(double(position_.done - position_.planned.begin) /
                         double(std::max<std::uint64_t>(position_.planned.size(), 1)));
    }

    // Collective: the root's adaptive round, taken by every other rank
    // (their renderers start empty where the root's film ends).
    void join_adaptive_round() {
        std::vector<std::uint32_t> pixels = ranks_.root_decides([&] { return renderer_.round_pixels(); });
        std::vector<std::uint32_t> before = ranks_.root_decides(
            [&] { return pixels.empty() ? std::vector<std::uint32_t>{} : renderer_.film().samples_before; });
        if (ranks_.is_root() || pixels.empty()) return;
        Film round = empty_like(renderer_.film(), position_.done);
        round.round_pixels = std::move(pixels);
        round.samples_before = std::move(before);
        renderer_.load(round);
    }

    // The renderer's adaptive round (its pixels) as the Position's.
    void take_round_pixels() {
        const std::vector<std::uint32_t>& round = renderer_.round_pixels();
        position_.pixels = round.empty() ? plan_.pixels : std::uint64_t(round.size());
        position_.planned = position_.pixels == plan_.pixels
                                ? plan_.items
                                : ItemRange{plan_.items.begin / plan_.pixels * position_.pixels,
                                            plan_.items.end / plan_.pixels * position_.pixels};
    }

    // Collective, with a time budget: whether the next round would end past
    // it, by the root's clock (it is assumed to take as long as the longest).
    bool out_of_time() {
        if (plan_.time_budget_s <= 0.0 || position_.rendered == 0) return false;
        return ranks_.root_decides([&] { return seconds_since(started_) + longest_round_s_ > plan_.time_budget_s; });
    }

    // This rank's share of the next round, which ends at the planned end,
    // after a pass on every rank, or at the next check.
    void render_round() {
        const ItemRange round{position_.done, std::min({position_.planned.end, position_.done + position_.round_items,
                                                        position_.next_check})};
        shares_.render(share_of(round, ranks_.rank(), ranks_.size()),
                       round_progress(progress_, position_.planned, round));
        position_.rendered += round.size();
        position_.done = round.end;
    }

    // Collective, at a check (a whole sample count of the round's pixels):
    // the root estimates the image's error against the target, then, if
    // adaptive sampling decides there, which pixels go on; fewer begin a
    // round over them on every rank. Returns why the render stops there, if
    // it does.
    std::optional<StopReason> check() {
        const std::uint64_t spp = position_.done / position_.pixels;
        const bool last = position_.done == position_.planned.end;  // it ends there anyway
        const Film film = film_so_far();
        if (plan_.target_error > 0.0) {
            result_.error = ranks_.root_decides([&] { return relative_standard_error(film); });
            if (result_.error <= plan_.target_error) return last ? StopReason::Done : StopReason::TargetError;
        }
        if (decides_at(spp)) {
            std::vector<std::uint32_t> active =
                ranks_.root_decides([&] { return pixels_still_active(film, plan_.adaptive.threshold); });
            if (active.empty()) return last ? StopReason::Done : StopReason::Converged;
            if (active.size() < position_.pixels) begin_adaptive_round(std::move(active), film.items, spp);
        }
        position_.next_check = next_check_after(spp) * position_.pixels;
        return std::nullopt;
    }

    // Adaptive sampling's round over `pixels`, begun alike by every rank
    // after `done` (the film's range so far), at `spp` samples per pixel.
    void begin_adaptive_round(std::vector<std::uint32_t> pixels, const ItemRange& done, std::uint64_t spp) {
        shares_.begin_round(std::move(pixels), done);
        take_round_pixels();
        position_.done = renderer_.items().end;
        position_.film_begin = position_.done;
        position_.round_start_spp = spp;
    }

    // Adaptive sampling decides at the checks from its minimum on that lie
    // at least a whole image's worth of work items after the round began,
    // so that a round over few pixels is not cut into passes too small to
    // fill the device (a wavefront pass costs some iterations over all its slots).
    bool decides_at(std::uint64_t spp) const {
        return plan_.adaptive.on() && spp >= plan_.adaptive.min_spp &&
               (spp - position_.round_start_spp) * position_.pixels >= plan_.pixels;
    }

    // The samples per pixel of the next check after `spp`: the error's next
    // estimate, or adaptive sampling's next decision when there is no target.
    std::uint64_t next_check_after(std::uint64_t spp) const {
        std::uint64_t next = next_error_check(spp);
        while (plan_.target_error <= 0.0 && !decides_at(next)) next = next_error_check(next);
        return next;
    }

    // Collective: whether a stop was requested on any rank.
    bool stop_requested() { return ranks_.any(plan_.stop_requested && plan_.stop_requested->load()); }

    // Collective, with a checkpoint file and work left: whether one is due,
    // by the root's clock.
    bool checkpoint_due() {
        if (plan_.checkpoint_path.empty() || position_.done >= position_.planned.end) return false;
        return ranks_.root_decides([&] { return seconds_since(last_checkpoint_) >= plan_.checkpoint_every_s; });
    }

    // Writes `film` (the root's) as the checkpoint.
    void write_checkpoint(const Film& film) {
        if (ranks_.is_root()) write_film_file(plan_.checkpoint_path, {plan_.identity, film});
        ++result_.checkpoints;
        last_checkpoint_ = Clock::now();
    }

    // Collective: every rank's sums so far, on the root.
    Film film_so_far() {
        Film film = shares_.sums();
        ranks_.sum_films_to_root(film);
        film.items = {position_.film_begin, position_.done};
        return film;
    }

    // Collective: the film, the last checkpoint and every rank's figures.
    LongRunResult finish(StopReason reason) {
        result_.reason = reason;
        result_.film = film_so_far();
        if (!plan_.checkpoint_path.empty()) write_checkpoint(result_.film);
        gather_stats();
        result_.stats.samples = position_.rendered;
        result_.stats.time_s = seconds_since(started_);
        renderer_.finish(result_.stats.time_s);
        return std::move(result_);
    }

    // Collective: rays, threads and non-finite values summed over the ranks,
    // and each rank's work items and busy time, on the root.
    void gather_stats() {
        const RenderStats mine = renderer_.stats();
        std::vector<std::uint64_t> figures{shares_.rendered(),  std::uint64_t(shares_.busy_s() * 1e9),
                                           mine.extension_rays, mine.shadow_rays,
                                           mine.threads,        mine.photons,
                                           mine.photon_rays,    mine.photon_deposits};
        figures.insert(figures.end(), mine.nonfinite_by_stage.begin(), mine.nonfinite_by_stage.end());
        const std::vector<std::uint64_t> all = ranks_.gather(figures);
        for (std::size_t at = 0; at < all.size(); at += figures.size()) {
            result_.samples_per_rank.push_back(all[at]);
            result_.busy_s_per_rank.push_back(double(all[at + 1]) * 1e-9);
            result_.stats.extension_rays += all[at + 2];
            result_.stats.shadow_rays += all[at + 3];
            result_.stats.threads += all[at + 4];
            result_.stats.photons += all[at + 5];
            result_.stats.photon_rays += all[at + 6];
            result_.stats.photon_deposits += all[at + 7];
            NonfiniteCounts counts{};
            std::copy_n(all.begin() + std::ptrdiff_t(at + 8), counts.size(), counts.begin());
            result_.stats.add_nonfinite(counts);
        }
    }

    FilmRenderer& renderer_;
    const LongRunPlan& plan_;
    const Progress& progress_;
    Ranks& ranks_;
    Shares shares_;
    Position position_;
    LongRunResult result_;
    // This rank's clock (the root's decides).
    const Clock::time_point started_ = Clock::now();
    Clock::time_point last_checkpoint_ = started_;
    double longest_round_s_ = 0.0;
};

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
    return LongRender(renderer, plan, progress, ranks).run();
}

LongRunResult run_long_render(FilmRenderer& renderer, const LongRunPlan& plan, const Progress& progress) {
    SingleProcess one;
    return run_long_render(renderer, plan, progress, one);
}

}  // namespace wp
