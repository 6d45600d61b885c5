// The renderers the CLI can run, by name. Adding a backend means adding its
// options to BackendOptions, its flags to add_backend_options and one entry
// to the table in backends.cpp; nothing else in the CLI changes.
#pragma once

#include <CLI/CLI.hpp>
#include <cstddef>
#include <string>
#include <vector>

#include "core/render.h"
#include "scene/scene.h"
#include "wavefront/compaction.h"

namespace wp::cli {

struct BackendOptions {
    std::string name = "wavefront";
    int threads = 0;  // CPU threads for the reference; 0 = all hardware threads
    std::string precision = "float";
    std::size_t wavefront = 0;                   // paths in flight for the wavefront; 0 = automatic
    std::string device;                          // OpenCL device index or name substring; "" = prefer a GPU
    bool explain = false;                        // print the wavefront's features, build and state size
    Compaction compaction = kDefaultCompaction;  // the wavefront's queue filling
    unsigned lanes = 0;                          // paths per work item in the wavefront's stage kernels; 0 = automatic
    bool profile = false;                        // print the wavefront's per-kernel profile on stderr
    std::string profile_json;                    // also write the profile to this JSON file; "" = none
};

// --backend and the flags of every backend.
void add_backend_options(CLI::App& render, BackendOptions& options);

std::vector<std::string> backend_names();

// Renders with the backend named in `options` (already validated by the
// parser). Throws UsageError for an option the backend does not support.
RenderResult render_with_backend(const Scene& scene, const BackendOptions& options, const Progress& progress);

}  // namespace wp::cli
