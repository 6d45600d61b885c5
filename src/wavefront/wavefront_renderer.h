// The OpenCL wavefront backend: the default renderer of wavepath.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "accel/embree_intersector.h"
#include "core/film_renderer.h"
#include "core/render.h"
#include "opencl/device.h"
#include "opencl/profile.h"
#include "opencl/program_cache.h"
#include "scene/scene.h"
#include "wavefront/compaction.h"
#include "wavefront/stage.h"

namespace wp {

struct WavefrontOptions {
    std::string device = "";    // "" (prefer a GPU), an index, or a name substring
    std::size_t wavefront = 0;  // paths in flight; 0 = chosen from device memory and image size
    bool specialise = true;     // compile only the scene's features (false: every shape and material, for comparison)
    bool profile = false;       // time every kernel (WavefrontReport::profile)
    Compaction compaction = kDefaultCompaction;
    unsigned lanes = 0;         // paths per work item in the stage kernels (1, 4, 8 or 16); 0 = resolve_lanes' choice
    bool film_squares = false;  // the film keeps sums of squares (per-pixel variance, --target-error)
    // What traces the rays: the OpenCL BVH in the kernels, or Embree on the
    // host (CPU devices only; wavefront/host_trace.h). Unset:
    // default_intersector's choice for the device and the scene (wavefront/intersector_choice.h).
    std::optional<Intersector> intersector = std::nullopt;
    // Whether next-event estimation's shadow rays go to a stage of their own
    // (intersect_shadow) or shade traces them. Unset: their own stage where
    // the host traces them (which needs it) and on GPUs, shade on CPUs
    // (kernels/interface/stages.h, docs/architecture.md "Shadow rays").
    std::optional<bool> shadow_stage = std::nullopt;
    // Whether one kernel traces the extension rays and shades their hits
    // (intersect_and_shade) or intersect and shade run apart. Unset: one
    // kernel on CPUs with scan compaction (which it needs), apart otherwise
    // (kernels/interface/stages.h, docs/architecture.md "Intersect and shade
    // as one kernel").
    std::optional<bool> intersect_and_shade = std::nullopt;
};

// Queue lengths of one iteration of a stage loop, for the profiler: of the
// camera pass, or of SPPM's photon pass (whose photons take the paths' words).
struct IterationRecord {
    StageLoop loop = StageLoop::CAMERA;
    std::uint32_t generated = 0;   // camera rays started (photons emitted)
    std::uint32_t traced = 0;      // extension rays intersected
    std::uint32_t hits = 0;        // of those, hits (to shade, shade_photons; 0 with intersect_and_shade)
    std::uint32_t shadow = 0;      // shadow rays
    std::uint32_t continuing = 0;  // paths that scattered on
    std::uint32_t finished = 0;    // paths that ended

    // The entries the iteration's stages took from `queue` (kernels/interface/queues.h).
    std::uint32_t taken_from(std::uint32_t queue) const;
};

// What --explain prints, and the profile of the run.
struct WavefrontReport {
    std::string device;
    std::string features;
    std::string build_options;
    bool cache_hit = false;
    double build_seconds = 0.0;
    std::string cache_file;
    std::size_t wavefront = 0;
    std::size_t pass_capacity = 0;
    std::size_t state_bytes_per_path = 0;
    unsigned lanes = 1;    // paths per work item in the stage kernels
    std::string meshes;    // MeshSummary::describe(), "" without meshes
    std::string textures;  // describe_textures, "" without textures
    Intersector intersector = Intersector::Bvh;
    std::string intersector_reason;  // why: asked for, or default_intersector's reason
    std::vector<IterationRecord> iterations;
    RenderProfile profile;  // filled when WavefrontOptions::profile

    std::string explain() const;
};

// Renders on OpenCL; throws DeviceError (no device, kernel build failure).
RenderResult render_wavefront(const Scene& scene, const WavefrontOptions& options, const Progress& progress,
                              WavefrontReport* report = nullptr);

// The wavefront as a FilmRenderer: the device is chosen and the kernels built
// here; `report` (if any) is filled now and, for the profile, by finish().
// `max_items` (the most work items it will render, 0: pixels x spp) sizes
// the automatic wavefront. Throws DeviceError.
std::unique_ptr<FilmRenderer> make_wavefront_renderer(const Scene& scene, const WavefrontOptions& options,
                                                      const Progress& progress, WavefrontReport* report = nullptr,
                                                      std::uint64_t max_items = 0);

// The program make_wavefront_renderer builds for `scene` with `options` on
// `device`, without building it (of the device, only its type, name and
// preferred vector width count): for listing every program the renderer can
// build (tests/gpu_compile). Throws as make_wavefront_renderer does for
// options that the device or the scene cannot take.
KernelProgram wavefront_program(const Scene& scene, const WavefrontOptions& options, const DeviceInfo& device);

// The automatic --wavefront size: up to 2^16 paths on a CPU and 2^20 on
// other devices, no more than the work (pixels x spp), and the state within
// a quarter of the device's memory.
std::size_t default_wavefront_size(std::uint64_t work_items, std::size_t bytes_per_path, const DeviceInfo& device);

}  // namespace wp
