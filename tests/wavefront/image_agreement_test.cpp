// Whole images: the wavefront against the reference renderer.
#include <gtest/gtest.h>

#include <cmath>

#include "reference/reference_renderer.h"
#include "wavefront/wavefront_renderer.h"
#include "wavefront_test_support.h"

namespace wp {
namespace {

Scene small_room(int size, int spp) {
    Scene scene = test::scene_from_file("scenes/room.json");
    scene.camera.width = size;
    scene.camera.height = size;
    scene.render.spp = spp;
    return scene;
}

// At 1 spp every wavefront path retraces the reference's float path; only
// float rounding differences (the OpenCL built-ins against libm in sin and
// cos of the hemisphere sampling) can separate them, and rarely change a
// path's course.
TEST(ImageAgreement, OneSampleMatchesReferencePathForPath) {
    Scene scene = small_room(48, 1);
    RenderResult wavefront = render_wavefront(scene, {}, {});
    RenderResult reference = render_reference(scene, ReferenceOptions{2, false});
    ASSERT_EQ(wavefront.image.rgb.size(), reference.image.rgb.size());
    std::size_t pixels = wavefront.image.rgb.size() / 3, agreeing = 0;
    for (std::size_t p = 0; p < pixels; ++p) {
        bool all = true;
        for (int c = 0; c < 3; ++c) {
            double a = wavefront.image.rgb[3 * p + c], b = reference.image.rgb[3 * p + c];
            all = all && std::fabs(a - b) <= 1e-4 * std::max(std::fabs(a), std::fabs(b)) + 1e-30;
        }
        agreeing += all;
    }
    double fraction = double(agreeing) / double(pixels);
    std::printf("pixels within 1e-4 relative of the reference: %.4f (%zu of %zu)\n", fraction, agreeing, pixels);
    EXPECT_GE(fraction, 0.99);
    EXPECT_EQ(wavefront.stats.samples, reference.stats.samples);
    EXPECT_EQ(wavefront.stats.extension_rays, reference.stats.extension_rays);
    EXPECT_EQ(wavefront.stats.shadow_rays, reference.stats.shadow_rays);
}

}  // namespace
}  // namespace wp
