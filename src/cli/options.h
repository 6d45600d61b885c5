// The `render` subcommand's flags and how they change a loaded scene.
#pragma once

#include <CLI/CLI.hpp>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "cli/backends.h"
#include "import/import_limits.h"
#include "scene/scene.h"

namespace wp::cli {

// Flags that override the scene's render block and camera resolution.
struct RenderOverrides {
    std::optional<int> spp, width, height, max_depth, rr_depth;
    std::optional<std::int64_t> seed;                 // wide enough to reject out-of-range values with a clear message
    std::optional<std::string> nee, mis, hemisphere;  // "on"/"off", "on"/"off", "cosine"/"uniform"
    std::optional<std::string> sampler;               // "sobol"/"independent"
    std::optional<std::string> integrator;            // "path"/"sppm"
    std::optional<std::int64_t> photons;              // sppm: photons per iteration
    std::optional<double> initial_radius, alpha;      // sppm
};

// Flags of long renders (docs/long-renders.md).
struct LongRunFlags {
    std::string checkpoint;  // "": no checkpoints
    double checkpoint_every_s = 300.0;
    std::string resume;            // "": start afresh
    std::optional<double> time_s;  // --time budget
    std::optional<double> target_error;
    std::optional<double> adaptive;  // --adaptive threshold
    std::string samples;             // "A:B": samples A to B-1 of every pixel, into a partial film
};

struct RenderCommand {
    std::string scene_path;
    std::vector<std::string> defines;  // -D name=value, for Mitsuba XML scenes
    std::string output_path;
    std::string stats_json_path;  // empty: none
    bool quiet = false;
    RenderOverrides overrides;
    LongRunFlags long_run;
    BackendOptions backend;
    MeshImportLimits mesh_import;  // --mesh-import-memory, --mesh-import-cpu, --mesh-import-time
};

// Adds SCENE, -o and every render flag to `render`. Each numeric flag is
// checked against the scene loader's limits while parsing.
void add_render_options(CLI::App& render, RenderCommand& command);

// Applies the overrides to `scene`. Throws UsageError if the resulting
// resolution exceeds the scene loader's pixel limit, for an sppm flag without
// the sppm integrator, and for sppm on a scene it cannot render (sppm_problem).
void apply_overrides(const RenderOverrides& overrides, Scene& scene);

}  // namespace wp::cli
