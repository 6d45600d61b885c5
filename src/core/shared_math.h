// The shared math of kernels/shared/ compiled as C++, once per precision.
// The code is included inside a class template, so its functions become
// static members: wp::SharedMath<float> matches the OpenCL kernels and
// wp::SharedMath<double> is the double-precision build, and code templated
// on the scalar type reaches the right one through that alias.
#pragma once

#include <cmath>
#include <cstdint>
#include <glm/geometric.hpp>
#include <glm/vec3.hpp>
#include <limits>
#include <type_traits>

namespace wp::shared_math_detail {

// Scalar functions the shared code calls unqualified; vector ones (dot,
// cross, normalize, length) are found through glm by argument lookup.
using std::acos;
using std::atan2;
using std::copysign;
using std::cos;
using std::fabs;
using std::floor;
using std::fmax;
using std::fmin;
using std::isfinite;
using std::isinf;
using std::sin;
using std::sqrt;

// One instantiation per precision.
template <class Real>
struct Precision {
    using real = Real;
    using uint = std::uint32_t;
    using vec3 = glm::vec<3, real>;
    static constexpr real real_max = std::numeric_limits<real>::max();
    // Half an ulp of 1: the relative error of one rounding to nearest (2^-24, 2^-53).
    static constexpr real unit_roundoff = std::numeric_limits<real>::epsilon() / 2;
#include "shared/shared_math.h"
};

}  // namespace wp::shared_math_detail

namespace wp {
template <class Real>
using SharedMath = std::conditional_t<std::is_same_v<Real, float> || std::is_same_v<Real, double>,
                                      shared_math_detail::Precision<Real>, void>;
}  // namespace wp
