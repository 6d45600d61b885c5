// The pinhole camera (kernels/shared/camera.h), float and double.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "core/shared_math.h"
#include "support/directions.h"
#include "support/real_types.h"

namespace {

using wp::test::kRoundingTolerance;
using wp::test::Vec3;
constexpr double kPi = std::numbers::pi;

template <class Real>
class Camera : public ::testing::Test {};
TYPED_TEST_SUITE(Camera, wp::test::RealTypes, wp::test::RealTypeNames);

// From every side, with ups that lean towards the view: forward points at
// look_at, the basis is orthonormal and right-handed with right = forward x up,
// and the frame's up lies on the scene up's side in the plane of forward and
// the scene's up (so that the image is upright).
TYPED_TEST(Camera, FrameLooksAtItsTargetUpright) {
    using R = TypeParam;
    using M = wp::SharedMath<R>;
    const glm::dvec3 position(1, -2, 3);
    for (int i = 0; i < 200; ++i) {
        glm::dvec3 view = wp::test::spread_direction(i, 200);
        glm::dvec3 scene_up = glm::normalize(wp::test::spread_direction((7 * i + 37) % 200, 200) + 0.5 * view);
        if (glm::length(glm::cross(view, scene_up)) < 0.1) continue;  // nearly parallel: refused by the loader
        auto f = M::camera_frame(Vec3<R>(position), Vec3<R>(position + 2.5 * view), Vec3<R>(scene_up), R(0.5), R(1.5));
        glm::dvec3 right(f.right), up(f.up), forward(f.forward);
        EXPECT_NEAR(glm::length(forward - view), 0.0, kRoundingTolerance<R>) << i;
        EXPECT_NEAR(glm::length(right), 1.0, kRoundingTolerance<R>) << i;
        EXPECT_NEAR(glm::length(up), 1.0, kRoundingTolerance<R>) << i;
        EXPECT_NEAR(glm::dot(right, up), 0.0, kRoundingTolerance<R>) << i;
        EXPECT_NEAR(glm::dot(right, forward), 0.0, kRoundingTolerance<R>) << i;
        EXPECT_NEAR(glm::dot(up, forward), 0.0, kRoundingTolerance<R>) << i;
        EXPECT_NEAR(glm::length(glm::cross(forward, up) - right), 0.0, kRoundingTolerance<R>) << i;
        EXPECT_NEAR(glm::dot(right, scene_up), 0.0, kRoundingTolerance<R>) << i;  // up in forward and scene_up's plane
        EXPECT_GT(glm::dot(up, scene_up), 0.0) << i;
        EXPECT_EQ(f.tan_half_fov_y, R(0.5));
        EXPECT_EQ(f.aspect, R(1.5));
    }
}

TYPED_TEST(Camera, DirectionSpansTheFieldOfView) {
    using R = TypeParam;
    using M = wp::SharedMath<R>;
    const double tan_half = std::tan(kPi / 6.0), aspect = 2.0;
    const typename M::CameraFrame frame{Vec3<R>(1, 0, 0), Vec3<R>(0, 1, 0), Vec3<R>(0, 0, -1), R(tan_half), R(aspect)};
    auto direction = [&](double x, double y) { return glm::dvec3(M::camera_direction(frame, R(x), R(y))); };
    EXPECT_NEAR(glm::length(direction(0.5, 0.5) - glm::dvec3(0, 0, -1)), 0.0, kRoundingTolerance<R>);
    // Film y runs down: (0, 0) is the top-left corner.
    glm::dvec3 top_left = glm::normalize(glm::dvec3(-tan_half * aspect, tan_half, -1));
    EXPECT_NEAR(glm::length(direction(0, 0) - top_left), 0.0, kRoundingTolerance<R>);
    glm::dvec3 bottom_right = glm::normalize(glm::dvec3(tan_half * aspect, -tan_half, -1));
    EXPECT_NEAR(glm::length(direction(1, 1) - bottom_right), 0.0, kRoundingTolerance<R>);
}

// Pixel (column, row) of a 4 x 2 film covers film points [column, column + 1)
// / 4 x [row, row + 1) / 2: its jitter (u, v) = (0, 0) is its top-left
// corner, (0.5, 0.5) its centre, and the last pixel ends at the film's
// bottom-right corner.
TYPED_TEST(Camera, PixelJitterCoversThePixel) {
    using R = TypeParam;
    using M = wp::SharedMath<R>;
    const typename M::CameraFrame frame{Vec3<R>(1, 0, 0), Vec3<R>(0, 1, 0), Vec3<R>(0, 0, -1), R(1), R(2)};
    auto through_film = [&](double x, double y) { return glm::normalize(glm::dvec3(2 * (2 * x - 1), 1 - 2 * y, -1)); };
    auto pixel = [&](double column, double row, double u, double v) {
        return glm::dvec3(M::pixel_direction(frame, R(column), R(row), R(4), R(2), R(u), R(v)));
    };
    EXPECT_NEAR(glm::length(pixel(0, 0, 0, 0) - through_film(0, 0)), 0.0, kRoundingTolerance<R>);
    EXPECT_NEAR(glm::length(pixel(1, 0, 0.5, 0.5) - through_film(0.375, 0.25)), 0.0, kRoundingTolerance<R>);
    EXPECT_NEAR(glm::length(pixel(2, 1, 0.25, 0.75) - through_film(0.5625, 0.875)), 0.0, kRoundingTolerance<R>);
    EXPECT_NEAR(glm::length(pixel(3, 1, 1, 1) - through_film(1, 1)), 0.0, kRoundingTolerance<R>);
}

}  // namespace
