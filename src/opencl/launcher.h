// Kernel launches over whole work groups, timed with OpenCL events when
// profiling, for both OpenCL backends.
#pragma once

#include <CL/opencl.hpp>
#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "interface/queues.h"
#include "opencl/profile.h"

namespace wp {

// n / d rounded up.
constexpr std::size_t divide_rounding_up(std::size_t n, std::size_t d) { return (n + d - 1) / d; }
// n rounded up to a multiple of `multiple`.
constexpr std::size_t round_up(std::size_t n, std::size_t multiple) {
    return divide_rounding_up(n, multiple) * multiple;
}

class KernelLauncher {
 public:
    // `queue` must have CL_QUEUE_PROFILING_ENABLE when `profiling`.
    KernelLauncher(cl::CommandQueue& queue, bool profiling) : queue_(queue), profiling_(profiling) {}

    // Launches `items` work items, rounded up to whole groups of `group`
    // (0: exactly `items`, groups left to the driver).
    void launch(cl::Kernel& kernel, const char* name, std::size_t items, std::size_t group = WP_GROUP_SIZE);
    // Work the host did between launches, the device idle (the wavefront's
    // host-traced stages): a row of the profile of its own, its seconds
    // taken out of the idle time between kernels. Nothing without profiling.
    void add_host_time(const std::string& row, double seconds);
    // Adds the launches finished since the last call (the queue must have been
    // waited on) and the host's work to `profile`: launches, device time and
    // the device's idle time between kernels. Nothing without profiling.
    void time_finished(RenderProfile& profile);
    bool profiling() const { return profiling_; }

 private:
    cl::CommandQueue& queue_;
    bool profiling_;
    std::vector<std::pair<const char*, cl::Event>> pending_;  // launched, not yet timed
    std::vector<std::pair<std::string, double>> host_time_;   // not yet in the profile
    cl_ulong last_kernel_end_ = 0;
};

// Seconds between an event's start and end (profiling queues only).
double event_seconds(const cl::Event& event);

}  // namespace wp
