// e^x, ln x, erf and erfinv written out in the shared code
// (kernels/shared/special_functions.h), float and double, against std::
// over their domains; and the rule that makes them necessary: no shared
// header calls a transcendental function of the library.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <numbers>
#include <regex>
#include <string>
#include <type_traits>

#include "core/shared_math.h"
#include "support/kernel_sources.h"
#include "support/real_types.h"

namespace {
// A namespace of its own: the sanitizer build compiles test files together (unity).
namespace special_functions_test {

template <class Real>
class SpecialFunctions : public ::testing::Test {};
TYPED_TEST_SUITE(SpecialFunctions, wp::test::RealTypes, wp::test::RealTypeNames);

// Float's unit in the last place at 1 (2^-23), the unit of the relative
// errors below: the functions are float-accurate in both precisions (the
// double build runs the same polynomials).
constexpr double kFloatUlp = std::numeric_limits<float>::epsilon();

// |computed - exact| / |exact|, with exact in double.
double relative_error(double computed, double exact) { return std::fabs(computed - exact) / std::fabs(exact); }

// erfinv in double, by bisection on std::erf, or on std::erfc beyond 1/2,
// where erf's value has lost the digits of 1 - |y|.
double reference_erfinv(double y) {
    double low = 0.0, high = 10.0;
    for (int i = 0; i < 200; ++i) {
        double x = 0.5 * (low + high);
        bool below = std::fabs(y) > 0.5 ? std::erfc(x) > 1.0 - std::fabs(y) : std::erf(x) < std::fabs(y);
        (below ? low : high) = x;
    }
    return std::copysign(0.5 * (low + high), y);
}

TYPED_TEST(SpecialFunctions, ExpIsFloatAccurateWhereItsValueIsANormalFloat) {
    using M = wp::SharedMath<TypeParam>;
    double worst = 0.0;
    for (int i = 0; i <= 100000; ++i) {
        const double x = TypeParam(-87.0 + 175.0 * i / 100000);
        worst = std::max(worst, relative_error(M::wp_exp(TypeParam(x)), std::exp(x)));
    }
    EXPECT_LT(worst, kFloatUlp);  // measured: 0.76 in float, 0.002 in double
    EXPECT_EQ(M::wp_exp(TypeParam(0)), TypeParam(1));
    EXPECT_EQ(M::wp_exp(TypeParam(-90)), TypeParam(0));
    EXPECT_EQ(M::wp_exp(-std::numeric_limits<TypeParam>::infinity()), TypeParam(0));
}

TYPED_TEST(SpecialFunctions, LogIsFloatAccurateOverTheNormalFloats) {
    using M = wp::SharedMath<TypeParam>;
    double worst = 0.0;
    for (int i = 0; i <= 100000; ++i) {
        const double x = TypeParam(std::exp2(-126.0 + 253.9 * i / 100000));
        if (x != 1.0) worst = std::max(worst, relative_error(M::wp_log(TypeParam(x)), std::log(x)));
    }
    for (int i = -1000; i <= 1000; ++i) {  // near 1, where ln x is small
        const double x = TypeParam(1.0 + 1e-3 * i / 1000);
        if (x != 1.0) worst = std::max(worst, relative_error(M::wp_log(TypeParam(x)), std::log(x)));
    }
    EXPECT_LT(worst, 2 * kFloatUlp);  // measured: 1.5 in float, 0.0004 in double
    EXPECT_EQ(M::wp_log(TypeParam(1)), TypeParam(0));
    EXPECT_NEAR(M::wp_log(TypeParam(0)), std::log(std::exp2(-126.0)), 1e-4) << "clamped to the smallest normal";
}

TYPED_TEST(SpecialFunctions, ErfIsFloatAccurate) {
    using M = wp::SharedMath<TypeParam>;
    double worst = 0.0;
    for (int i = -60000; i <= 60000; ++i) {
        const double x = TypeParam(6.0 * i / 60000);
        if (x == 0.0) continue;
        worst = std::max(worst, relative_error(M::wp_erf(TypeParam(x)), std::erf(x)));
    }
    EXPECT_LT(worst, 3 * kFloatUlp);  // measured: 2.4 in float, 0.5 in double (the fit's own error)
    EXPECT_EQ(M::wp_erf(TypeParam(0)), TypeParam(0));
    EXPECT_EQ(M::wp_erf(std::numeric_limits<TypeParam>::infinity()), TypeParam(1));
    EXPECT_EQ(M::wp_erf(-std::numeric_limits<TypeParam>::infinity()), TypeParam(-1));
}

TYPED_TEST(SpecialFunctions, ErfinvIsFloatAccurateUpToItsEnds) {
    using M = wp::SharedMath<TypeParam>;
    double worst = 0.0;
    for (int i = -20000; i <= 20000; ++i) {
        const double y = TypeParam(0.9999 * i / 20000);
        if (y == 0.0) continue;
        worst = std::max(worst, relative_error(M::wp_erfinv(TypeParam(y)), reference_erfinv(y)));
    }
    for (int k = 14; k <= 23; ++k) {  // 1 - 2^-k: the tail, up to float's last value below 1
        const double y = 1.0 - std::exp2(-k);
        worst = std::max(worst, relative_error(M::wp_erfinv(TypeParam(y)), reference_erfinv(y)));
        worst = std::max(worst, relative_error(M::wp_erfinv(TypeParam(-y)), reference_erfinv(-y)));
    }
    EXPECT_LT(worst, 3 * kFloatUlp);  // measured: 2.1 in float, 1.0 in double (the fit's own error)
    EXPECT_EQ(M::wp_erfinv(TypeParam(0)), TypeParam(0));
}

// erfinv inverts erf: erf(erfinv(y)) == y within float's accuracy.
TYPED_TEST(SpecialFunctions, ErfinvInvertsErf) {
    using M = wp::SharedMath<TypeParam>;
    for (int i = -999; i <= 999; ++i) {
        const TypeParam y = TypeParam(i / 1000.0);
        EXPECT_NEAR(M::wp_erf(M::wp_erfinv(y)), y, 4 * kFloatUlp) << y;
    }
}

// atan2 in turns against std::atan2 over every quadrant and several radii.
TYPED_TEST(SpecialFunctions, Atan2TurnsMatchesTheLibrary) {
    using R = TypeParam;
    using M = wp::SharedMath<R>;
    const double tolerance = std::is_same_v<R, float> ? 2e-7 : 1e-9;
    for (int i = 0; i < 4000; ++i) {
        const double angle = 2.0 * std::numbers::pi * (i + 0.37) / 4000.0, radius = 1.0 + (i % 7);
        const R y = R(radius * std::sin(angle)), x = R(radius * std::cos(angle));
        double expected = std::atan2(double(y), double(x)) / (2.0 * std::numbers::pi);
        if (expected < 0) expected += 1.0;
        EXPECT_NEAR(M::atan2_turns(y, x), expected, tolerance) << "angle " << angle;
    }
    EXPECT_EQ(M::atan2_turns(R(0), R(0)), R(0));
}

// The shared code (kernels/shared, every header) calls no exp, log, pow, erf,
// sin, cos, tan or their kin: their last bits differ between libm and PoCL,
// and the backends must agree bit for bit. Comments may name them.
TEST(SharedCode, CallsNoTranscendentalFunctionOfTheLibrary) {
    const std::regex call(
        R"re(\b(exp|exp2|expm1|log|log2|log10|log1p|pow|erf|erfc|erfinv|sin|cos|tan|asin|acos|atan|atan2|sinh|cosh|tanh|sincos|tgamma|lgamma|cbrt|hypot)\s*\()re");
    int headers = 0;
    for (const auto& entry : std::filesystem::recursive_directory_iterator(wp::test::kKernelDirectory / "shared")) {
        if (!entry.is_regular_file()) continue;
        const std::string code = wp::test::without_comments(wp::test::read_text(entry.path()));
        std::smatch m;
        EXPECT_FALSE(std::regex_search(code, m, call)) << entry.path() << " calls " << m.str();
        ++headers;
    }
    EXPECT_GE(headers, 20);
}

}  // namespace special_functions_test
}  // namespace
