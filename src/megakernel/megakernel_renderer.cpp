#include "megakernel/megakernel_renderer.h"

#include <algorithm>
#include <chrono>

#include "device/opencl_device.h"
#include "device/program_cache.h"
#include "wavefront/kernel_options.h"
#include "wavefront/pipeline.h"
#include "wavefront/scene_upload.h"
#include "wavefront/wavefront_renderer.h"

namespace wp {
namespace {

// Samples per launch: enough work items to fill any device, few enough that
// the progress moves and the pass entries (12 bytes each) stay small.
constexpr std::uint64_t kPassSize = std::uint64_t(1) << 18;

std::size_t round_up(std::size_t n, std::size_t multiple) { return (n + multiple - 1) / multiple * multiple; }

// Adds the finished launches' device times to `profile`.
void time_launches(std::vector<std::pair<const char*, cl::Event>>& events, WavefrontProfile& profile,
                   std::uint64_t megakernel_items) {
    for (auto& [name, event] : events) {
        KernelProfile& k = profile.kernel(name);
        ++k.launches;
        k.device_s += double(event.getProfilingInfo<CL_PROFILING_COMMAND_END>() -
                             event.getProfilingInfo<CL_PROFILING_COMMAND_START>()) *
                      1e-9;
    }
    events.clear();
    profile.kernel("megakernel").items = megakernel_items;
    profile.kernel("accumulate").items = megakernel_items;
}

}  // namespace

RenderResult render_megakernel(const Scene& scene, const MegakernelOptions& options, const Progress& progress,
                               MegakernelReport* report) {
    DeviceInfo device = choose_device(options.device);
    cl::Context context(device.device);
    cl::CommandQueue queue(context, device.device,
                           options.profile ? cl_command_queue_properties(CL_QUEUE_PROFILING_ENABLE) : 0);
    BuiltProgram program = build_program(
        context, device, {"megakernel.cl", "accumulate.cl"},
        kernel_build_options(scene.features(), uses_nee(scene), device.fp64, scene.render) + shape_count_options(scene),
        progress);
    DeviceScene device_scene(context, flatten_scene(scene));
    const Camera& camera = scene.camera;
    std::size_t pixel_count = std::size_t(camera.width) * camera.height;
    std::uint64_t total = std::uint64_t(pixel_count) * scene.render.spp;
    std::uint64_t pass_capacity = std::min(total, kPassSize);
    cl::Buffer pass_radiance(context, CL_MEM_READ_WRITE, sizeof(float) * 3 * pass_capacity);
    cl::Buffer counts(context, CL_MEM_READ_WRITE, sizeof(std::uint32_t) * WP_COUNTS_SIZE);
    queue.enqueueFillBuffer(counts, std::uint32_t(0), 0, sizeof(std::uint32_t) * WP_COUNTS_SIZE);
    cl::Buffer film = make_film(context, queue, pixel_count, device.fp64);

    cl::Kernel megakernel(program.program, "megakernel"), accumulate(program.program, "accumulate");
    cl_uint arg = 0;
    for (const cl::Buffer& b : device_scene.buffers) megakernel.setArg(arg++, b);
    const cl_uint pass_start_arg = arg;
    megakernel.setArg(pass_start_arg + 2, pass_radiance);
    megakernel.setArg(pass_start_arg + 3, counts);

    MegakernelReport local_report;
    MegakernelReport& r = report ? *report : local_report;
    r.device = device.name + " (" + device.platform + ")";
    r.build_options = program.options;
    r.cache_hit = program.cache_hit;
    r.build_seconds = program.build_seconds;
    std::vector<std::pair<const char*, cl::Event>> events;
    auto enqueue = [&](cl::Kernel& kernel, const char* name, std::size_t items) {
        cl::Event event;
        queue.enqueueNDRangeKernel(kernel, cl::NullRange, cl::NDRange(round_up(items, WP_GROUP_SIZE)),
                                   cl::NDRange(WP_GROUP_SIZE), nullptr, options.profile ? &event : nullptr);
        if (options.profile) events.emplace_back(name, event);
    };

    RenderResult result;
    auto render_start = std::chrono::steady_clock::now();
    progress.report(0.0);
    for (std::uint64_t start = 0; start < total; start += pass_capacity) {
        auto size = static_cast<std::uint32_t>(std::min(pass_capacity, total - start));
        megakernel.setArg(pass_start_arg, cl_ulong(start));
        megakernel.setArg(pass_start_arg + 1, cl_uint(size));
        enqueue(megakernel, "megakernel", size);
        set_accumulate_args(accumulate, start, size, pixel_count, pass_radiance, film);
        enqueue(accumulate, "accumulate", pixel_count);
        // 32-bit device counters: read and cleared every pass.
        std::vector<std::uint32_t> figures(WP_COUNTS_SIZE);
        queue.enqueueReadBuffer(counts, CL_TRUE, 0, sizeof(std::uint32_t) * figures.size(), figures.data());
        queue.enqueueFillBuffer(counts, std::uint32_t(0), 0, sizeof(std::uint32_t) * WP_COUNTS_SIZE);
        result.stats.extension_rays += figures[WP_COUNTER_EXTENSION_RAYS];
        result.stats.shadow_rays += figures[WP_COUNTER_SHADOW_RAYS];
        result.stats.add_nonfinite(nonfinite_counts(figures.data()));
        progress.report(double(start + size) / double(total));
    }
    result.image = film_to_image(read_film_sums(queue, film, pixel_count, device.fp64), camera.width, camera.height,
                                 scene.render.spp);
    result.stats.samples = total;
    result.stats.time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - render_start).count();
    if (options.profile) {
        time_launches(events, r.profile, total);
        r.profile.render_s = result.stats.time_s;
        r.profile.build_s = r.build_seconds;
    }
    return result;
}

}  // namespace wp
