#include "opencl/profile.h"

#include <algorithm>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "core/json_file.h"

namespace wp {
namespace {

double per_second(std::uint64_t count, double seconds) { return seconds > 0.0 ? double(count) / seconds : 0.0; }

// Depths 0..last with a non-zero entry, comma-separated.
std::string depth_list(const std::vector<std::uint64_t>& by_depth) {
    std::string text;
    std::size_t end = by_depth.size();
    while (end > 0 && by_depth[end - 1] == 0) --end;
    for (std::size_t d = 0; d < end; ++d) text += (d ? " " : "") + std::to_string(by_depth[d]);
    return text.empty() ? "-" : text;
}

// The tracing stages' kernels, set against the intersect bound where they
// ran, with what sets each apart from the bound's tests.
struct TracingKernel {
    const char* name;
    const char* note;
};
constexpr TracingKernel kTracingKernels[] = {{"intersect", ""},
                                             {"intersect_and_shade", " (shading too)"},
                                             {"intersect_shadow", " (any hit: cheaper tests, same bound)"}};

template <class Kernels>
auto find_kernel(Kernels& kernels, const std::string& name) {
    return std::find_if(kernels.begin(), kernels.end(), [&](const KernelProfile& k) { return k.name == name; });
}

}  // namespace

KernelProfile& RenderProfile::kernel(const std::string& name) {
    auto it = find_kernel(kernels, name);
    if (it != kernels.end()) return *it;
    kernels.push_back({name});
    return kernels.back();
}

bool RenderProfile::has_kernel(const std::string& name) const { return find_kernel(kernels, name) != kernels.end(); }

double RenderProfile::kernel_s() const {
    double sum = 0.0;
    for (const KernelProfile& k : kernels) sum += k.device_s;
    return sum;
}

double KernelProfile::bytes_per_s() const { return per_second(bytes_per_item * items, device_s); }

double RenderProfile::fraction_of_copy_bandwidth(const KernelProfile& k) const {
    return copy_bytes_per_s > 0.0 ? k.bytes_per_s() / copy_bytes_per_s : 0.0;
}

double RenderProfile::fraction_of_intersect_bound(const std::string& name) const {
    auto it = find_kernel(kernels, name);
    if (it == kernels.end() || intersect_bound_rays_per_s <= 0.0) return 0.0;
    return per_second(it->items, it->device_s) / intersect_bound_rays_per_s;
}

std::string format_profile_table(const RenderProfile& p) {
    std::string out =
        "wavepath profile (device time from OpenCL events, host time for the embree: rows; share of the render's "
        "wall time)\n";
    char line[256];
    std::snprintf(line, sizeof line, "  %-24s %9s %13s %11s %13s %7s %7s %8s %7s\n", "kernel", "launches", "items",
                  "device ms", "Mitems/s", "share", "B/item", "GB/s", "of copy");
    out += line;
    auto row = [&](const char* name, const char* launches, const char* items, double seconds, const char* rate,
                   const char* bytes = "", const char* bandwidth = "", const char* of_copy = "") {
        std::snprintf(line, sizeof line, "  %-24s %9s %13s %11.2f %13s %6.1f%% %7s %8s %7s\n", name, launches, items,
                      seconds * 1e3, rate, p.render_s > 0 ? 100.0 * seconds / p.render_s : 0.0, bytes, bandwidth,
                      of_copy);
        out += line;
    };
    for (const KernelProfile& k : p.kernels) {
        char rate[32], bandwidth[32] = "", of_copy[32] = "";
        std::snprintf(rate, sizeof rate, "%.2f", per_second(k.items, k.device_s) * 1e-6);
        const std::string bytes = k.bytes_per_item ? std::to_string(k.bytes_per_item) : "";
        if (k.bytes_per_item) std::snprintf(bandwidth, sizeof bandwidth, "%.2f", k.bytes_per_s() * 1e-9);
        if (k.bytes_per_item && p.copy_bytes_per_s > 0.0)
            std::snprintf(of_copy, sizeof of_copy, "%.0f%%", 100.0 * p.fraction_of_copy_bandwidth(k));
        row(k.name.c_str(), std::to_string(k.launches).c_str(), std::to_string(k.items).c_str(), k.device_s, rate,
            bytes.c_str(), bandwidth, of_copy);
    }
    row("(between kernels)", "", "", p.gaps_s, "");
    row("(host, other)", "", "", std::max(0.0, p.render_s - p.kernel_s() - p.gaps_s), "");
    std::snprintf(line, sizeof line, "  render %.3f s over %llu iterations; program build %.3f s (not in the render)\n",
                  p.render_s, static_cast<unsigned long long>(p.iterations), p.build_s);
    out += line;
    out += "  extension rays by depth: " + depth_list(p.extension_rays_by_depth) + "\n";
    out += "  shadow rays by depth:    " + depth_list(p.shadow_rays_by_depth) + "\n";
    if (p.intersect_bound_rays_per_s > 0.0) {
        std::snprintf(line, sizeof line, "  intersect bound (ray-primitive tests only, no state traffic): %.1f Mrays/s",
                      p.intersect_bound_rays_per_s * 1e-6);
        out += line;
        bool first = true;  // "; intersect at 90% of it, intersect_shadow at 80% (...)"
        for (const TracingKernel& k : kTracingKernels) {
            if (!p.has_kernel(k.name)) continue;
            std::snprintf(line, sizeof line, "%s%s at %.0f%%%s%s", first ? "; " : ", ", k.name,
                          100.0 * p.fraction_of_intersect_bound(k.name), first ? " of it" : "", k.note);
            out += line;
            first = false;
        }
        out += "\n";
    }
    if (p.copy_bytes_per_s > 0.0) {
        std::snprintf(line, sizeof line,
                      "  copy bandwidth: %.2f GB/s (bytes read + written; clEnqueueCopyBuffer of %llu MiB, best of "
                      "3); B/item is the stage's declared path state and queue bytes, an upper bound\n",
                      p.copy_bytes_per_s * 1e-9, static_cast<unsigned long long>(p.copy_buffer_bytes >> 20));
        out += line;
    }
    return out;
}

nlohmann::json profile_json(const RenderProfile& p) {
    nlohmann::json kernels = nlohmann::json::array();
    for (const KernelProfile& k : p.kernels) {
        nlohmann::json& row =
            kernels.emplace_back(nlohmann::json{{"name", k.name},
                                                {"launches", k.launches},
                                                {"items", k.items},
                                                {"device_s", k.device_s},
                                                {"items_per_s", per_second(k.items, k.device_s)},
                                                {"share", p.render_s > 0 ? k.device_s / p.render_s : 0.0}});
        if (k.bytes_per_item == 0) continue;
        row["bytes_per_item"] = k.bytes_per_item;
        row["bytes_per_s"] = k.bytes_per_s();
        if (p.copy_bytes_per_s > 0.0) row["of_copy_bandwidth"] = p.fraction_of_copy_bandwidth(k);
    }
    nlohmann::json json = {{"render_s", p.render_s},
                           {"kernel_s", p.kernel_s()},
                           {"gaps_s", p.gaps_s},
                           {"host_other_s", std::max(0.0, p.render_s - p.kernel_s() - p.gaps_s)},
                           {"build_s", p.build_s},
                           {"iterations", p.iterations},
                           {"kernels", kernels},
                           {"extension_rays_by_depth", p.extension_rays_by_depth},
                           {"shadow_rays_by_depth", p.shadow_rays_by_depth}};
    if (p.intersect_bound_rays_per_s > 0.0) {
        json["intersect_bound_rays_per_s"] = p.intersect_bound_rays_per_s;
        json["of_intersect_bound"] = nlohmann::json::object();
        for (const TracingKernel& k : kTracingKernels)
            if (p.has_kernel(k.name)) json["of_intersect_bound"][k.name] = p.fraction_of_intersect_bound(k.name);
    }
    if (p.copy_bytes_per_s > 0.0) {
        json["copy_bytes_per_s"] = p.copy_bytes_per_s;
        json["copy_buffer_bytes"] = p.copy_buffer_bytes;
    }
    return json;
}

void write_profile_json(const RenderProfile& profile, const std::string& path) {
    write_json_atomically(profile_json(profile), path);
}

}  // namespace wp
