#include "cli/summary.h"

#include <algorithm>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "core/json_file.h"

namespace wp::cli {

namespace {

// Per second of render time; 0 when the run was too short to time.
double per_second(std::uint64_t count, double time_s) {
    return time_s > 0.0 ? static_cast<double>(count) / time_s : 0.0;
}

// " (emission 1, direct 0, scatter 2)" when any value was dropped, else "".
std::string nonfinite_breakdown(const RenderStats& s) {
    if (s.nonfinite == 0) return "";
    std::string text = " (";
    for (std::size_t i = 0; i < s.nonfinite_by_stage.size(); ++i) {
        text += (i ? ", " : "") + std::string(nonfinite_stage_names[i]) + " " + std::to_string(s.nonfinite_by_stage[i]);
    }
    return text + ")";
}

nlohmann::json nonfinite_by_stage_json(const RenderStats& s) {
    nlohmann::json by_stage = nlohmann::json::object();
    for (std::size_t i = 0; i < s.nonfinite_by_stage.size(); ++i) {
        by_stage[std::string(nonfinite_stage_names[i])] = s.nonfinite_by_stage[i];
    }
    return by_stage;
}

// "64 spp", or what the pixels have when that is not the asked spp.
std::string samples_text(const RunSummary& summary) {
    if (summary.spp_min == summary.spp_max && summary.spp_max == std::uint64_t(summary.spp) &&
        summary.stopped == "done")
        return std::to_string(summary.spp) + " spp";
    std::string done = std::to_string(summary.spp_min);
    if (summary.spp_max != summary.spp_min) done.append(1, '-').append(std::to_string(summary.spp_max));
    std::string text = done + " of " + std::to_string(summary.spp) + " spp";
    if (summary.stopped != "done") text += ", stopped: " + summary.stopped;
    return text;
}

std::string error_text(const RunSummary& summary) {
    if (summary.error < 0.0) return "";
    char text[64];
    std::snprintf(text, sizeof text, ", estimated relative error %.3g", summary.error);
    return text;
}

std::string adaptive_text(const RunSummary& summary) {
    if (!summary.adaptive) return "";
    char text[96];
    std::snprintf(text, sizeof text, ", adaptive: mean %.1f spp, %.1f%% of pixels stopped early", summary.spp_mean,
                  100.0 * summary.stopped_early);
    return text;
}

std::string sppm_text(const RunSummary& summary) {
    if (!summary.sppm) return "";
    char text[192];
    std::snprintf(text, sizeof text,
                  ", sppm: %llu photons, %llu stored, mean radius %.4g, %.3g footprints (mean footprint %.4g)",
                  static_cast<unsigned long long>(summary.stats.photons),
                  static_cast<unsigned long long>(summary.stats.photon_deposits), summary.radii.mean_radius,
                  summary.radii.radius_in_footprints, summary.radii.mean_footprint);
    return text;
}

std::string backend_text(const RunSummary& summary) {
    if (!summary.backend_choice) return summary.backend;
    return summary.backend + " (auto: " + summary.backend_choice->situation + ")";
}

std::string ranks_text(const RunSummary& summary) {
    const std::size_t ranks = summary.samples_per_rank.size();
    return ranks > 1 ? ", " + std::to_string(ranks) + " ranks" : "";
}

}  // namespace

std::string format_summary_line(const RunSummary& summary) {
    const RenderStats& s = summary.stats;
    char figures[256];
    std::snprintf(figures, sizeof figures,
                  "in %.3f s: %.3f Msamples/s, extension %.2f Mrays/s, shadow %.2f Mrays/s, %llu non-finite values",
                  s.time_s, per_second(s.samples, s.time_s) * 1e-6, per_second(s.extension_rays, s.time_s) * 1e-6,
                  per_second(s.shadow_rays, s.time_s) * 1e-6, static_cast<unsigned long long>(s.nonfinite));
    return "wavepath: wrote " + summary.output_path + " (" + std::to_string(summary.width) + "x" +
           std::to_string(summary.height) + ", " + samples_text(summary) + ", " + backend_text(summary) +
           ranks_text(summary) + ") " + figures + nonfinite_breakdown(s) + error_text(summary) +
           adaptive_text(summary) + sppm_text(summary);
}

std::string sppm_warning(const RunSummary& summary) {
    const SppmRadii& r = summary.radii;
    if (!summary.sppm || r.pixels == 0 || !(r.radius_in_footprints > kSppmBlurredFootprints)) return "";
    char text[320];
    std::snprintf(text, sizeof text,
                  "wavepath: warning: sppm: the gathering radii are still %.3g pixel footprints (mean radius %.4g, "
                  "footprint %.4g): photon light is blurred over about %.0f pixels; render more iterations or give a "
                  "smaller --initial-radius",
                  r.radius_in_footprints, r.mean_radius, r.mean_footprint, 2.0 * r.radius_in_footprints);
    return text;
}

nlohmann::json stats_json(const RunSummary& summary) {
    const RenderStats& s = summary.stats;
    return {
        {"backend", summary.backend},
        {"backend_choice",
         summary.backend_choice ? nlohmann::json(explain_choice(*summary.backend_choice)) : nlohmann::json(nullptr)},
        {"estimator", summary.estimator},
        {"width", summary.width},
        {"height", summary.height},
        {"spp", summary.spp},
        {"spp_done_min", summary.spp_min},
        {"spp_done_max", summary.spp_max},
        {"stopped", summary.stopped},
        {"error_estimate", summary.error < 0.0 ? nlohmann::json(nullptr) : nlohmann::json(summary.error)},
        {"adaptive", summary.adaptive
                         ? nlohmann::json{{"spp_mean", summary.spp_mean}, {"stopped_early", summary.stopped_early}}
                         : nlohmann::json(nullptr)},
        {"sppm", summary.sppm ? nlohmann::json{{"photons", s.photons},
                                               {"photon_rays", s.photon_rays},
                                               {"photon_deposits", s.photon_deposits},
                                               {"mean_radius", summary.radii.mean_radius},
                                               {"mean_footprint", summary.radii.mean_footprint},
                                               {"radius_in_footprints", summary.radii.radius_in_footprints}}
                              : nlohmann::json(nullptr)},
        {"ranks", std::max<std::size_t>(summary.samples_per_rank.size(), 1)},
        {"samples_per_rank",
         summary.samples_per_rank.empty() ? std::vector<std::uint64_t>{s.samples} : summary.samples_per_rank},
        {"render_s_per_rank", summary.busy_s_per_rank},
        {"time_s", s.time_s},
        {"samples", s.samples},
        {"samples_per_s", per_second(s.samples, s.time_s)},
        {"extension_rays", s.extension_rays},
        {"extension_rays_per_s", per_second(s.extension_rays, s.time_s)},
        {"shadow_rays", s.shadow_rays},
        {"shadow_rays_per_s", per_second(s.shadow_rays, s.time_s)},
        {"nonfinite", s.nonfinite},
        {"nonfinite_by_stage", nonfinite_by_stage_json(s)},
        {"threads", s.threads},
    };
}

void write_stats_json(const RunSummary& summary, const std::string& path) {
    write_json_atomically(stats_json(summary), path);
}

}  // namespace wp::cli
