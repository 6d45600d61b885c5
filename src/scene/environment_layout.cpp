#include "scene/environment_layout.h"

#include <cmath>
#include <numbers>

namespace wp {
namespace {
namespace environment_layout {

double texel_luminance(const EnvironmentMap& map, std::size_t x, std::size_t y) {
    const float* rgb = &map.texels[3 * (y * std::size_t(map.width) + x % std::size_t(map.width))];
    return map.scale * (0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2]);
}

// The mean of sin t over texel row y's band, [t_y - d/2, t_y + d/2] within
// [0, pi] (d = pi / (H - 1)): 2 sin(t_y) sin(d/2) / d inside, and
// (1 - cos(d/2)) / (d/2) at the poles, where sin(t_y) is 0.
double band_mean_sin(std::size_t y, std::size_t rows) {
    const double d = std::numbers::pi / double(rows), theta = d * double(y);
    const double top = std::max(theta - 0.5 * d, 0.0), bottom = std::min(theta + 0.5 * d, std::numbers::pi);
    return (std::cos(top) - std::cos(bottom)) / (bottom - top);
}

// The cells' mean weight: each cell's is the mean of its four texels'.
double mean_cell_weight(const std::vector<double>& weights, std::size_t width, std::size_t rows) {
    double total = 0.0;
    for (std::size_t y = 0; y < rows; ++y)
        for (std::size_t x = 0; x < width; ++x)
            total += weights[y * width + x] + weights[y * width + (x + 1) % width] + weights[(y + 1) * width + x] +
                     weights[(y + 1) * width + (x + 1) % width];
    return 0.25 * total / double(width * rows);
}

}  // namespace environment_layout
}  // namespace

std::vector<double> environment_texel_weights(const EnvironmentMap& map) {
    using environment_layout::band_mean_sin;
    const auto width = static_cast<std::size_t>(map.width), height = static_cast<std::size_t>(map.height);
    std::vector<double> weights(width * height);
    for (std::size_t y = 0; y < height; ++y) {
        const double sin_theta = band_mean_sin(y, height - 1);
        for (std::size_t x = 0; x < width; ++x)
            weights[y * width + x] = environment_layout::texel_luminance(map, x, y) * sin_theta;
    }
    return weights;
}

std::vector<double> environment_texel_densities(const EnvironmentMap& map) {
    const auto width = static_cast<std::size_t>(map.width), rows = static_cast<std::size_t>(map.height - 1);
    std::vector<double> densities = environment_texel_weights(map);
    const double mean = environment_layout::mean_cell_weight(densities, width, rows);
    for (double& density : densities) density /= mean;
    return densities;
}

double environment_luminance_integral(const EnvironmentMap& map) {
    const auto width = static_cast<std::size_t>(map.width), rows = static_cast<std::size_t>(map.height - 1);
    const double mean = environment_layout::mean_cell_weight(environment_texel_weights(map), width, rows);
    return mean * 2.0 * std::numbers::pi * std::numbers::pi;
}

}  // namespace wp
