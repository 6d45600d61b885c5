// The constants of a scene's pixel filter for kernels/shared/pixel_filter.h,
// computed once in double and rounded to the precision that renders: every
// backend reads the same values.
#pragma once

#include <cmath>
#include <numbers>

#include "core/shared_math.h"
#include "scene/scene.h"

namespace wp {

template <class Real>
typename SharedMath<Real>::PixelFilter pixel_filter_constants(const PixelFilter& filter) {
    typename SharedMath<Real>::PixelFilter f{};
    switch (filter.type) {
        case FilterType::Box:
            f.type = WP_FILTER_BOX;
            break;
        case FilterType::Tent:
            f.type = WP_FILTER_TENT;
            f.radius = Real(filter.radius);
            break;
        case FilterType::Gaussian:
            f.type = WP_FILTER_GAUSSIAN;
            f.scale = Real(filter.stddev * std::numbers::sqrt2);
            f.erf_radius = Real(std::erf(4.0 / std::numbers::sqrt2));  // the window, 4 stddev, over the scale
            break;
    }
    return f;
}

}  // namespace wp
