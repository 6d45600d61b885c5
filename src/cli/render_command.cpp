#include "cli/render_command.h"

#include <algorithm>
#include <bit>
#include <iostream>

#include "cli/errors.h"
#include "cli/progress.h"
#include "cli/rank_failures.h"
#include "cli/scene_file.h"
#include "cli/signals.h"
#include "cli/summary.h"
#include "core/atomic_file.h"
#include "distributed/ranks.h"
#include "image/image_io.h"
#include "longrun/film_file.h"
#include "longrun/render_loop.h"
#include "scene/limits.h"

namespace wp::cli {

namespace {

// --samples "A:B": work items [A * pixels, B * pixels). Without it, every
// sample the scene asks for.
ItemRange planned_items(const std::string& samples, const Scene& scene) {
    const std::uint64_t pixels = std::uint64_t(scene.camera.width) * scene.camera.height;
    if (samples.empty()) return {0, pixels * std::uint64_t(scene.render.spp)};
    std::size_t colon = samples.find(':');
    std::uint64_t a = 0, b = 0;
    try {
        std::size_t used_a = 0, used_b = 0;
        if (colon == std::string::npos) throw std::invalid_argument("no colon");
        a = std::stoull(samples.substr(0, colon), &used_a);
        b = std::stoull(samples.substr(colon + 1), &used_b);
        if (used_a != colon || used_b != samples.size() - colon - 1 || samples[0] == '-' || samples[colon + 1] == '-')
            throw std::invalid_argument("trailing text");
    } catch (const std::exception&) {
        throw UsageError("--samples: expected A:B (samples A to B-1 of every pixel), got '" + samples + "'");
    }
    if (a >= b || b > std::uint64_t(kMaxSpp))
        throw UsageError("--samples: need 0 <= A < B <= " + std::to_string(kMaxSpp) + ", got " + samples);
    return {a * pixels, b * pixels};
}

// Output paths are checked before the render: a film (.wpfilm) or an image.
void check_outputs(const RenderCommand& command) {
    if (is_film_path(command.output_path))
        check_writable_destination(command.output_path);
    else if (!command.long_run.samples.empty())
        throw UsageError("--samples: a partial render writes a film: -o must name a " +
                         std::string(kFilmFileExtension) + " file, got " + command.output_path);
    else
        validate_output_path(command.output_path);
    if (!command.long_run.checkpoint.empty()) check_writable_destination(command.long_run.checkpoint);
    if (!command.stats_json_path.empty()) check_writable_destination(command.stats_json_path);
    if (!command.backend.profile_json.empty()) check_writable_destination(command.backend.profile_json);
}

// The checkpoint to continue, checked against this render before anything is rendered or written.
Film film_to_resume(const std::string& path, const RenderIdentity& identity, const Scene& scene, const ItemRange& items,
                    bool squares) {
    FilmFile file = read_film_file(path);
    check_film_matches(path, file, identity, scene.camera.width, scene.camera.height);
    Film& film = file.film;
    if (film.in_round() && film.max_samples() * film.pixel_count() > items.end)
        throw FilmFileError(path + ": holds " + std::to_string(film.max_samples()) +
                            " samples per pixel, more than the " + std::to_string(items.end / film.pixel_count()) +
                            " this render asks for (--spp)");
    if (!film.in_round() && film.items.begin != items.begin)
        throw FilmFileError(path + ": starts at work item " + std::to_string(film.items.begin) + ", this render at " +
                            std::to_string(items.begin));
    if (!film.in_round() && film.items.end > items.end)
        throw FilmFileError(path + ": holds " + std::to_string(film.max_samples()) +
                            " samples per pixel, more than the " + std::to_string(items.end / film.pixel_count()) +
                            " this render asks for (--spp, --samples)");
    if (squares && film.squares.empty())
        throw FilmFileError(path + ": has no sums of squares, which this render needs");
    if (!squares) film.squares.clear();
    return film;
}

// --adaptive's settings; squares kept for it and for --target-error.
AdaptiveSampling adaptive_sampling(const LongRunFlags& flags, const Scene& scene) {
    if (!flags.adaptive) return {};
    if (!flags.samples.empty())
        throw UsageError(
            "--adaptive: needs the whole render, not a --samples range (each pixel's samples depend on "
            "the others' decisions, so partial films could not be merged)");
    return {*flags.adaptive, adaptive_min_spp(std::uint64_t(scene.render.spp))};
}

// The mean samples per pixel and the fraction of pixels with fewer than `spp`.
void summarise_samples(const Film& film, int spp, RunSummary& summary) {
    const std::vector<std::uint64_t> counts = film.sample_counts();
    std::uint64_t total = 0, early = 0;
    for (std::uint64_t n : counts) {
        total += n;
        early += n < std::uint64_t(spp) ? 1 : 0;
    }
    summary.spp_mean = double(total) / double(counts.size());
    summary.stopped_early = double(early) / double(counts.size());
}

void write_output(const RenderCommand& command, const RenderIdentity& identity, const Film& film) {
    if (is_film_path(command.output_path))
        write_film_file(command.output_path, {identity, film});
    else
        write_image(film.image(), command.output_path);
}

// Every rank must render the same scene with the same settings: each loads
// its own copy of the scene and mesh files (one per machine, unless they
// share a filesystem), and takes the same decisions after each round (its
// flags were the same, unless mpirun was given one command line per rank).
void check_every_rank_renders(Ranks& ranks, const LongRunPlan& plan) {
    const RenderIdentity& identity = plan.identity;
    // The scene and the estimator first, whose differences have messages of their own.
    enum Fact : std::size_t { kScene, kEstimator, kOthers };
    const std::vector<std::uint64_t> mine{identity.scene,
                                          fnv1a64(identity.estimator.data(), identity.estimator.size()),
                                          identity.settings,
                                          plan.items.begin,
                                          plan.items.end,
                                          std::bit_cast<std::uint64_t>(plan.target_error),
                                          std::bit_cast<std::uint64_t>(plan.time_budget_s),
                                          std::bit_cast<std::uint64_t>(plan.checkpoint_every_s),
                                          plan.checkpoint_path.empty() ? 0u : 1u};
    const std::vector<std::uint64_t> all = ranks.gather(mine);
    on_every_rank(ranks, [&] {
        for (std::size_t at = mine.size(); at < all.size(); at += mine.size()) {
            const std::string rank = "rank " + std::to_string(at / mine.size());
            if (all[at + kScene] != all[kScene])
                throw SceneError(rank +
                                 " loaded another scene than rank 0 (their content differs): every machine "
                                 "needs the same scene and mesh files");
            if (all[at + kEstimator] != all[kEstimator])
                throw UsageError(rank +
                                 " renders with another estimator than rank 0 (another backend: --backend auto "
                                 "chooses per kind of device; give --backend)");
            if (!std::equal(all.begin() + std::ptrdiff_t(at + kOthers), all.begin() + std::ptrdiff_t(at + mine.size()),
                            all.begin() + kOthers))
                throw UsageError(rank + " was given other settings than rank 0");
        }
    });
}

// What SPPM cannot do (docs/long-renders.md, "SPPM"): its iterations are
// not independent samples (each starts from the last one's radii, and its
// photons' estimate is biased and correlated), so neither an error estimate
// from their spread nor a split of them over processes applies.
void check_sppm_flags(const LongRunFlags& flags, const Ranks& ranks) {
    const char* why = "sppm's iterations are not independent samples (each starts from the radii the last one left)";
    if (flags.target_error)
        throw UsageError(std::string("--target-error: does not apply to the sppm integrator: ") + why +
                         ", so their spread estimates no error; use --spp or --time");
    if (flags.adaptive)
        throw UsageError(std::string("--adaptive: does not apply to the sppm integrator: ") + why +
                         ", and every iteration's photons reach every pixel");
    if (!flags.samples.empty())
        throw UsageError(std::string("--samples: does not apply to the sppm integrator: ") + why +
                         ", so a range of them cannot be rendered apart and merged");
    if (ranks.size() > 1)
        throw UsageError(std::string("sppm runs in one process, not on ") + std::to_string(ranks.size()) +
                         " MPI ranks: " + why + ", so they cannot be split among ranks as path tracing's samples are");
}

struct PreparedRender {
    Scene scene;
    BackendOptions backend;
    LongRunPlan plan;
};

// The scene, the backend and the plan, checked on every rank before anything
// is rendered or written; the root checks the outputs and reads the
// checkpoint to resume.
PreparedRender prepare_render(const RenderCommand& command, Ranks& ranks) {
    PreparedRender prepared;
    Scene& scene = prepared.scene;
    LongRunPlan& plan = prepared.plan;
    on_every_rank(ranks, [&] {
        if (ranks.is_root()) check_outputs(command);
        ProgressReporter loading(choose_progress_style(command.quiet || !ranks.is_root()), std::cerr);
        scene = load_scene_file(command.scene_path, command.defines, command.mesh_import,
                                ranks.is_root() ? &std::cerr : nullptr, &loading);
        apply_overrides(command.overrides, scene);
        if (scene.render.integrator == Integrator::Sppm) check_sppm_flags(command.long_run, ranks);
        if (command.long_run.target_error && !command.long_run.samples.empty())
            throw UsageError("--target-error: needs the whole render, not a --samples range");
        plan.adaptive = adaptive_sampling(command.long_run, scene);
        prepared.backend = resolve_backend(command.backend, scene);
        prepared.backend.film_squares = command.long_run.target_error.has_value() || plan.adaptive.on();
        plan.items = planned_items(command.long_run.samples, scene);
        plan.identity = render_identity(scene, estimator_name(prepared.backend, scene), plan.adaptive);
    });
    const LongRunFlags& flags = command.long_run;
    plan.pixels = std::uint64_t(scene.camera.width) * scene.camera.height;
    plan.target_error = flags.target_error.value_or(0.0);
    plan.time_budget_s = flags.time_s.value_or(0.0);
    plan.checkpoint_path = flags.checkpoint;
    plan.checkpoint_every_s = flags.checkpoint_every_s;
    check_every_rank_renders(ranks, plan);
    on_every_rank(ranks, [&] {
        if (ranks.is_root() && !flags.resume.empty())
            plan.start = film_to_resume(flags.resume, plan.identity, scene, plan.items, prepared.backend.film_squares);
    });
    return prepared;
}

void report_run(const RenderCommand& command, const PreparedRender& prepared, const LongRunResult& result) {
    const Scene& scene = prepared.scene;
    const LongRunPlan& plan = prepared.plan;
    RunSummary summary;
    summary.backend = prepared.backend.name;
    summary.backend_choice = prepared.backend.chosen;
    summary.estimator = plan.identity.estimator;
    summary.output_path = command.output_path;
    summary.width = scene.camera.width;
    summary.height = scene.camera.height;
    summary.spp = scene.render.spp;
    summary.spp_min = result.film.min_samples();
    summary.spp_max = result.film.max_samples();
    summary.stopped = stop_reason_name(result.reason);
    summary.stats = result.stats;
    summary.error = result.error;
    summary.adaptive = plan.adaptive.on();
    if (summary.adaptive) summarise_samples(result.film, scene.render.spp, summary);
    summary.sppm = !result.film.photons.empty();
    if (summary.sppm) summary.radii = sppm_radii(result.film.photons);
    summary.samples_per_rank = result.samples_per_rank;
    summary.busy_s_per_rank = result.busy_s_per_rank;
    if (!command.stats_json_path.empty()) write_stats_json(summary, command.stats_json_path);
    if (!command.quiet) std::cerr << format_summary_line(summary) << std::endl;
    // Even with --quiet, as errors: the image is not what the defaults promise.
    if (const std::string warning = sppm_warning(summary); !warning.empty()) std::cerr << warning << std::endl;
}

}  // namespace

int run_render(const RenderCommand& command) {
    const std::unique_ptr<Ranks> ranks = join_ranks();
    PreparedRender prepared = prepare_render(command, *ranks);
    const LongRunPlan& plan = prepared.plan;
    StopSignals signals;
    prepared.plan.stop_requested = &signals.requested();

    // Only the root shows progress.
    ProgressReporter progress(choose_progress_style(command.quiet || !ranks->is_root()), std::cerr);
    progress.set_plan({double(plan.items.begin) / double(plan.pixels), double(plan.items.end) / double(plan.pixels),
                       plan.time_budget_s});
    LongRunResult result;
    or_end_the_job(*ranks, [&] {
        run_with_backend(
            prepared.scene, prepared.backend, progress.callback(), plan.items.size() / ranks->size(),
            [&](FilmRenderer& renderer) { result = run_long_render(renderer, plan, progress.callback(), *ranks); });
    });
    progress.finish();
    if (!ranks->is_root()) return kExitOk;

    write_output(command, plan.identity, result.film);
    report_run(command, prepared, result);
    return result.reason == StopReason::Interrupted ? kExitInterrupted : kExitOk;
}

}  // namespace wp::cli
