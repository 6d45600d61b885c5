// The scalar types the shared math and the reference renderer are built for,
// for GoogleTest typed tests: TYPED_TEST_SUITE(Suite, wp::test::RealTypes, wp::test::RealTypeNames).
#pragma once

#include <gtest/gtest.h>

#include <limits>
#include <string>
#include <type_traits>

#include "core/shared_math.h"

namespace wp::test {

using RealTypes = ::testing::Types<float, double>;

struct RealTypeNames {
    template <class Real>
    static std::string GetName(int) {
        return std::is_same_v<Real, float> ? "Float" : "Double";
    }
};

template <class Real>
using Vec3 = typename SharedMath<Real>::vec3;

// A few dozen roundings: the tolerance of checks on short formulas.
template <class Real>
constexpr double kRoundingTolerance = 64.0 * std::numeric_limits<Real>::epsilon();

}  // namespace wp::test
