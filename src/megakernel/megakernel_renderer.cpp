#include "megakernel/megakernel_renderer.h"

#include <algorithm>
#include <stdexcept>

#include "interface/queues.h"
#include "opencl/device.h"
#include "opencl/film.h"
#include "opencl/kernel_arguments.h"
#include "opencl/kernel_options.h"
#include "opencl/lanes.h"
#include "opencl/launcher.h"
#include "opencl/program_cache.h"
#include "opencl/scene_upload.h"

namespace wp {
namespace {

// Samples per launch: enough work items to fill any device, few enough that
// the progress moves and the pass entries (12 bytes each) stay small.
constexpr std::uint64_t kPassSize = std::uint64_t(1) << 18;

// Work items to launch for `size` (a pass's, over the lanes): the next power
// of two (items past the pass return), so that adaptive sampling's rounds of every size
// reuse a few launch sizes, each of which PoCL compiles the kernel for.
std::size_t launch_size(std::uint64_t size) {
    std::size_t items = 1;
    while (items < size) items *= 2;
    return items;
}

NonfiniteCounts nonfinite_counts(const std::vector<std::uint32_t>& counts) {
    NonfiniteCounts by_stage{};
    for (std::size_t i = 0; i < by_stage.size(); ++i) by_stage[i] = counts[WP_COUNTER_NONFINITE_EMISSION + i];
    return by_stage;
}

class MegakernelFilmRenderer : public FilmRenderer {
 public:
    MegakernelFilmRenderer(const Scene& scene, const MegakernelOptions& options, const Progress& progress,
                           MegakernelReport* report)
        : device_(choose_device(options.device)),
          context_(device_.device),
          queue_(context_, device_.device,
                 options.profile ? cl_command_queue_properties(CL_QUEUE_PROFILING_ENABLE) : 0),
          launcher_(queue_, options.profile),
          source_(megakernel_program(scene, options, device_)),
          lanes_(source_.lanes),
          program_(build_program(context_, device_, source_.files, source_.options, progress)),
          scene_(context_, flatten_scene(scene)),
          pass_radiance_(context_, CL_MEM_READ_WRITE, sizeof(float) * 3 * kPassSize),
          counts_(context_, CL_MEM_READ_WRITE, sizeof(std::uint32_t) * WP_COUNTS_SIZE),
          film_(context_, queue_, program_.program, scene.camera.width, scene.camera.height, options.film_squares),
          megakernel_(program_.program, "megakernel"),
          profile_(options.profile),
          report_(report ? *report : local_report_) {
        queue_.enqueueFillBuffer(counts_, std::uint32_t(0), 0, sizeof(std::uint32_t) * WP_COUNTS_SIZE);
        scene_.bind(megakernel_);
        megakernel_.setArg(arg::Megakernel::pass_radiance, pass_radiance_);
        megakernel_.setArg(arg::Megakernel::counts, counts_);
        bind_round();
        report_.device = device_.name + " (" + device_.platform + ")";
        report_.build_options = program_.options;
        report_.cache_hit = program_.cache_hit;
        report_.build_seconds = program_.build_seconds;
        report_.cache_file = program_.cache_file;
        report_.lanes = lanes_;
    }

    std::uint64_t pass_items() const override { return kPassSize; }
    RenderStats stats() const override { return stats_; }

    void finish(double render_seconds) override {
        if (!profile_) return;
        MegakernelReport& r = report_;
        launcher_.time_finished(r.profile);
        r.profile.kernel("megakernel").items = samples_;
        r.profile.kernel("accumulate").items = samples_;
        r.profile.render_s = render_seconds;
        r.profile.build_s = r.build_seconds;
    }

 protected:
    void render_items(const ItemRange& items, const Progress& progress) override {
        for (std::uint64_t start = items.begin; start < items.end; start += kPassSize) {
            auto size = static_cast<std::uint32_t>(std::min(kPassSize, items.end - start));
            megakernel_.setArg(arg::Megakernel::pass_start, cl_ulong(start));
            megakernel_.setArg(arg::Megakernel::pass_size, cl_uint(size));
            launcher_.launch(megakernel_, "megakernel",
                             launch_size(divide_rounding_up(size, lanes_ * WP_MEGAKERNEL_PATHS_PER_LANE(lanes_))));
            film_.accumulate(launcher_, start, size, pass_radiance_);
            // 32-bit device counters: read and cleared every pass.
            std::vector<std::uint32_t> figures(WP_COUNTS_SIZE);
            queue_.enqueueReadBuffer(counts_, CL_TRUE, 0, sizeof(std::uint32_t) * figures.size(), figures.data());
            queue_.enqueueFillBuffer(counts_, std::uint32_t(0), 0, sizeof(std::uint32_t) * WP_COUNTS_SIZE);
            launcher_.time_finished(report_.profile);
            stats_.extension_rays += figures[WP_COUNTER_EXTENSION_RAYS];
            stats_.shadow_rays += figures[WP_COUNTER_SHADOW_RAYS];
            stats_.add_nonfinite(nonfinite_counts(figures));
            samples_ += size;
            progress.report(double(start + size - items.begin) / double(items.size()));
        }
    }
    Film read_film(const ItemRange& items) override { return film_.read(queue_, items); }
    void load_film(const Film& film) override { film_.load(queue_, film); }
    void use_round_pixels(const std::vector<std::uint32_t>& pixels) override {
        film_.set_round_pixels(queue_, pixels);
        bind_round();
    }

 private:
    void bind_round() {
        film_.bind_round(megakernel_, arg::Megakernel::round_pixels, arg::Megakernel::round_pixel_count);
    }

    DeviceInfo device_;
    cl::Context context_;
    cl::CommandQueue queue_;
    KernelLauncher launcher_;
    KernelProgram source_;
    unsigned lanes_;
    BuiltProgram program_;
    DeviceScene scene_;
    cl::Buffer pass_radiance_, counts_;
    DeviceFilm film_;
    cl::Kernel megakernel_;
    bool profile_;
    MegakernelReport local_report_;
    MegakernelReport& report_;
    RenderStats stats_;
    std::uint64_t samples_ = 0;
};

}  // namespace

std::string MegakernelReport::explain() const {
    return "device: " + device + "\n" + explain_build(build_options, cache_hit, build_seconds, cache_file) +
           "megakernel: " + std::to_string(lanes) + (lanes == 1 ? " path" : " paths") + " per work item\n";
}

KernelProgram megakernel_program(const Scene& scene, const MegakernelOptions& options, const DeviceInfo& device) {
    if (scene.render.integrator == Integrator::Sppm)
        throw std::invalid_argument("the megakernel traces camera paths only, not the sppm integrator's photons");
    KernelProgram program;
    program.files = {"megakernel.cl", "accumulate.cl"};
    program.lanes = resolve_lanes(options.lanes, LaneProgram::megakernel(scene.features().meshes), device);
    program.options = program_build_options(scene, scene.features(), options.film_squares, "", program.lanes);
    return program;
}

std::unique_ptr<FilmRenderer> make_megakernel_renderer(const Scene& scene, const MegakernelOptions& options,
                                                       const Progress& progress, MegakernelReport* report) {
    return std::make_unique<MegakernelFilmRenderer>(scene, options, progress, report);
}

RenderResult render_megakernel(const Scene& scene, const MegakernelOptions& options, const Progress& progress,
                               MegakernelReport* report) {
    std::unique_ptr<FilmRenderer> renderer = make_megakernel_renderer(scene, options, progress, report);
    return render_every_item(*renderer, scene.camera.width, scene.camera.height, scene.render.spp, progress);
}

}  // namespace wp
