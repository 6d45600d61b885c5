// What --profile measures of a wavefront render besides kernel times: rays
// per path depth (kernels/count_depths.cl), the roofline of the tracing
// stages (kernels/intersect_bound.cl) and the device's copy bandwidth.
#pragma once

#include <CL/opencl.hpp>
#include <cstdint>

#include "interface/queues.h"
#include "opencl/launcher.h"
#include "opencl/profile.h"
#include "opencl/scene_upload.h"

namespace wp {

// Counts the depths of the paths in a queue into a histogram among the counters.
class RayDepthCounter {
 public:
    // shadow_rays: next-event estimation runs (else there are none to count).
    RayDepthCounter(const cl::Program& program, const cl::Buffer& queues, const cl::Buffer& counts,
                    std::size_t capacity, const cl::Buffer& depth, bool shadow_rays);
    // Counts the extension rays (the RAY queue, before intersect) or the
    // shadow rays (SHADOW, complete after shade, whichever stage traces
    // them) of at most `entries` entries into their histogram among the counters.
    void count_extension_rays(KernelLauncher& launcher, std::size_t entries);
    void count_shadow_rays(KernelLauncher& launcher, std::size_t entries);
    // The queues whose entries it reads besides their consumer (bits 1 <<
    // queue): SHADOW, which where no stage consumes it is otherwise only
    // counted (wavefront/queue_plan.h). RAY it reads before its consumer.
    static constexpr std::uint32_t kQueuesRead = 1u << WP_QUEUE_SHADOW;
    // Extension and shadow rays per depth, counted so far.
    void read(cl::CommandQueue& queue, RenderProfile& profile) const;

 private:
    void count(KernelLauncher& launcher, std::uint32_t queue, std::uint32_t histogram_offset,
               std::uint32_t depth_after_vertex, std::size_t entries);

    cl::Kernel kernel_;
    cl::Buffer counts_;
    bool shadow_rays_;
};

struct IntersectBound {
    double rays_per_s = 0.0;        // rays over the best of three launches' device time
    double hit_distance_sum = 0.0;  // over the rays that hit something: what the kernel computed, for tests
};

// Traces `rays` camera rays through pixel centres with nothing but the
// ray-primitive tests, `lanes` per work item: the bound the intersect
// stages' rays/s is measured against. `queue` must be a profiling queue.
IntersectBound measure_intersect_bound(const cl::Context& context, cl::CommandQueue& queue, const cl::Program& program,
                                       const DeviceScene& scene, unsigned lanes, std::uint32_t rays);

struct CopyBandwidth {
    double bytes_per_s = 0.0;  // bytes read plus bytes written, over the best of three copies' device time
    std::uint64_t bytes = 0;   // copied by each
};

// Copies one device buffer of `bytes` (at most the device's largest
// allocation) to another, once untimed (the pages are touched then), then
// three times timed: the bandwidth the stages' declared bytes per second are
// held against. `queue` must be a profiling queue.
CopyBandwidth measure_copy_bandwidth(const cl::Context& context, cl::CommandQueue& queue, std::uint64_t bytes);

}  // namespace wp
