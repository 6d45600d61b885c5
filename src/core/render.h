// What every backend produces: a linear RGB image and the figures of the run.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

namespace wp {

// Linear RGB, row-major, top row first, 3 floats per pixel.
struct Image {
    int width = 0;
    int height = 0;
    std::vector<float> rgb;
};

struct RenderStats {
    double time_s = 0.0;
    std::uint64_t samples = 0;         // camera samples (pixels x spp)
    std::uint64_t extension_rays = 0;  // camera and bounce rays
    std::uint64_t shadow_rays = 0;
    std::uint64_t nonfinite = 0;       // samples whose radiance was NaN or Inf, dropped and counted
};

struct RenderResult {
    Image image;
    RenderStats stats;
};

// Called with the fraction of samples done, from any thread, possibly often.
using ProgressFn = std::function<void(double fraction_done)>;

}  // namespace wp
