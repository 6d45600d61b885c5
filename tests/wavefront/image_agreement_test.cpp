// Whole images: the wavefront against the reference renderer.
#include <gtest/gtest.h>

#include <cmath>

#include "reference/reference_renderer.h"
#include "support/image_statistics.h"
#include "wavefront/wavefront_renderer.h"
#include "wavefront_test_support.h"

namespace wp {
namespace {

// At 1 spp every wavefront path retraces the reference's float path; only
// float rounding differences (the OpenCL built-ins against libm in sin and
// cos of the hemisphere sampling) can separate them, and rarely change a
// path's course.
TEST(ImageAgreement, OneSampleMatchesReferencePathForPath) {
    Scene scene = test::small_room(48, 1);
    RenderResult wavefront = render_wavefront(scene, {}, {});
    RenderResult reference = render_reference(scene, ReferenceOptions{2, false});
    ASSERT_EQ(wavefront.image.rgb.size(), reference.image.rgb.size());
    double fraction = test::fraction_of_pixels_within(wavefront.image, reference.image, 1e-4);
    std::printf("pixels within 1e-4 relative of the reference: %.4f\n", fraction);
    EXPECT_GE(fraction, 0.99);
    EXPECT_EQ(wavefront.stats.samples, reference.stats.samples);
    EXPECT_EQ(wavefront.stats.extension_rays, reference.stats.extension_rays);
    EXPECT_EQ(wavefront.stats.shadow_rays, reference.stats.shadow_rays);
}

}  // namespace
}  // namespace wp
