// The figures of `wavepath render --profile`: per kernel the launches, items
// processed, device time (OpenCL event profiling) and items/s; the device's
// idle time between kernels (host synchronisation, transfers, launch
// latency); rays per path depth; the tracing stages' rays/s against the
// intersect bound (the roofline); the wavefront stages' declared bytes per
// item and GB/s against the device's measured copy bandwidth; and the
// program build time apart.
#pragma once

#include <cstdint>
#include <nlohmann/json_fwd.hpp>
#include <string>
#include <vector>

namespace wp {

// A kernel's row; or, for work the host does between kernels (the
// wavefront's host-traced stages, rows "embree:<stage>"), the host's.
struct KernelProfile {
    std::string name;
    std::uint64_t launches = 0;
    std::uint64_t items = 0;  // queue entries (or pixels, for accumulate) the launches processed
    double device_s = 0.0;    // sum of the launches' end - start (a host row: the host's wall time)
    // Bytes read and written per item as declared (a wavefront stage's
    // wp::stage_bytes_per_item, an upper bound); 0: not declared.
    std::uint64_t bytes_per_item = 0;
    double bytes_per_s() const;  // bytes_per_item x items / device_s
};

struct RenderProfile {
    std::vector<KernelProfile> kernels;
    double render_s = 0.0;         // wall time of the render (the build left out)
    double gaps_s = 0.0;           // device time between one kernel's end and the next one's start
    double build_s = 0.0;          // program build or cache load
    std::uint64_t iterations = 0;  // of the stage loop, over all passes
    std::vector<std::uint64_t> extension_rays_by_depth;  // index = depth; the last entry counts that depth and deeper
    std::vector<std::uint64_t> shadow_rays_by_depth;
    // The tracing stages' roofline (Pipeline::measure_intersect_bound); 0: not measured (the megakernel).
    double intersect_bound_rays_per_s = 0.0;
    // The device's copy bandwidth (wavefront/profiling.h measure_copy_bandwidth):
    // bytes read plus bytes written per second, and the bytes copied; 0: not measured.
    double copy_bytes_per_s = 0.0;
    std::uint64_t copy_buffer_bytes = 0;

    KernelProfile& kernel(const std::string& name);  // added if absent
    bool has_kernel(const std::string& name) const;
    double kernel_s() const;  // sum over the kernels
    // The kernel's items/s as a fraction of intersect_bound_rays_per_s.
    double fraction_of_intersect_bound(const std::string& name) const;
    // The kernel's bytes_per_s as a fraction of copy_bytes_per_s (0: either unknown).
    double fraction_of_copy_bandwidth(const KernelProfile& kernel) const;
};

// An aligned table for people (stderr).
std::string format_profile_table(const RenderProfile& profile);

// {"render_s","kernel_s","gaps_s","host_other_s","build_s","iterations",
//  "kernels":[{"name","launches","items","device_s","items_per_s","share"}],
//  "extension_rays_by_depth":[...], "shadow_rays_by_depth":[...]}, and when the bound was measured
//  "intersect_bound_rays_per_s" and "of_intersect_bound":{"intersect","intersect_and_shade","intersect_shadow"}
//  (fractions, of the kernels that ran);
//  a kernel with declared bytes also has "bytes_per_item" and "bytes_per_s", and, when the copy
//  bandwidth was measured, "of_copy_bandwidth" (a fraction); the profile then has "copy_bytes_per_s"
//  and "copy_buffer_bytes"
nlohmann::json profile_json(const RenderProfile& profile);

// Writes profile_json atomically; throws OutputError.
void write_profile_json(const RenderProfile& profile, const std::string& path);

}  // namespace wp
