#include "wavefront/wavefront_renderer.h"

#include <algorithm>
#include <chrono>
#include <sstream>
#include <stdexcept>

#include "opencl/device.h"
#include "opencl/film.h"
#include "opencl/kernel_options.h"
#include "wavefront/intersector_choice.h"
#include "wavefront/pipeline.h"
#include "wavefront/scheduler.h"
#include "wavefront/stage.h"

namespace wp {
namespace {

// Work items per pass, as a multiple of the wavefront: a pass drains (its
// last paths run with the wavefront partly empty) before accumulation, so
// longer passes waste less; each item costs 12 bytes of pass radiance.
constexpr std::size_t kPassesPerWavefront = 16;

// Rays of the intersect bound (--profile): enough that launch overhead is
// negligible, and the same for every image size.
constexpr std::uint32_t kIntersectBoundRays = 1u << 20;

// Bytes of the copy bandwidth's buffers (--profile): more than the last-level
// caches of the CPUs and GPUs it runs on, so that the copy goes through memory.
constexpr std::uint64_t kCopyBandwidthBytes = std::uint64_t(256) << 20;

// The scene's features plus every shape, material and light type: what an
// unspecialised build compiles (lights and background stay as in the scene,
// since next-event estimation needs at least one light).
FeatureSet every_shape_and_material(FeatureSet f) {
    f.spheres = f.planes = f.quads = true;
    f.diffuse = f.mirror = f.glass = f.emitter_material = f.conductor = f.rough_conductor = true;
    f.rough_dielectric = f.thin_dielectric = f.plastic = f.rough_plastic = true;
    f.sphere_lights = f.quad_lights = true;
    return f;
}

// The intersector asked for, or the device's default for the scene; with why.
// Throws DeviceError for Embree on a device that is not a CPU.
IntersectorChoice choose_intersector(const WavefrontOptions& options, const DeviceInfo& device,
                                     const FeatureSet& features) {
    if (!options.intersector) return default_intersector(device, features);
    if (*options.intersector == Intersector::Embree && device.type != "CPU")
        throw DeviceError("--intersector embree: Embree traces on the host, which needs a CPU device; " + device.name +
                          " is a " + device.type);
    if (*options.intersector == Intersector::Embree && features.sppm)
        throw std::invalid_argument(
            "--intersector embree: the sppm integrator's photon stages trace on the device; use --intersector bvh");
    return {*options.intersector, "asked for"};
}

// The kernels' features: the scene's (or every shape's), whether the host
// traces, whether the shadow rays have a stage of their own, and whether one
// kernel traces and shades.
FeatureSet kernel_features(const Scene& scene, const WavefrontOptions& options, Intersector intersector,
                           const DeviceInfo& device) {
    FeatureSet f = options.specialise ? scene.features() : every_shape_and_material(scene.features());
    f.host_traced = intersector == Intersector::Embree;
    f.shadow_stage = options.shadow_stage.value_or(f.host_traced || device.type != "CPU");
    if (f.host_traced && !f.shadow_stage)
        throw std::invalid_argument("shadow rays the host traces need their own stage (intersect_shadow)");
    const bool scan = options.compaction == Compaction::Scan;
    f.intersect_and_shade = options.intersect_and_shade.value_or(scan && device.type == "CPU");
    if (f.intersect_and_shade && !scan)
        throw std::invalid_argument("intersect_and_shade pushes to the queue it takes, which needs --compaction scan");
    return f;
}

PipelineOptions pipeline_options(const WavefrontOptions& options, const Progress& progress) {
    return {options.profile, options.compaction, options.lanes, progress, options.film_squares};
}

// Items each kernel processed: a stage's, the entries it took from its
// queue summed over the iterations (generate: the free slots it filled);
// accumulate's, the pass entries it summed; compaction's, the slots its
// launches went through; compact_scan's, the blocks of slots it summed;
// count_depths', the rays it counted. A stage kernel's row also gets the
// bytes per item its declaration gives for the kernels' features.
void fill_profile(RenderProfile& profile, const std::vector<IterationRecord>& iterations, std::uint64_t samples,
                  std::size_t wavefront, const FeatureSet& features) {
    for (const char* name : {"compact_count", "compact_write"})
        if (profile.has_kernel(name)) profile.kernel(name).items = profile.kernel(name).launches * wavefront;
    if (profile.has_kernel("compact_scan"))
        profile.kernel("compact_scan").items =
            profile.kernel("compact_scan").launches * divide_rounding_up(wavefront, WP_COMPACT_BLOCK);
    if (profile.has_kernel("count_depths")) {
        KernelProfile& k = profile.kernel("count_depths");
        k.items = 0;
        for (const IterationRecord& r : iterations) k.items += r.traced + r.shadow;
    }
    for (const StageDeclaration& stage : stage_declarations) {
        for (const std::string& row : {std::string(stage.kernel), host_trace_row(stage)}) {
            if (!profile.has_kernel(row)) continue;
            KernelProfile& k = profile.kernel(row);
            k.items = 0;
            for (const IterationRecord& r : iterations) k.items += r.taken_from(stage.consumes);
        }
        if (profile.has_kernel(stage.kernel))
            profile.kernel(stage.kernel).bytes_per_item = stage_bytes_per_item(stage, features).total();
    }
    profile.kernel("accumulate").items = samples;
    profile.iterations = iterations.size();
}

}  // namespace

std::uint32_t IterationRecord::taken_from(std::uint32_t queue) const {
    const bool photons = loop == StageLoop::PHOTON;
    switch (queue) {
        case WP_QUEUE_FREE:
            return photons ? 0 : generated;
        case WP_QUEUE_RAY:
            return photons ? 0 : traced;
        case WP_QUEUE_HIT:
            return photons ? 0 : hits;
        case WP_QUEUE_SHADOW:
            return photons ? 0 : shadow;
        case WP_QUEUE_PHOTON_FREE:
            return photons ? generated : 0;
        case WP_QUEUE_PHOTON_RAY:
            return photons ? traced : 0;
        case WP_QUEUE_PHOTON_HIT:
            return photons ? hits : 0;
    }
    return 0;
}

std::size_t default_wavefront_size(std::uint64_t work_items, std::size_t bytes_per_path, const DeviceInfo& device) {
    // On a CPU the state should stay near the caches: fewer paths in flight
    // rendered faster on PoCL (bench/results/defaults.md); GPUs need many.
    std::size_t most = device.type == "CPU" ? std::size_t(1) << 16 : std::size_t(1) << 20;
    constexpr std::size_t kGroup = WP_GROUP_SIZE;
    // State, five queue entries and the pass entries of each path slot.
    std::size_t bytes_per_slot = bytes_per_path + WP_QUEUE_COUNT * 4 + kPassesPerWavefront * 12;
    std::size_t by_memory = std::size_t(device.global_memory_bytes / 4 / bytes_per_slot);
    std::size_t size = std::min<std::uint64_t>({most, work_items, by_memory});
    return std::max(kGroup, round_up(size, kGroup));
}

std::string WavefrontReport::explain() const {
    std::ostringstream out;
    out << "device: " << device << "\n"
        << "features: " << features << "\n"
        << explain_build(build_options, cache_hit, build_seconds, cache_file) << "wavefront: " << wavefront
        << " paths in flight, passes of up to " << pass_capacity << " samples, " << lanes
        << (lanes == 1 ? " path" : " paths") << " per work item in the stage kernels\n"
        << "path state: " << state_bytes_per_path << " bytes per path, " << state_bytes_per_path * wavefront / 1024
        << " KiB in all\n";
    if (!meshes.empty()) out << "meshes: " << meshes << "\n";
    if (!textures.empty()) out << "textures: " << textures << "\n";
    out << "intersector: " << intersector_name(intersector) << " (" << intersector_reason << ")\n";
    return out.str();
}

namespace {

class WavefrontFilmRenderer : public FilmRenderer {
 public:
    WavefrontFilmRenderer(const Scene& scene, const WavefrontOptions& options, const Progress& progress,
                          WavefrontReport* report, std::uint64_t max_items)
        : device_(choose_device(options.device)),
          intersector_(choose_intersector(options, device_, scene.features())),
          features_(kernel_features(scene, options, intersector_.intersector, device_)),
          wavefront_(options.wavefront
                         ? options.wavefront
                         : default_wavefront_size(max_items, PathState::bytes_per_path(features_), device_)),
          pipeline_(scene, device_, wavefront_, std::min<std::uint64_t>(max_items, kPassesPerWavefront * wavefront_),
                    features_, pipeline_options(options, progress)),
          profile_(options.profile),
          report_(report ? *report : local_report_),
          photons_per_iteration_(sppm_photons(scene)),
          pixels_(scene.render.integrator == Integrator::Sppm
                      ? std::uint64_t(scene.camera.width) * std::uint64_t(scene.camera.height)
                      : 0) {
        WavefrontReport& r = report_;
        r.device = device_.name + " (" + device_.platform + ")";
        r.features = describe_features(features_);
        r.build_options = pipeline_.program().options;
        r.cache_hit = pipeline_.program().cache_hit;
        r.build_seconds = pipeline_.program().build_seconds;
        r.cache_file = pipeline_.program().cache_file;
        r.lanes = pipeline_.lanes();
        r.wavefront = wavefront_;
        r.pass_capacity = pipeline_.pass_capacity();
        r.state_bytes_per_path = pipeline_.state().bytes_per_path();
        r.meshes = pipeline_.device_scene().meshes().describe();
        r.textures = pipeline_.device_scene().textures();
        r.intersector = intersector_.intersector;
        r.intersector_reason = intersector_.reason;
    }

