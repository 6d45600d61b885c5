#include "cli/summary.h"

#include <cstdio>

#include "core/json_file.h"

namespace wp::cli {

namespace {

// Per second of render time; 0 when the run was too short to time.
double per_second(std::uint64_t count, double time_s) {
    return time_s > 0.0 ? static_cast<double>(count) / time_s : 0.0;
}

}  // namespace

std::string format_summary_line(const RunSummary& summary) {
    const RenderStats& s = summary.stats;
    char figures[256];
    std::snprintf(figures, sizeof figures,
                  "in %.3f s: %.3f Msamples/s, extension %.2f Mrays/s, shadow %.2f Mrays/s, %llu non-finite samples",
                  s.time_s, per_second(s.samples, s.time_s) * 1e-6, per_second(s.extension_rays, s.time_s) * 1e-6,
                  per_second(s.shadow_rays, s.time_s) * 1e-6, static_cast<unsigned long long>(s.nonfinite));
    return "wavepath: wrote " + summary.output_path + " (" + std::to_string(summary.width) + "x" +
           std::to_string(summary.height) + ", " + std::to_string(summary.spp) + " spp, " + summary.backend + ") " +
           figures;
}

nlohmann::json stats_json(const RunSummary& summary) {
    const RenderStats& s = summary.stats;
    return {
        {"backend", summary.backend},
        {"width", summary.width},
        {"height", summary.height},
        {"spp", summary.spp},
        {"time_s", s.time_s},
        {"samples", s.samples},
        {"samples_per_s", per_second(s.samples, s.time_s)},
        {"extension_rays", s.extension_rays},
        {"extension_rays_per_s", per_second(s.extension_rays, s.time_s)},
        {"shadow_rays", s.shadow_rays},
        {"shadow_rays_per_s", per_second(s.shadow_rays, s.time_s)},
        {"nonfinite", s.nonfinite},
    };
}

void write_stats_json(const RunSummary& summary, const std::string& path) {
    write_json_atomically(stats_json(summary), path);
}

}  // namespace wp::cli
