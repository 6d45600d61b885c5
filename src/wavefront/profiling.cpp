#include "wavefront/profiling.h"

#include <algorithm>
#include <limits>
#include <numeric>
#include <vector>

#include "interface/queues.h"
#include "opencl/kernel_arguments.h"

namespace wp {
namespace {

// The shortest device time of three runs of `enqueue` (which enqueues one
// command with the event it is given), after one run that is not timed.
template <class Enqueue>
double best_of_three_after_one_untimed(Enqueue enqueue) {
    double best_s = std::numeric_limits<double>::infinity();
    for (int run = 0; run <= 3; ++run) {
        cl::Event event;
        enqueue(event);
        event.wait();
        if (run > 0) best_s = std::min(best_s, event_seconds(event));
    }
    return best_s;
}

}  // namespace

RayDepthCounter::RayDepthCounter(const cl::Program& program, const cl::Buffer& queues, const cl::Buffer& counts,
                                 std::size_t capacity, const cl::Buffer& depth, bool shadow_rays)
    : kernel_(program, "count_depths"), counts_(counts), shadow_rays_(shadow_rays) {
    kernel_.setArg(arg::CountDepths::queues, queues);
    kernel_.setArg(arg::CountDepths::counts, counts);
    kernel_.setArg(arg::CountDepths::capacity, cl_uint(capacity));
    kernel_.setArg(arg::CountDepths::depth, depth);
}

void RayDepthCounter::count_extension_rays(KernelLauncher& launcher, std::size_t entries) {
    count(launcher, WP_QUEUE_RAY, WP_PROFILE_EXTENSION_BY_DEPTH, 0, entries);
}

// shade has counted the shadow ray's vertex in its path's depth already.
void RayDepthCounter::count_shadow_rays(KernelLauncher& launcher, std::size_t entries) {
    if (shadow_rays_) count(launcher, WP_QUEUE_SHADOW, WP_PROFILE_SHADOW_BY_DEPTH, 1, entries);
}

void RayDepthCounter::count(KernelLauncher& launcher, std::uint32_t queue, std::uint32_t histogram_offset,
                            std::uint32_t depth_after_vertex, std::size_t entries) {
    kernel_.setArg(arg::CountDepths::queue, cl_uint(queue));
    kernel_.setArg(arg::CountDepths::histogram_offset, cl_uint(histogram_offset));
    kernel_.setArg(arg::CountDepths::depth_after_vertex, cl_uint(depth_after_vertex));
    launcher.launch(kernel_, "count_depths", entries);
}

void RayDepthCounter::read(cl::CommandQueue& queue, RenderProfile& profile) const {
    std::vector<std::uint32_t> histograms(2 * WP_PROFILE_DEPTHS);
    queue.enqueueReadBuffer(counts_, CL_TRUE, WP_PROFILE_EXTENSION_BY_DEPTH * sizeof(std::uint32_t),
                            histograms.size() * sizeof(std::uint32_t), histograms.data());
    profile.extension_rays_by_depth.assign(histograms.begin(), histograms.begin() + WP_PROFILE_DEPTHS);
    profile.shadow_rays_by_depth.assign(histograms.begin() + WP_PROFILE_DEPTHS, histograms.end());
}

IntersectBound measure_intersect_bound(const cl::Context& context, cl::CommandQueue& queue, const cl::Program& program,
                                       const DeviceScene& scene, unsigned lanes, std::uint32_t rays) {
    cl::Buffer hit_t(context, CL_MEM_WRITE_ONLY, sizeof(float) * rays);
    cl::Kernel kernel(program, "intersect_bound");
    scene.bind(kernel);
    kernel.setArg(arg::IntersectBound::ray_count, cl_uint(rays));
    kernel.setArg(arg::IntersectBound::hit_t, hit_t);
    std::size_t items = round_up(divide_rounding_up(rays, lanes), WP_GROUP_SIZE);
    // The untimed launch: PoCL compiles the kernel for its launch geometry then.
    const double best_s = best_of_three_after_one_untimed([&](cl::Event& event) {
        queue.enqueueNDRangeKernel(kernel, cl::NullRange, cl::NDRange(items), cl::NDRange(WP_GROUP_SIZE), nullptr,
                                   &event);
    });
    std::vector<float> distances(rays);
    queue.enqueueReadBuffer(hit_t, CL_TRUE, 0, sizeof(float) * rays, distances.data());
    return {double(rays) / best_s, std::accumulate(distances.begin(), distances.end(), 0.0)};
}

CopyBandwidth measure_copy_bandwidth(const cl::Context& context, cl::CommandQueue& queue, std::uint64_t bytes) {
    const cl::Device device = context.getInfo<CL_CONTEXT_DEVICES>().front();
    bytes = std::min<std::uint64_t>(bytes, device.getInfo<CL_DEVICE_MAX_MEM_ALLOC_SIZE>()) & ~std::uint64_t(3);
    cl::Buffer source(context, CL_MEM_READ_ONLY, bytes), destination(context, CL_MEM_WRITE_ONLY, bytes);
    queue.enqueueFillBuffer(source, std::uint32_t(0x3f800000), 0, bytes);
    const double best_s = best_of_three_after_one_untimed(
        [&](cl::Event& event) { queue.enqueueCopyBuffer(source, destination, 0, 0, bytes, nullptr, &event); });
    return {2.0 * double(bytes) / best_s, bytes};
}

}  // namespace wp
