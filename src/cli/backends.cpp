#include "cli/backends.h"

#include <algorithm>
#include <array>
#include <iostream>
#include <map>

#include "cli/errors.h"
#include "cli/flag_checks.h"
#include "megakernel/megakernel_renderer.h"
#include "opencl/device.h"
#include "opencl/lanes.h"
#include "opencl/program_cache.h"
#include "reference/reference_renderer.h"
#include "wavefront/intersector_choice.h"
#include "wavefront/wavefront_renderer.h"

namespace wp::cli {

namespace {

constexpr int kMaxThreads = 4096;
constexpr std::int64_t kMaxWavefront = std::int64_t(1) << 26;

using RunFn = void (*)(const Scene&, const BackendOptions&, const Progress&, std::uint64_t, const FilmRun&);

struct Backend {
    const char* name;
    const char* description;
    RunFn run;
};

bool wants_profile(const BackendOptions& options) { return options.profile || !options.profile_json.empty(); }

// The reference's intersector: the one asked for, else the fastest in its precision.
Intersector reference_intersector(const BackendOptions& options) {
    if (options.intersector.empty()) return fastest_reference_intersector(options.precision == "double");
    return options.intersector == "embree" ? Intersector::Embree : Intersector::Bvh;
}

void run_on_reference(const Scene& scene, const BackendOptions& options, const Progress&, std::uint64_t,
                      const FilmRun& run) {
    if (wants_profile(options))
        throw UsageError("--profile/--profile-json: the reference backend has no kernels to profile");
    ReferenceOptions reference{options.threads, options.precision == "double", options.film_squares,
                               reference_intersector(options)};
    if (reference.double_precision && reference.intersector == Intersector::Embree)
        throw UsageError(
            "--intersector embree: Embree traces in float only; use --precision float or --intersector bvh");
    std::unique_ptr<FilmRenderer> renderer = make_reference_renderer(scene, reference);
    run(*renderer);
}

// The megakernel traces with its OpenCL BVH only.
void check_megakernel_intersector(const BackendOptions& options) {
    if (options.intersector == "embree")
        throw UsageError(
            "--intersector embree: the megakernel traces with its OpenCL BVH; the wavefront and the reference trace "
            "with Embree");
}

// The wavefront's intersector: the one asked for, else default_intersector's for the device and scene.
std::optional<Intersector> wavefront_intersector(const BackendOptions& options) {
    if (options.intersector.empty()) return std::nullopt;
    return options.intersector == "embree" ? Intersector::Embree : Intersector::Bvh;
}

// Runs an OpenCL backend: a kernel that fails to build shows the compiler's
// log before the one-line error; the profile is printed and written as asked.
template <class Report, class Make>
void run_on_opencl(const BackendOptions& options, const FilmRun& run, Make make) {
    Report report;
    try {
        std::unique_ptr<FilmRenderer> renderer = make(report);
        run(*renderer);
        if (options.profile) std::cerr << format_profile_table(report.profile) << std::flush;
        if (!options.profile_json.empty()) write_profile_json(report.profile, options.profile_json);
    } catch (const KernelBuildError& error) {
        std::cerr << error.log() << std::endl;
        throw;
    }
}

void run_on_wavefront(const Scene& scene, const BackendOptions& options, const Progress& progress,
                      std::uint64_t max_items, const FilmRun& run) {
    if (options.lanes != 0)
        if (std::string problem =
                lanes_problem(options.lanes, wavefront_lanes(options.compaction, scene.features().meshes));
            !problem.empty())
            throw UsageError(problem);
    const WavefrontOptions wavefront{.device = options.device,
                                     .wavefront = options.wavefront,
                                     .profile = wants_profile(options),
                                     .compaction = options.compaction,
                                     .lanes = options.lanes,
                                     .film_squares = options.film_squares,
                                     .intersector = wavefront_intersector(options)};
    if (scene.render.integrator == Integrator::Sppm && wavefront.intersector == Intersector::Embree)
        throw UsageError(
            "--intersector embree: the sppm integrator's photon stages trace on the device; use --intersector bvh");
    run_on_opencl<WavefrontReport>(options, run, [&](WavefrontReport& report) {
        std::unique_ptr<FilmRenderer> renderer =
            make_wavefront_renderer(scene, wavefront, progress, &report, max_items);
        if (options.explain) std::cout << report.explain() << std::flush;
        return renderer;
    });
}

void run_on_megakernel(const Scene& scene, const BackendOptions& options, const Progress& progress, std::uint64_t,
                       const FilmRun& run) {
    check_megakernel_intersector(options);
    if (scene.render.integrator == Integrator::Sppm)
        throw UsageError(
            "--backend megakernel: traces camera paths only; the sppm integrator runs on the wavefront and reference "
            "backends (its photon pass needs every pixel's visible point first: docs/architecture.md)");
    if (options.lanes != 0)
        if (std::string problem = lanes_problem(options.lanes, LaneProgram::megakernel(scene.features().meshes));
            !problem.empty())
            throw UsageError(problem);
    run_on_opencl<MegakernelReport>(options, run, [&](MegakernelReport& report) {
        std::unique_ptr<FilmRenderer> renderer = make_megakernel_renderer(
            scene, {options.device, wants_profile(options), options.film_squares, options.lanes}, progress, &report);
        if (options.explain) std::cout << report.explain() << std::flush;
        return renderer;
    });
}

constexpr std::array<Backend, 3> kBackends{{
    {"wavefront", "OpenCL wavefront path tracer", run_on_wavefront},
    {"megakernel", "OpenCL megakernel baseline: one work item traces a whole path", run_on_megakernel},
    {"reference", "scalar C++ path tracer on the CPU threads", run_on_reference},
}};

constexpr const char* kAuto = "auto";

std::string backend_help() {
    std::string help = std::string("Renderer: ") + kAuto +
                       " (the default: the fastest for the device and the scene by the bench's figures, among "
                       "the backends that take every flag given; --explain and the summary line say which and why)";
    for (const Backend& backend : kBackends)
        help += std::string(", ") + backend.name + " (" + backend.description + ")";
    return help;
}

// --explain's first line: "backend: megakernel (auto: CPU device, no meshes: ...)".
std::string explain_backend(const BackendOptions& options) {
    return "backend: " + options.name + " (" + (options.chosen ? explain_choice(*options.chosen) : "--backend") + ")\n";
}

// For --backend auto, which chooses among the backends that take every flag given.
const std::vector<std::string> kWavefrontOnly{"wavefront"}, kOpenClOnly{"wavefront", "megakernel"},
    kReferenceOnly{"reference"}, kEmbreeTracers{"wavefront", "reference"}, kSppmIntegrators{"wavefront", "reference"};

void note_limiting_flag(BackendOptions& options, const std::string& flag, const std::vector<std::string>& backends) {
    std::vector<LimitingFlag>& given = options.limiting_flags;
    if (std::none_of(given.begin(), given.end(), [&](const LimitingFlag& f) { return f.flag == flag; }))
        given.push_back({flag, backends});
}

// `option` given on the command line narrows auto's choice to `backends`.
CLI::Option* taken_only_by(CLI::Option* option, BackendOptions& options, const std::vector<std::string>& backends) {
    return option->each([&options, &backends, flag = option->get_name()](const std::string&) {
        note_limiting_flag(options, flag, backends);
    });
}

}  // namespace

std::vector<std::string> backend_names() {
    std::vector<std::string> names;
    for (const Backend& backend : kBackends) names.emplace_back(backend.name);
    return names;
}

void add_backend_options(CLI::App& render, BackendOptions& options) {
    std::vector<std::string> names = backend_names();
    names.insert(names.begin(), kAuto);
    render.add_option("--backend", options.name, backend_help())->check(CLI::IsMember(names))->capture_default_str();
    taken_only_by(render.add_option("--threads", options.threads, "CPU threads for the reference backend (0: all)"),
                  options, kReferenceOnly)
        ->check(integer_in(0, kMaxThreads))
        ->capture_default_str();
    taken_only_by(render.add_option("--precision", options.precision, "Arithmetic of the reference backend"), options,
                  kReferenceOnly)
        ->check(CLI::IsMember({"float", "double"}))
        ->capture_default_str();
    render
        .add_option("--intersector", options.intersector,
                    "What traces the rays: embree (Embree finds the shapes, our own watertight tests the distances; on "
                    "the host: the reference in float, the wavefront on CPU devices) or bvh (our BVH). Default: the "
                    "fastest the backend has: embree for the reference in float; for the wavefront embree on a CPU "
                    "device for scenes with meshes, bvh otherwise (--explain says which and why); bvh for the "
                    "megakernel")
        ->check(CLI::IsMember({"embree", "bvh"}))
        ->each([&options](const std::string& intersector) {
            if (intersector == "embree") note_limiting_flag(options, "--intersector embree", kEmbreeTracers);
        });
    taken_only_by(
        render.add_option("--wavefront", options.wavefront, "Paths in flight for the wavefront backend (0: automatic)"),
        options, kWavefrontOnly)
        ->check(integer_in(0, kMaxWavefront))
        ->capture_default_str();
    render.add_option("--device", options.device,
                      "OpenCL device for the OpenCL backends: index or name substring (see `wavepath devices`)");
    render.add_flag("--explain", options.explain,
                    "Print the backend and why it was chosen, then the OpenCL backends' device, build options and "
                    "program cache hit or miss, and the wavefront's feature set and state size");
    taken_only_by(render.add_option("--compaction", options.compaction,
                                    "How the wavefront fills its queues: atomic (pushes aggregated per work group) "
                                    "or scan (stable prefix sum)"),
                  options, kWavefrontOnly)
        ->transform(CLI::CheckedTransformer(
            std::map<std::string, Compaction>{{"atomic", Compaction::Atomic}, {"scan", Compaction::Scan}}))
        ->default_str(kDefaultCompaction == Compaction::Scan ? "scan" : "atomic");
    taken_only_by(render.add_option(
                      "--lanes", options.lanes,
                      "Paths per work item in the wavefront's stage kernels and in the megakernel, as vector code: 1, "
                      "4, 8 or 16 (more than 1 needs --compaction scan on the wavefront; 0: the measured default: 8 "
                      "on CPU devices, 16 in the megakernel without meshes where the preferred float vector holds 16, "
                      "1 on others and in the megakernel for meshes; bench/run.py --series lanes measures them; "
                      "opencl/lanes.cpp)"),
                  options, kOpenClOnly)
        ->check(CLI::IsMember({0u, 1u, 4u, 8u, 16u}))
        ->capture_default_str();
    taken_only_by(
        render.add_flag(
            "--profile", options.profile,
            "Print the OpenCL backend's per-kernel profile (launches, items, device time, "
            "items/s; a wavefront stage's declared bytes/item and GB/s against the copy bandwidth) on stderr"),
        options, kOpenClOnly);
    taken_only_by(render.add_option("--profile-json", options.profile_json,
                                    "Also write the OpenCL backend's profile to this JSON file"),
                  options, kOpenClOnly);
}

BackendOptions resolve_backend(const BackendOptions& options, const Scene& scene) {
    BackendOptions resolved = options;
    if (options.name != kAuto) return resolved;
    // The megakernel traces camera paths only (run_on_megakernel), so the sppm integrator narrows the choice
    // as a flag would, whether the scene or --integrator asked for it; the wavefront runs it with our BVH
    // only (its host tracing is refused), so not where it is ranked with Embree.
    std::vector<LimitingFlag> flags = options.limiting_flags;
    if (scene.render.integrator == Integrator::Sppm)
        flags.push_back({"the sppm integrator", kSppmIntegrators, {"wavefront"}});
    try {
        resolved.chosen = choose_backend(situation_of(choose_device(options.device), scene), flags);
    } catch (const NoBackendTakesTheFlags& error) {
        throw UsageError(error.what());
    }
    resolved.name = resolved.chosen->backend;
    return resolved;
}

std::string estimator_name(const BackendOptions& options, const Scene& scene) {
    // Embree and the BVH differ in which of two shapes at (nearly) one distance a ray hits, so in a few bits.
    // Embree traces in float only, so "reference-embree" says the precision too (and fits a film file's
    // 16 bytes, longrun/film_file.h).
    if (options.name == "reference")
        return reference_intersector(options) == Intersector::Embree ? "reference-embree"
                                                                     : "reference-" + options.precision;
    if (options.name == "wavefront") {
        std::optional<Intersector> asked = wavefront_intersector(options);
        Intersector intersector =
            asked ? *asked : default_intersector(choose_device(options.device), scene.features()).intersector;
        if (intersector == Intersector::Embree) return "opencl-embree";
    }
    return "opencl";
}

void run_with_backend(const Scene& scene, const BackendOptions& options, const Progress& progress,
                      std::uint64_t max_items, const FilmRun& run) {
    const auto backend = std::find_if(kBackends.begin(), kBackends.end(),
                                      [&](const Backend& candidate) { return options.name == candidate.name; });
    if (backend == kBackends.end()) throw UsageError("--backend: unknown backend '" + options.name + "'");
    if (options.explain) std::cout << explain_backend(options) << std::flush;
    backend->run(scene, options, progress, max_items, run);
}

}  // namespace wp::cli