    // SPPM: an iteration (its camera pass may take several of the pipeline's passes).
    std::uint64_t pass_items() const override { return pixels_ != 0 ? pixels_ : pipeline_.pass_capacity(); }

    RenderStats stats() const override {
        RenderStats stats;
        stats.extension_rays = totals_.extension_rays;
        stats.shadow_rays = totals_.shadow_rays;
        stats.photons = totals_.photons;
        stats.photon_rays = totals_.photon_rays;
        stats.photon_deposits = totals_.photon_deposits;
        stats.add_nonfinite(totals_.nonfinite);
        return stats;
    }

    void finish(double render_seconds) override {
        if (!profile_) return;
        WavefrontReport& r = report_;
        r.profile = pipeline_.profile();
        fill_profile(r.profile, r.iterations, samples_, wavefront_, features_);
        r.profile.render_s = render_seconds;
        r.profile.build_s = r.build_seconds;
        pipeline_.read_rays_by_depth(r.profile);
        // The bound is the kernels' tracing: not what a host-traced render traces with.
        if (!features_.host_traced)
            r.profile.intersect_bound_rays_per_s = pipeline_.measure_intersect_bound(kIntersectBoundRays).rays_per_s;
        const CopyBandwidth copy = pipeline_.measure_copy_bandwidth(kCopyBandwidthBytes);
        r.profile.copy_bytes_per_s = copy.bytes_per_s;
        r.profile.copy_buffer_bytes = copy.bytes;
    }

