#include "wavefront/sppm_pass.h"

#include <array>
#include <stdexcept>
#include <vector>

#include "core/shared_math.h"
#include "interface/sppm_state.h"
#include "opencl/kernel_arguments.h"

namespace wp {

namespace {

cl::Kernel sppm_kernel(const cl::Program& program, const char* name, const DeviceScene& scene, const cl::Buffer& counts,
                       const SppmState& state) {
    cl::Kernel kernel(program, name);
    kernel.setArg(arg::Sppm::scene, scene.header());
    kernel.setArg(arg::Sppm::counts, counts);
    state.bind(kernel, arg::Sppm::count);
    return kernel;
}

}  // namespace

SppmPass::SppmPass(const cl::Context& context, cl::CommandQueue& queue, const cl::Program& program,
                   const DeviceScene& scene, const cl::Buffer& counts, std::uint64_t pixels, unsigned lanes,
                   const FeatureSet& features)
    : queue_(queue),
      state_(context, pixels, features),
      lanes_(lanes),
      bounds_(sppm_kernel(program, "grid_bounds", scene, counts, state_)),
      count_(sppm_kernel(program, "grid_count", scene, counts, state_)),
      scan_blocks_(sppm_kernel(program, "grid_scan_blocks", scene, counts, state_)),
      scan_top_(sppm_kernel(program, "grid_scan_top", scene, counts, state_)),
      scan_write_(sppm_kernel(program, "grid_scan_write", scene, counts, state_)),
      fill_(sppm_kernel(program, "grid_fill", scene, counts, state_)),
      update_(sppm_kernel(program, "sppm_update", scene, counts, state_)) {
    auto pixel_bytes = [&](std::size_t element) { return element * state_.elements(SppmSize::PIXELS); };
    queue_.enqueueFillBuffer(state_.field("sppm_count"), 0.0f, 0, pixel_bytes(sizeof(float)));
    queue_.enqueueFillBuffer(state_.field("sppm_radius"), 0.0f, 0, pixel_bytes(sizeof(float)));
    queue_.enqueueFillBuffer(state_.field("sppm_footprint"), 0.0f, 0, pixel_bytes(sizeof(float)));
    queue_.enqueueFillBuffer(state_.field("sppm_flux"), 0.0f, 0, pixel_bytes(3 * sizeof(float)));
}

void SppmPass::begin_iteration() {
    const std::uint64_t pixels = state_.elements(SppmSize::PIXELS);
    queue_.enqueueFillBuffer(state_.field("visible_depth"), std::uint32_t(WP_NO_VISIBLE_POINT), 0,
                             sizeof(std::uint32_t) * pixels);
    queue_.enqueueFillBuffer(state_.field("iteration_photons"), std::uint32_t(0), 0, sizeof(std::uint32_t) * pixels);
    queue_.enqueueFillBuffer(state_.field("iteration_flux"), std::uint32_t(0), 0,
                             sizeof(std::uint32_t) * state_.elements(SppmSize::DEPOSITS));
    queue_.enqueueFillBuffer(state_.field("grid_counts"), std::uint32_t(0), 0,
                             sizeof(std::uint32_t) * state_.elements(SppmSize::BUCKETS));
}

void SppmPass::launch_over_pixels(KernelLauncher& launcher, cl::Kernel& kernel, const char* name) {
    launcher.launch(kernel, name, divide_rounding_up(state_.pixels(), lanes_));
}

bool SppmPass::build_grid(KernelLauncher& launcher) {
    launcher.launch(bounds_, "grid_bounds", WP_GROUP_SIZE);
    std::array<float, 4> frame{};
    queue_.enqueueReadBuffer(state_.field("grid_frame"), CL_TRUE, 0, sizeof frame, frame.data());
    if (!(frame[3] > 0.0f)) return false;
    const std::size_t blocks = divide_rounding_up(state_.buckets(), WP_GRID_SCAN_BLOCK);
    launch_over_pixels(launcher, count_, "grid_count");
    launcher.launch(scan_blocks_, "grid_scan_blocks", blocks, 0);
    launcher.launch(scan_top_, "grid_scan_top", 1, 0);
    launcher.launch(scan_write_, "grid_scan_write", blocks, 0);
    launch_over_pixels(launcher, fill_, "grid_fill");
    return true;
}

void SppmPass::update(KernelLauncher& launcher) { launch_over_pixels(launcher, update_, "sppm_update"); }

PhotonEstimate SppmPass::read(std::uint64_t photons_per_iteration) {
    const std::uint64_t pixels = state_.pixels();
    std::vector<float> count(pixels), radius(pixels), footprint(pixels), flux(3 * pixels);
    queue_.enqueueReadBuffer(state_.field("sppm_count"), CL_TRUE, 0, sizeof(float) * pixels, count.data());
    queue_.enqueueReadBuffer(state_.field("sppm_radius"), CL_TRUE, 0, sizeof(float) * pixels, radius.data());
    queue_.enqueueReadBuffer(state_.field("sppm_footprint"), CL_TRUE, 0, sizeof(float) * pixels, footprint.data());
    queue_.enqueueReadBuffer(state_.field("sppm_flux"), CL_TRUE, 0, sizeof(float) * flux.size(), flux.data());
    PhotonEstimate estimate = PhotonEstimate::start(pixels, photons_per_iteration);
    for (std::uint64_t p = 0; p < pixels; ++p) {
        estimate.count[p] = count[p];
        estimate.radius[p] = radius[p];
        estimate.footprint[p] = footprint[p];
        for (std::uint64_t c = 0; c < 3; ++c) estimate.flux[3 * p + c] = flux[c * pixels + p];  // three planes
    }
    return estimate;
}

void SppmPass::load(const PhotonEstimate& estimate) {
    const std::uint64_t pixels = state_.pixels();
    if (estimate.count.size() != pixels) throw std::invalid_argument("SppmPass::load: an estimate of another size");
    std::vector<float> count(pixels), radius(pixels), footprint(pixels), flux(3 * pixels);
    for (std::uint64_t p = 0; p < pixels; ++p) {
        count[p] = static_cast<float>(estimate.count[p]);
        radius[p] = static_cast<float>(estimate.radius[p]);
        footprint[p] = static_cast<float>(estimate.footprint[p]);
        for (std::uint64_t c = 0; c < 3; ++c) flux[c * pixels + p] = static_cast<float>(estimate.flux[3 * p + c]);
    }
    queue_.enqueueWriteBuffer(state_.field("sppm_count"), CL_TRUE, 0, sizeof(float) * pixels, count.data());
    queue_.enqueueWriteBuffer(state_.field("sppm_radius"), CL_TRUE, 0, sizeof(float) * pixels, radius.data());
    queue_.enqueueWriteBuffer(state_.field("sppm_footprint"), CL_TRUE, 0, sizeof(float) * pixels, footprint.data());
    queue_.enqueueWriteBuffer(state_.field("sppm_flux"), CL_TRUE, 0, sizeof(float) * flux.size(), flux.data());
}

}  // namespace wp
