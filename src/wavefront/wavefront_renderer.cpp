#include "wavefront/wavefront_renderer.h"

#include <algorithm>
#include <chrono>
#include <map>
#include <sstream>

#include "opencl/device.h"
#include "opencl/film.h"
#include "opencl/kernel_options.h"
#include "wavefront/pipeline.h"
#include "wavefront/scheduler.h"

namespace wp {
namespace {

// Work items per pass, as a multiple of the wavefront: a pass drains (its
// last paths run with the wavefront partly empty) before accumulation, so
// longer passes waste less; each item costs 12 bytes of pass radiance.
constexpr std::size_t kPassesPerWavefront = 16;

// Rays of the intersect bound (--profile): enough that launch overhead is
// negligible, and the same for every image size.
constexpr std::uint32_t kIntersectBoundRays = 1u << 20;

// The scene's features plus every shape, material and light type: what an
// unspecialised build compiles (lights and background stay as in the scene,
// since next-event estimation needs at least one light).
FeatureSet every_shape_and_material(FeatureSet f) {
    f.spheres = f.planes = f.quads = true;
    f.diffuse = f.mirror = f.glass = f.emitter_material = true;
    f.sphere_lights = f.quad_lights = true;
    return f;
}

// Items each kernel processed: its input queue's length summed over the
// iterations (accumulate: the pass entries it summed; compaction: the slots
// its launches went through; compact_scan: the blocks of slots it summed;
// count_depths: the rays it counted).
void fill_profile(RenderProfile& profile, const std::vector<IterationRecord>& iterations, std::uint64_t samples,
                  std::size_t wavefront) {
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
    const std::map<std::string, std::uint32_t IterationRecord::*> input_queue{
        {"generate", &IterationRecord::free_slots},
        {"intersect", &IterationRecord::traced},
        {"shade_direct", &IterationRecord::hits},
        {"intersect_shadow", &IterationRecord::shadow},
        {"scatter", &IterationRecord::scattered}};
    for (KernelProfile& k : profile.kernels) {
        auto queue = input_queue.find(k.name);
        if (queue == input_queue.end()) continue;
        k.items = 0;
        for (const IterationRecord& r : iterations) k.items += r.*(queue->second);
    }
    profile.kernel("accumulate").items = samples;
    profile.iterations = iterations.size();
}

}  // namespace

std::size_t default_wavefront_size(std::uint64_t work_items, std::size_t bytes_per_path, const DeviceInfo& device) {
    // On a CPU the state should stay near the caches: 2^16 paths rendered room.json
    // at 512x512 1.7x faster than 2^20 on PoCL (2 cores); GPUs need many paths in flight.
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
        << "build options: " << build_options << "\n"
        << "program: " << (cache_hit ? "cache hit" : "cache miss, compiled") << " in " << build_seconds << " s"
        << (cache_file.empty() ? " (no cache directory)" : " (" + cache_file + ")") << "\n"
        << "wavefront: " << wavefront << " paths in flight, passes of up to " << pass_capacity << " samples, " << lanes
        << (lanes == 1 ? " path" : " paths") << " per work item in the stage kernels\n"
        << "path state: " << state_bytes_per_path << " bytes per path, " << state_bytes_per_path * wavefront / 1024
        << " KiB in all\n";
    if (!meshes.empty()) out << "meshes: " << meshes << "\n";
    return out.str();
}

RenderResult render_wavefront(const Scene& scene, const WavefrontOptions& options, const Progress& progress,
                              WavefrontReport* report) {
    DeviceInfo device = choose_device(options.device);
    const Camera& camera = scene.camera;
    std::uint64_t total = std::uint64_t(camera.width) * camera.height * scene.render.spp;
    std::size_t wavefront = options.wavefront
                                ? options.wavefront
                                : default_wavefront_size(total, PathState::bytes_per_path(scene.features()), device);
    FeatureSet features = options.specialise ? scene.features() : every_shape_and_material(scene.features());
    Pipeline pipeline(scene, device, wavefront, std::min<std::uint64_t>(total, kPassesPerWavefront * wavefront),
                      features, {options.profile, options.compaction, options.lanes, progress, options.float_film});

    WavefrontReport local_report;
    WavefrontReport& r = report ? *report : local_report;
    r.device = device.name + " (" + device.platform + ")";
    r.features = describe_features(features);
    r.build_options = pipeline.program().options;
    r.cache_hit = pipeline.program().cache_hit;
    r.build_seconds = pipeline.program().build_seconds;
    r.cache_file = pipeline.program().cache_file;
    r.lanes = pipeline.lanes();
    r.wavefront = wavefront;
    r.pass_capacity = pipeline.pass_capacity();
    r.state_bytes_per_path = pipeline.state().bytes_per_path();
    r.meshes = pipeline.device_scene().meshes().describe();

    auto render_start = std::chrono::steady_clock::now();  // time_s leaves out device setup and the build
    progress.report(0.0);
    ScheduleTotals totals = run_schedule(pipeline, total, features.nee, progress, r.iterations);
    RenderResult result;
    result.image = film_to_image(pipeline.read_film(), camera.width, camera.height, scene.render.spp);
    result.stats.samples = total;
    result.stats.extension_rays = totals.extension_rays;
    result.stats.shadow_rays = totals.shadow_rays;
    result.stats.add_nonfinite(totals.nonfinite);
    result.stats.time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - render_start).count();
    if (options.profile) {
        r.profile = pipeline.profile();
        fill_profile(r.profile, r.iterations, total, wavefront);
        r.profile.render_s = result.stats.time_s;
        r.profile.build_s = r.build_seconds;
        pipeline.read_rays_by_depth(r.profile);
        r.profile.intersect_bound_rays_per_s = pipeline.measure_intersect_bound(kIntersectBoundRays).rays_per_s;
    }
    return result;
}

}  // namespace wp
