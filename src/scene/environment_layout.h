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

// The texels' sampling weights, row by row (W x H): luminance, scale
// applied, times the mean of sin t over the texel's band of rows
// (kernels/shared/environment_map.h says why).
std::vector<double> environment_texel_weights(const EnvironmentMap& map);

// The same, scaled so that their bilinear blend is the sampling density
// over [0, 1)^2 in (u, v): over the cells' mean weight (a cell's weight the
// mean of its four texels').
std::vector<double> environment_texel_densities(const EnvironmentMap& map);

// The integral of the map's luminance over the sphere, as the weights'
// bilinear blend estimates it: the cells' mean weight times the map's area
// in solid angle per unit of (u, v), 2 pi^2 (a constant map's is exactly
// 4 pi times its luminance). 0 where no weight is positive: the map has no
// power to sample.
double environment_luminance_integral(const EnvironmentMap& map);

template <class Real>
struct EnvironmentLayout {
    typename SharedMath<Real>::EnvironmentMapLayout map{};
    // The texels, their densities, the rows' marginal cumulative distribution
    // and the texel rows' cumulative sums (environment_map.h's order); never
    // empty (the buffer exists without a map).
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
    const auto width = static_cast<std::size_t>(map.width), height = static_cast<std::size_t>(map.height);
    layout.map.width = static_cast<std::uint32_t>(map.width);
    layout.map.height = static_cast<std::uint32_t>(map.height);
    for (int i = 0; i < 9; ++i) layout.map.to_world[i] = static_cast<Real>(map.to_world[i % 3][i / 3]);
    for (float texel : map.texels) layout.data.push_back(static_cast<Real>(double(texel) * map.scale));
    const std::vector<double> densities = environment_texel_densities(map);
    for (double density : densities) layout.data.push_back(static_cast<Real>(density));
    std::vector<double> row_sums;  // each texel row's cumulative sums of its cells' edge densities
    for (std::size_t y = 0; y < height; ++y) {
        double sum = 0.0;
        for (std::size_t x = 0; x < width; ++x) {
            sum += 0.5 * (densities[y * width + x] + densities[y * width + (x + 1) % width]);
            row_sums.push_back(sum);
        }
    }
    auto row_total = [&](std::size_t y) { return row_sums[y * width + width - 1]; };
    std::vector<double> cell_rows(height - 1);
    for (std::size_t y = 0; y + 1 < height; ++y) cell_rows[y] = 0.5 * (row_total(y) + row_total(y + 1));
    for (double c : cumulative_distribution(cell_rows)) layout.data.push_back(static_cast<Real>(c));
    for (double sum : row_sums) layout.data.push_back(static_cast<Real>(sum));
    return layout;
}

}  // namespace wp