 protected:
    void render_items(const ItemRange& items, const Progress& progress) override {
        if (pipeline_.sppm())
            render_sppm_iterations(items, progress);
        else
            run_schedule(pipeline_, items, progress, totals_, report_.iterations);
        samples_ += items.size();
    }
    Film read_film(const ItemRange& items) override {
        Film film = pipeline_.read_film(items);
        if (SppmPass* sppm = pipeline_.sppm()) film.photons = sppm->read(photons_per_iteration_);
        return film;
    }
    void load_film(const Film& film) override {
        if (SppmPass* sppm = pipeline_.sppm()) {
            if (film.photons.photons_per_iteration != photons_per_iteration_)
                throw std::invalid_argument("sppm: a film without this render's photons per iteration");
            sppm->load(film.photons);
        }
        pipeline_.load_film(film);
    }
    void use_round_pixels(const std::vector<std::uint32_t>& pixels) override {
        if (pipeline_.sppm() && !pixels.empty())
            throw std::invalid_argument("sppm: every iteration renders every pixel");
        pipeline_.set_round_pixels(pixels);
    }

 private:
    DeviceInfo device_;
    IntersectorChoice intersector_;
    FeatureSet features_;
    std::size_t wavefront_;
    Pipeline pipeline_;
    bool profile_;
    WavefrontReport local_report_;
    WavefrontReport& report_;
    // SPPM: whole iterations (every pixel's sample i is iteration i).
    void render_sppm_iterations(const ItemRange& items, const Progress& progress) {
        const std::uint64_t pixels = pixels_;
        if (items.begin % pixels != 0 || items.end % pixels != 0)
            throw std::invalid_argument("sppm: work items must be whole iterations (every pixel's next sample)");
        const std::uint64_t first = items.begin / pixels, end = items.end / pixels;
        for (std::uint64_t iteration = first; iteration < end; ++iteration) {
            Progress within;  // the camera pass's share of the iteration stands for it
            if (progress.samples)
                within.samples = [&](double f) {
                    progress.report((double(iteration - first) + f) / double(end - first));
                };
            run_sppm_iteration(pipeline_, static_cast<std::uint32_t>(iteration), within, totals_, report_.iterations);
        }
    }

    ScheduleTotals totals_;
    std::uint64_t samples_ = 0;
    std::uint64_t photons_per_iteration_;  // SPPM (the film's PhotonEstimate)
    std::uint64_t pixels_;                 // SPPM: the work items of an iteration; 0 for path tracing
};

}  // namespace

KernelProgram wavefront_program(const Scene& scene, const WavefrontOptions& options, const DeviceInfo& device) {
    const Intersector intersector = choose_intersector(options, device, scene.features()).intersector;
    return pipeline_program(scene, device, kernel_features(scene, options, intersector, device),
                            pipeline_options(options, {}));
}

std::unique_ptr<FilmRenderer> make_wavefront_renderer(const Scene& scene, const WavefrontOptions& options,
                                                      const Progress& progress, WavefrontReport* report,
                                                      std::uint64_t max_items) {
    const std::uint64_t every_item = std::uint64_t(scene.camera.width) * scene.camera.height * scene.render.spp;
    std::uint64_t items = max_items ? max_items : every_item;
    // SPPM's photon pass goes through the same slots: an iteration's photons size them too.
    if (scene.render.integrator == Integrator::Sppm) items = std::max(items, sppm_photons(scene));
    return std::make_unique<WavefrontFilmRenderer>(scene, options, progress, report, items);
}

RenderResult render_wavefront(const Scene& scene, const WavefrontOptions& options, const Progress& progress,
                              WavefrontReport* report) {
    std::unique_ptr<FilmRenderer> renderer = make_wavefront_renderer(scene, options, progress, report);
    return render_every_item(*renderer, scene.camera.width, scene.camera.height, scene.render.spp, progress);
}

}  // namespace wp
