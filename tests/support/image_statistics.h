// Per-channel statistics over the pixels of a rendered image. Pixels are
// independent estimates (their random numbers never overlap), so where all
// selected pixels share one expected value, their spread gives the standard
// error of their mean.
#pragma once

#include <algorithm>
#include <cmath>
#include <functional>

#include "core/render.h"
#include "support/statistics.h"

namespace wp::test {

inline float pixel_channel(const Image& image, int x, int y, int channel) {
    return image.rgb[3 * (static_cast<std::size_t>(y) * image.width + x) + channel];
}

// Mean and standard error of one channel over the pixels `keep` accepts.
inline RunningMean channel_mean(
    const Image& image, int channel, const std::function<bool(int, int)>& keep = [](int, int) { return true; }) {
    RunningMean mean;
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x)
            if (keep(x, y)) mean.add(pixel_channel(image, x, y, channel));
    return mean;
}

// The fraction of pixels whose three channels all agree within `relative`
// (of the larger magnitude) between two images of the same size.
inline double fraction_of_pixels_within(const Image& a, const Image& b, double relative) {
    std::size_t pixels = a.rgb.size() / 3, agreeing = 0;
    for (std::size_t p = 0; p < pixels; ++p) {
        bool all = true;
        for (int c = 0; c < 3; ++c) {
            double x = a.rgb[3 * p + c], y = b.rgb[3 * p + c];
            all = all && std::fabs(x - y) <= relative * std::max(std::fabs(x), std::fabs(y)) + 1e-30;
        }
        agreeing += all;
    }
    return pixels ? double(agreeing) / double(pixels) : 0.0;
}

}  // namespace wp::test
