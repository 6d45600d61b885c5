#include "opencl/launcher.h"

#include <algorithm>

namespace wp {

void KernelLauncher::launch(cl::Kernel& kernel, const char* name, std::size_t items, std::size_t group) {
    cl::Event event;
    queue_.enqueueNDRangeKernel(kernel, cl::NullRange, cl::NDRange(group ? round_up(items, group) : items),
                                group ? cl::NDRange(group) : cl::NullRange, nullptr, profiling_ ? &event : nullptr);
    if (profiling_) pending_.emplace_back(name, event);
}

void KernelLauncher::add_host_time(const std::string& row, double seconds) {
    if (profiling_) host_time_.emplace_back(row, seconds);
}

void KernelLauncher::time_finished(RenderProfile& profile) {
    for (auto& [name, event] : pending_) {
        cl_ulong start = event.getProfilingInfo<CL_PROFILING_COMMAND_START>();
        cl_ulong end = event.getProfilingInfo<CL_PROFILING_COMMAND_END>();
        KernelProfile& k = profile.kernel(name);
        ++k.launches;
        k.device_s += double(end - start) * 1e-9;
        if (last_kernel_end_ != 0 && start > last_kernel_end_)
            profile.gaps_s += double(start - last_kernel_end_) * 1e-9;
        last_kernel_end_ = std::max(last_kernel_end_, end);
    }
    pending_.clear();
    for (const auto& [row, seconds] : host_time_) {
        KernelProfile& k = profile.kernel(row);
        ++k.launches;
        k.device_s += seconds;
        profile.gaps_s = std::max(0.0, profile.gaps_s - seconds);
    }
    host_time_.clear();
}

double event_seconds(const cl::Event& event) {
    return double(event.getProfilingInfo<CL_PROFILING_COMMAND_END>() -
                  event.getProfilingInfo<CL_PROFILING_COMMAND_START>()) *
           1e-9;
}

}  // namespace wp
