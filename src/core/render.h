// What every backend produces: a linear RGB image and the figures of the run.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <string_view>
#include <vector>

namespace wp {

// Linear RGB, row-major, top row first, 3 floats per pixel.
struct Image {
    int width = 0;
    int height = 0;
    std::vector<float> rgb;
};

// Where a non-finite value can arise; each backend checks it there, drops it
// and counts it (docs/robustness.md, "Guards"). Same order as the kernels'
// WP_COUNTER_NONFINITE_* counters (kernels/interface/queues.h).
enum class NonfiniteStage : std::size_t {
    emission,  // emission or background added to the radiance
    direct,    // a light sample's contribution added to the radiance
    scatter,   // throughput after BSDF sampling and roulette: the path ends
};
inline constexpr std::array<std::string_view, 3> nonfinite_stage_names{"emission", "direct", "scatter"};
using NonfiniteCounts = std::array<std::uint64_t, nonfinite_stage_names.size()>;

struct RenderStats {
    double time_s = 0.0;
    std::uint64_t samples = 0;         // camera samples (pixels x spp)
    std::uint64_t extension_rays = 0;  // camera and bounce rays
    std::uint64_t shadow_rays = 0;
    std::uint64_t photons = 0;             // SPPM: photons emitted (and traced)
    std::uint64_t photon_rays = 0;         // SPPM: the photons' rays
    std::uint64_t photon_deposits = 0;     // SPPM: photons stored at a pixel's visible point
    NonfiniteCounts nonfinite_by_stage{};  // non-finite values dropped, per NonfiniteStage
    std::uint64_t nonfinite = 0;           // their sum
    std::uint64_t threads = 0;             // CPU threads the reference backend rendered on; 0 for OpenCL

    void add_nonfinite(const NonfiniteCounts& counts) {
        for (std::size_t i = 0; i < counts.size(); ++i) {
            nonfinite_by_stage[i] += counts[i];
            nonfinite += counts[i];
        }
    }
};

struct RenderResult {
    Image image;
    RenderStats stats;
};

// What a renderer tells its user while it works. Either callback may be empty.
struct Progress {
    // A step before sampling that takes a while (building kernels), in words.
    std::function<void(std::string_view what)> step;
    // The fraction of samples done, from any thread, possibly often. Sampling
    // starts at the first call: renderers report 0 just before their first sample.
    std::function<void(double fraction_done)> samples;

    void announce(std::string_view what) const {
        if (step) step(what);
    }
    void report(double fraction_done) const {
        if (samples) samples(fraction_done);
    }
};

}  // namespace wp
