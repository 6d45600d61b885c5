// SPPM's per-pixel rules (kernels/shared/sppm.h), float and double, against
// values worked out by hand: the progressive update of a pixel's photon
// count N, radius r and flux tau (sppm_pixel_update, Hachisuka and Jensen
// 2009, eq. 7 and 11, with alpha = 2/3), and the first radius a pixel takes
// from its footprint (sppm_footprint, sppm_first_radius). Exact rules, so
// the checks allow only rounding (kRoundingTolerance): a radius that never
// shrinks, an update that ignores alpha, or flux that is not rescaled with
// the disc each fail them by a constant factor.
#include <gtest/gtest.h>

#include <cmath>

#include "core/shared_math.h"
#include "support/real_types.h"

namespace {
// A namespace of its own: the sanitizer build compiles test files together (unity).
namespace sppm_test {

using wp::test::kRoundingTolerance;

template <class Real>
class Sppm : public ::testing::Test {};
TYPED_TEST_SUITE(Sppm, wp::test::RealTypes, wp::test::RealTypeNames);

// k updates of M = 6 photons each, alpha = 2/3, from r0 = 1, N = 0, tau = 0,
// each bringing flux Phi = (1, 2, 3). Update i (i = 1, 2, ...) starts from
// N = 4 (i - 1) and makes N' = N + 4 = 4 i; the disc shrinks by
// r'^2 / r^2 = N' / (N + M) = 4 i / (4 i + 2) = 2 i / (2 i + 1), so
//   r_k^2 = prod_{i <= k} 2 i / (2 i + 1):  2/3, 8/15, 16/35, 128/315, ...
// and tau_k = (tau_{k-1} + Phi) 2 k / (2 k + 1), which is tau_k = 2 k / 3 Phi
// (by induction: (2 (k - 1) / 3 + 1) 2 k / (2 k + 1) = (2 k + 1) / 3 x 2 k / (2 k + 1)).
TYPED_TEST(Sppm, RadiusCountAndFluxAfterKEqualUpdates) {
    using R = TypeParam;
    using M = wp::SharedMath<R>;
    const double squared_radius[] = {2.0 / 3.0, 8.0 / 15.0, 16.0 / 35.0, 128.0 / 315.0};
    typename M::SppmPixel pixel{R(0), R(1), typename M::vec3(R(0))};
    const typename M::vec3 phi(R(1), R(2), R(3));
    for (int k = 1; k <= 4; ++k) {
        pixel = M::sppm_pixel_update(pixel, 6u, phi, R(2.0 / 3.0));
        const double tol = kRoundingTolerance<R>;
        EXPECT_NEAR(double(pixel.count), 4.0 * k, tol * 4.0 * k) << k;
        EXPECT_NEAR(double(pixel.radius), std::sqrt(squared_radius[k - 1]), tol) << k;
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(double(pixel.flux[c]), 2.0 * k / 3.0 * (c + 1), tol * 3.0 * k) << k;
    }
}

// Uneven counts, from r0 = 0.5, alpha = 2/3: M = 3 (N 0 -> 2, r^2 0.25 -> 0.25
// x 2/3 = 1/6, tau = 3 x 2/3 = 2 from Phi = 3), M = 0 (nothing changes, even
// with flux offered), M = 6 (N 2 -> 6, r^2 1/6 x 6/8 = 1/8, tau (2 + 9) x 3/4
// = 33/4 from Phi = 9).
TYPED_TEST(Sppm, UnevenUpdatesAndAnIterationWithoutPhotons) {
    using R = TypeParam;
    using M = wp::SharedMath<R>;
    using vec3 = typename M::vec3;
    const R alpha = R(2.0 / 3.0);
    const double tol = kRoundingTolerance<R>;
    typename M::SppmPixel pixel{R(0), R(0.5), vec3(R(0))};
    pixel = M::sppm_pixel_update(pixel, 3u, vec3(R(3), R(0), R(1.5)), alpha);
    EXPECT_NEAR(double(pixel.count), 2.0, 2 * tol);
    EXPECT_NEAR(double(pixel.radius), std::sqrt(1.0 / 6.0), tol);
    EXPECT_NEAR(double(pixel.flux[0]), 2.0, 2 * tol);
    EXPECT_EQ(double(pixel.flux[1]), 0.0);
    EXPECT_NEAR(double(pixel.flux[2]), 1.0, tol);
    const typename M::SppmPixel before = pixel;
    pixel = M::sppm_pixel_update(pixel, 0u, vec3(R(5)), alpha);
    EXPECT_EQ(pixel.count, before.count);
    EXPECT_EQ(pixel.radius, before.radius);
    EXPECT_EQ(pixel.flux, before.flux);
    pixel = M::sppm_pixel_update(pixel, 6u, vec3(R(9), R(0), R(0)), alpha);
    EXPECT_NEAR(double(pixel.count), 6.0, 6 * tol);
    EXPECT_NEAR(double(pixel.radius), std::sqrt(1.0 / 8.0), tol);
    EXPECT_NEAR(double(pixel.flux[0]), 33.0 / 4.0, 9 * tol);
    EXPECT_NEAR(double(pixel.flux[2]), 0.75, tol);
}

// The footprint is the cone's spread times the distance; the first radius
// two footprints (WP_SPPM_FOOTPRINTS), or the override where one is set.
TYPED_TEST(Sppm, FirstRadiusIsTwoFootprintsUnlessOverridden) {
    using R = TypeParam;
    using M = wp::SharedMath<R>;
    EXPECT_EQ(M::sppm_footprint(R(0.125), R(3)), R(0.375));
    EXPECT_EQ(M::sppm_first_radius(R(0), R(0.375)), R(0.75));
    EXPECT_EQ(M::sppm_first_radius(R(0.01), R(0.375)), R(0.01));
    EXPECT_EQ(M::sppm_first_radius(R(0), R(3e-9)), R(6e-9));  // no floor: units are the scene's
}

}  // namespace sppm_test
}  // namespace
