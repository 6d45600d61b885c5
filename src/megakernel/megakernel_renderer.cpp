#include "megakernel/megakernel_renderer.h"

#include <algorithm>
#include <chrono>

#include "interface/queues.h"
#include "opencl/device.h"
#include "opencl/film.h"
#include "opencl/kernel_arguments.h"
#include "opencl/kernel_options.h"
#include "opencl/launcher.h"
#include "opencl/program_cache.h"
#include "opencl/scene_upload.h"

namespace wp {
namespace {

// Samples per launch: enough work items to fill any device, few enough that
// the progress moves and the pass entries (12 bytes each) stay small.
constexpr std::uint64_t kPassSize = std::uint64_t(1) << 18;

NonfiniteCounts nonfinite_counts(const std::vector<std::uint32_t>& counts) {
    NonfiniteCounts by_stage{};
    for (std::size_t i = 0; i < by_stage.size(); ++i) by_stage[i] = counts[WP_COUNTER_NONFINITE_EMISSION + i];
    return by_stage;
}

}  // namespace

RenderResult render_megakernel(const Scene& scene, const MegakernelOptions& options, const Progress& progress,
                               MegakernelReport* report) {
    DeviceInfo device = choose_device(options.device);
    cl::Context context(device.device);
    cl::CommandQueue queue(context, device.device,
                           options.profile ? cl_command_queue_properties(CL_QUEUE_PROFILING_ENABLE) : 0);
    KernelLauncher launcher(queue, options.profile);
    BuiltProgram program = build_program(
        context, device, {"megakernel.cl", "accumulate.cl"},
        kernel_build_options(scene.features(), device.fp64, scene.render.hemisphere) + shape_count_options(scene),
        progress);
    DeviceScene device_scene(context, flatten_scene(scene));
    const Camera& camera = scene.camera;
    std::size_t pixel_count = std::size_t(camera.width) * camera.height;
    std::uint64_t total = std::uint64_t(pixel_count) * scene.render.spp;
    std::uint64_t pass_capacity = std::min(total, kPassSize);
    cl::Buffer pass_radiance(context, CL_MEM_READ_WRITE, sizeof(float) * 3 * pass_capacity);
    cl::Buffer counts(context, CL_MEM_READ_WRITE, sizeof(std::uint32_t) * WP_COUNTS_SIZE);
    queue.enqueueFillBuffer(counts, std::uint32_t(0), 0, sizeof(std::uint32_t) * WP_COUNTS_SIZE);
    Film film(context, queue, program.program, pixel_count, scene.render.spp, device.fp64);

    cl::Kernel megakernel(program.program, "megakernel");
    device_scene.bind(megakernel);
    megakernel.setArg(arg::Megakernel::pass_radiance, pass_radiance);
    megakernel.setArg(arg::Megakernel::counts, counts);

    MegakernelReport local_report;
    MegakernelReport& r = report ? *report : local_report;
    r.device = device.name + " (" + device.platform + ")";
    r.build_options = program.options;
    r.cache_hit = program.cache_hit;
    r.build_seconds = program.build_seconds;

    RenderResult result;
    auto render_start = std::chrono::steady_clock::now();
    progress.report(0.0);
    for (std::uint64_t start = 0; start < total; start += pass_capacity) {
        auto size = static_cast<std::uint32_t>(std::min(pass_capacity, total - start));
        megakernel.setArg(arg::Megakernel::pass_start, cl_ulong(start));
        megakernel.setArg(arg::Megakernel::pass_size, cl_uint(size));
        launcher.launch(megakernel, "megakernel", size);
        film.accumulate(launcher, start, size, pass_radiance);
        // 32-bit device counters: read and cleared every pass.
        std::vector<std::uint32_t> figures(WP_COUNTS_SIZE);
        queue.enqueueReadBuffer(counts, CL_TRUE, 0, sizeof(std::uint32_t) * figures.size(), figures.data());
        queue.enqueueFillBuffer(counts, std::uint32_t(0), 0, sizeof(std::uint32_t) * WP_COUNTS_SIZE);
        launcher.time_finished(r.profile);
        result.stats.extension_rays += figures[WP_COUNTER_EXTENSION_RAYS];
        result.stats.shadow_rays += figures[WP_COUNTER_SHADOW_RAYS];
        result.stats.add_nonfinite(nonfinite_counts(figures));
        progress.report(double(start + size) / double(total));
    }
    result.image = film_to_image(film.read_sums(queue), camera.width, camera.height, scene.render.spp);
    result.stats.samples = total;
    result.stats.time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - render_start).count();
    if (options.profile) {
        launcher.time_finished(r.profile);
        r.profile.kernel("megakernel").items = total;
        r.profile.kernel("accumulate").items = total;
        r.profile.render_s = result.stats.time_s;
        r.profile.build_s = r.build_seconds;
    }
    return result;
}

}  // namespace wp
