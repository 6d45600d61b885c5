// The environment map as the shared code reads it (kernels/shared/environment_map.h):
// its texels with the scale applied and its sampling distribution, built in
// double and stored in one buffer, for one precision (the device upload
// takes float's, the reference its own Real's).
#pragma once

#include <cstdint>
#include <vector>

#include "core/shared_math.h"
#include "scene/scene.h"

namespace wp {

// The sampling cells' weights, row by row: W x (H - 1) cells, cell (x, y)
// the mean luminance of texels (x, y), (x + 1, y), (x, y + 1), (x + 1, y + 1)
// (columns wrapping), scale applied, times sin t at the cell's centre.
std::vector<double> environment_cell_weights(const EnvironmentMap& map);

// The integral of the map's luminance over the sphere, as the cells
// estimate it: their weights' sum times each cell's (2 pi / W) (pi / (H - 1)).
double environment_luminance_integral(const EnvironmentMap& map);

template <class Real>
struct EnvironmentLayout {
    typename SharedMath<Real>::EnvironmentMapLayout map{};
    // The texels, the marginal and the conditional cumulative distributions
    // (environment_map.h's order); never empty (the buffer exists without a map).
    std::vector<Real> data;
};

template <class Real>
EnvironmentLayout<Real> environment_layout(const Scene& scene) {
    EnvironmentLayout<Real> layout;
    if (!scene.environment_map) {
        layout.data.assign(1, Real(0));
        return layout;
    }
    const EnvironmentMap& map = *scene.environment_map;
    const auto width = static_cast<std::size_t>(map.width), rows = static_cast<std::size_t>(map.height - 1);
    layout.map.width = static_cast<std::uint32_t>(map.width);
    layout.map.height = static_cast<std::uint32_t>(map.height);
    for (int i = 0; i < 9; ++i) layout.map.to_world[i] = static_cast<Real>(map.to_world[i % 3][i / 3]);
    for (float texel : map.texels) layout.data.push_back(static_cast<Real>(double(texel) * map.scale));
    const std::vector<double> weights = environment_cell_weights(map);
    std::vector<double> row_weights(rows, 0.0);
    for (std::size_t y = 0; y < rows; ++y)
        for (std::size_t x = 0; x < width; ++x) row_weights[y] += weights[y * width + x];
    for (double c : cumulative_distribution(row_weights)) layout.data.push_back(static_cast<Real>(c));
    for (std::size_t y = 0; y < rows; ++y) {
        std::vector<double> row(weights.begin() + std::ptrdiff_t(y * width),
                                weights.begin() + std::ptrdiff_t((y + 1) * width));
        for (double c : cumulative_distribution(row)) layout.data.push_back(static_cast<Real>(c));
    }
    return layout;
}

}  // namespace wp
