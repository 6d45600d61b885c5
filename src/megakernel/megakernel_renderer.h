// The megakernel baseline (--backend megakernel): kernels/megakernel.cl traces
// whole paths, one work item per sample (or, as vector code, 4, 8 or 16:
// lanes, as the wavefront's stages on CPUs), on the same device, with the same
// per-vertex code, random numbers and deterministic accumulation as the
// wavefront, so the two designs are compared like for like.
#pragma once

#include <memory>
#include <string>

#include "core/film_renderer.h"
#include "core/render.h"
#include "opencl/device.h"
#include "opencl/profile.h"
#include "opencl/program_cache.h"
#include "scene/scene.h"

namespace wp {

struct MegakernelOptions {
    std::string device;         // as WavefrontOptions::device
    bool profile = false;       // time the launches with OpenCL events
    bool film_squares = false;  // the film keeps sums of squares (per-pixel variance)
    unsigned lanes = 0;         // paths per work item: 1, 4, 8 or 16; 0: resolve_lanes' choice (opencl/lanes.h)
};

struct MegakernelReport {
    std::string device;
    std::string build_options;
    bool cache_hit = false;
    double build_seconds = 0.0;
    std::string cache_file;
    unsigned lanes = 1;     // paths per work item
    RenderProfile profile;  // kernels "megakernel" and "accumulate", when profiling

    std::string explain() const;  // what --explain prints
};

// The program make_megakernel_renderer builds for `scene` with `options` on
// `device`, without building it (as wavefront_program). Throws
// std::invalid_argument for lanes it cannot take and for the sppm integrator.
KernelProgram megakernel_program(const Scene& scene, const MegakernelOptions& options, const DeviceInfo& device);

// Renders on OpenCL; throws DeviceError (no device, kernel build failure).
RenderResult render_megakernel(const Scene& scene, const MegakernelOptions& options, const Progress& progress,
                               MegakernelReport* report = nullptr);

// The megakernel as a FilmRenderer (as make_wavefront_renderer).
std::unique_ptr<FilmRenderer> make_megakernel_renderer(const Scene& scene, const MegakernelOptions& options,
                                                       const Progress& progress, MegakernelReport* report = nullptr);

}  // namespace wp
