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

}  // namespace environment_layout
}  // namespace

std::vector<double> environment_cell_weights(const EnvironmentMap& map) {
    using environment_layout::texel_luminance;
    const auto width = static_cast<std::size_t>(map.width), rows = static_cast<std::size_t>(map.height - 1);
    std::vector<double> weights(width * rows);
    for (std::size_t y = 0; y < rows; ++y) {
        const double sin_theta = std::sin(std::numbers::pi * (double(y) + 0.5) / double(rows));
        for (std::size_t x = 0; x < width; ++x) {
            const double corners = texel_luminance(map, x, y) + texel_luminance(map, x + 1, y) +
                                   texel_luminance(map, x, y + 1) + texel_luminance(map, x + 1, y + 1);
            weights[y * width + x] = 0.25 * corners * sin_theta;
        }
    }
    return weights;
}

double environment_luminance_integral(const EnvironmentMap& map) {
    double total = 0.0;
    for (double weight : environment_cell_weights(map)) total += weight;
    return total * (2.0 * std::numbers::pi / double(map.width)) * (std::numbers::pi / double(map.height - 1));
}

}  // namespace wp
