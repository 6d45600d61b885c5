// SPPM on the wavefront (docs/architecture.md, "Photon mapping"): its state
// on the device (wavefront/sppm_state.h) and the kernels of an iteration
// besides the stages: the grid over the visible points (kernels/photon_grid.cl)
// and every pixel's update (kernels/sppm_update.cl). The camera pass and the
// photon pass are the stages' (wavefront/scheduler.h).
#pragma once

#include <CL/opencl.hpp>
#include <cstdint>

#include "core/film.h"
#include "opencl/launcher.h"
#include "opencl/scene_upload.h"
#include "wavefront/sppm_state.h"

namespace wp {

class SppmPass {
 public:
    // `program` holds the grid and update kernels, built with -DWP_LANES=lanes
    // and -DWP_SPPM for the scene's `features`; `counts` is the queues' counters (WP_COUNTER_PHOTON_DEPOSITS).
    // Every pixel starts with no photon and no radius (0: its first visible
    // point sets it, sppm_first_radius in kernels/shared/sppm.h).
    SppmPass(const cl::Context& context, cl::CommandQueue& queue, const cl::Program& program, const DeviceScene& scene,
             const cl::Buffer& counts, std::uint64_t pixels, unsigned lanes, const FeatureSet& features);

    const SppmState& state() const { return state_; }
    // Before an iteration's camera pass: no visible point, nothing gathered.
    void begin_iteration();
    // The grid over the iteration's visible points; false where no pixel has
    // one (no photon could add to any: the photon pass is skipped).
    bool build_grid(KernelLauncher& launcher);
    // After the photon pass: every pixel's N, r and tau.
    void update(KernelLauncher& launcher);
    // The estimate as a film holds it (the device's floats, exactly), and replacing it.
    PhotonEstimate read(std::uint64_t photons_per_iteration);
    void load(const PhotonEstimate& estimate);

 private:
    void launch_over_pixels(KernelLauncher& launcher, cl::Kernel& kernel, const char* name);

    cl::CommandQueue& queue_;
    SppmState state_;
    unsigned lanes_;
    cl::Kernel bounds_, count_, scan_blocks_, scan_top_, scan_write_, fill_, update_;
};

}  // namespace wp
