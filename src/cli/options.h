// The `render` subcommand's flags and how they change a loaded scene.
#pragma once

#include <CLI/CLI.hpp>
#include <cstdint>
#include <optional>
#include <string>

#include "cli/backends.h"
#include "scene/scene.h"

namespace wp::cli {

// Flags that override the scene's render block and camera resolution.
struct RenderOverrides {
    std::optional<int> spp, width, height, max_depth, rr_depth;
    std::optional<std::int64_t> seed;            // wide enough to reject out-of-range values with a clear message
    std::optional<std::string> nee, hemisphere;  // "on"/"off", "cosine"/"uniform"
};

struct RenderCommand {
    std::string scene_path;
    std::string output_path;
    std::string stats_json_path;  // empty: none
    bool quiet = false;
    RenderOverrides overrides;
    BackendOptions backend;
};

// Adds SCENE, -o and every render flag to `render`. Each numeric flag is
// checked against the scene loader's limits while parsing.
void add_render_options(CLI::App& render, RenderCommand& command);

// Applies the overrides to `scene`. Throws UsageError if the resulting
// resolution exceeds the scene loader's pixel limit.
void apply_overrides(const RenderOverrides& overrides, Scene& scene);

}  // namespace wp::cli
