// The renderers the CLI can run, by name, and `auto` (the default), which
// picks one for the device and the scene (cli/backend_choice.h). Adding a
// backend means adding its options to BackendOptions, its flags to
// add_backend_options and one entry to the table in backends.cpp; nothing
// else in the CLI changes.
#pragma once

#include <CLI/CLI.hpp>
#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "cli/backend_choice.h"
#include "core/film_renderer.h"
#include "core/render.h"
#include "scene/scene.h"
#include "wavefront/compaction.h"

namespace wp::cli {

struct BackendOptions {
    std::string name = "auto";                 // a backend, or "auto" until resolve_backend names one
    std::optional<BackendChoice> chosen;       // how auto chose `name`; none when --backend named it
    std::vector<LimitingFlag> limiting_flags;  // flags given that only some backends take
    int threads = 0;                           // CPU threads for the reference; 0 = all hardware threads
    std::string precision = "float";
    std::string intersector;                     // "embree" or "bvh"; "" = the backend's fastest
    std::size_t wavefront = 0;                   // paths in flight for the wavefront; 0 = automatic
    std::string device;                          // OpenCL device index or name substring; "" = prefer a GPU
    bool explain = false;                        // print the backend chosen and why, its build and state size
    Compaction compaction = kDefaultCompaction;  // the wavefront's queue filling
    unsigned lanes = 0;                          // paths per work item in the OpenCL backends' kernels; 0 = automatic
    bool profile = false;                        // print the wavefront's per-kernel profile on stderr
    std::string profile_json;                    // also write the profile to this JSON file; "" = none
    bool film_squares = false;                   // the film keeps sums of squares (set by the render command)
};

// --backend and the flags of every backend.
void add_backend_options(CLI::App& render, BackendOptions& options);

// The backends' names (not "auto").
std::vector<std::string> backend_names();

// `options` with --backend auto resolved for this scene on the device
// --device names: the highest-ranked backend in the table of
// cli/backend_choice.h that takes every flag given (--wavefront and
// --compaction only the wavefront; --lanes, --profile and --profile-json
// the OpenCL backends; --threads, --precision and --intersector embree the
// reference). The choice depends on the device kind, the scene and the
// flags alone, so a checkpoint resumes with the same one. Throws
// DeviceError when there is no such device, UsageError when no backend
// takes all the flags given.
BackendOptions resolve_backend(const BackendOptions& options, const Scene& scene);

// What a film from this backend's estimator is, for checkpoints and partial
// films: "opencl" (wavefront and megakernel agree bit for bit, tracing with
// the OpenCL BVH), "reference-float" or "reference-double"; tracing with
// Embree, "opencl-embree" for the wavefront and "reference-embree" (float)
// for the reference (for the wavefront's default intersector, the one
// default_intersector picks for the device and `scene`).
std::string estimator_name(const BackendOptions& options, const Scene& scene);

// What the command does with the backend's FilmRenderer once it is set up.
using FilmRun = std::function<void(FilmRenderer& renderer)>;

// Sets up the backend named in `options` (resolved), calls `run` with it,
// then prints or writes its profile and --explain as asked. `max_items` (0: pixels x spp) sizes the automatic
// wavefront. Throws UsageError for an option the backend does not support.
void run_with_backend(const Scene& scene, const BackendOptions& options, const Progress& progress,
                      std::uint64_t max_items, const FilmRun& run);

}  // namespace wp::cli
