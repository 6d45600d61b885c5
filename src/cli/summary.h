// The figures of a finished run: one summary line for people, a JSON file
// for tools.
#pragma once

#include <nlohmann/json_fwd.hpp>
#include <optional>
#include <string>
#include <vector>

#include "cli/backend_choice.h"
#include "core/film.h"
#include "core/render.h"

namespace wp::cli {

struct RunSummary {
    std::string backend;
    std::string output_path;
    int width = 0, height = 0, spp = 0;      // spp: asked for
    std::uint64_t spp_min = 0, spp_max = 0;  // samples the pixels have (fewest, most)
    std::string stopped = "done";            // why the render ended (stop_reason_name)
    double error = -1.0;                     // last estimated relative error (--target-error); -1: none
    RenderStats stats;
    bool adaptive = false;       // --adaptive: the two figures below are reported
    double spp_mean = 0.0;       // samples per pixel, mean over the pixels
    double stopped_early = 0.0;  // fraction of pixels with fewer samples than asked for
    bool sppm = false;           // the sppm integrator: the photons' figures are reported
    SppmRadii radii;             // sppm: the pixels' gathering radii against their footprints
    // Work items each rank rendered, in rank order (one entry in one process).
    std::vector<std::uint64_t> samples_per_rank;
    std::vector<double> busy_s_per_rank;          // seconds each rank spent rendering (not waiting)
    std::optional<BackendChoice> backend_choice;  // how --backend auto chose `backend`; none when --backend named it
    std::string estimator;  // the film's estimator (cli/backends.h, estimator_name): it names the intersector
};

// "wavepath: wrote out.png (512x512, 64 spp, reference) in 12.3 s: 1.36 Msamples/s,
//  extension 5.12 Mrays/s, shadow 3.40 Mrays/s, 0 non-finite values", then, when
//  any value was dropped, the count per stage: " (emission 1, direct 0, scatter 2)".
// A render that stopped early or holds a partial range says what the pixels
// have: "(512x512, 12-13 of 64 spp, stopped: time budget, wavefront)"; with
// --target-error the last estimate follows: ", estimated relative error 0.0098";
// with --adaptive: ", adaptive: mean 23.4 spp, 71.2% of pixels stopped early"; with
// the sppm integrator: ", sppm: 65536 photons, 20417 stored, mean radius 0.0123,
// 1.62 footprints (mean footprint 0.00761)": the mean of each pixel's radius
// over its footprint (sppm_radii, core/film.h).
// A backend --backend auto chose reads "megakernel (auto: CPU device, no
// meshes)"; on several MPI ranks "wavefront, 3 ranks".
std::string format_summary_line(const RunSummary& summary);

// {"backend","backend_choice" (explain_choice's words, or
// null),"estimator","width","height","spp","spp_done_min","spp_done_max","stopped","error_estimate" (or null),
//  "adaptive" (null, or {"spp_mean","stopped_early"}),
//  "sppm" (null, or {"photons","photon_rays","photon_deposits","mean_radius","mean_footprint",
//  "radius_in_footprints"}),
//  "ranks","samples_per_rank","render_s_per_rank","time_s", "samples","samples_per_s",
//  "extension_rays","extension_rays_per_s","shadow_rays","shadow_rays_per_s","nonfinite",
//  "nonfinite_by_stage": {"emission","direct","scatter"}}
nlohmann::json stats_json(const RunSummary& summary);

// SPPM's radii are still blurring the image when each pixel's radius is, in
// the mean, more than this many footprints (its first radius by default is
// 2, WP_SPPM_FOOTPRINTS; only a larger --initial-radius starts above this).
inline constexpr double kSppmBlurredFootprints = 4.0;

// One warning line where a render with the sppm integrator stopped with its
// radii above kSppmBlurredFootprints footprints: "wavepath: warning: sppm:
// the gathering radii are still 9.8 pixel footprints (mean radius 0.0745,
// footprint 0.0076): photon light is blurred over about 20 pixels; render more
// iterations or give a smaller --initial-radius". "" otherwise.
std::string sppm_warning(const RunSummary& summary);

// Writes stats_json atomically; throws OutputError.
void write_stats_json(const RunSummary& summary, const std::string& path);

}  // namespace wp::cli
