// The megakernel baseline against the reference and the wavefront: the same
// estimator, random numbers and per-vertex code, so the same paths.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "megakernel/megakernel_renderer.h"
#include "reference/reference_renderer.h"
#include "support/image_statistics.h"
#include "wavefront/wavefront_renderer.h"
#include "wavefront/wavefront_test_support.h"

namespace wp {
namespace {

// As the wavefront's test: float rounding (OpenCL built-ins against libm) may
// rarely change a path's course, so at least 99% of the pixels agree within 1e-4.
TEST(Megakernel, OneSampleMatchesReferencePathForPath) {
    Scene scene = test::small_room(48, 1);
    RenderResult megakernel = render_megakernel(scene, {}, {});
    RenderResult reference = render_reference(scene, ReferenceOptions{2, false});
    ASSERT_EQ(megakernel.image.rgb.size(), reference.image.rgb.size());
    double fraction = test::fraction_of_pixels_within(megakernel.image, reference.image, 1e-4);
    std::printf("pixels within 1e-4 relative of the reference: %.4f\n", fraction);
    EXPECT_GE(fraction, 0.99);
    EXPECT_EQ(megakernel.stats.samples, reference.stats.samples);
    EXPECT_EQ(megakernel.stats.extension_rays, reference.stats.extension_rays);
    EXPECT_EQ(megakernel.stats.shadow_rays, reference.stats.shadow_rays);
}

// Both OpenCL backends run the same float code per vertex and accumulate each
// pixel's samples in sample order, so their images are bit-identical.
TEST(Megakernel, BitIdenticalToWavefront) {
    Scene scene = test::small_room(40, 3);
    RenderResult megakernel = render_megakernel(scene, {}, {});
    RenderResult wavefront = render_wavefront(scene, {}, {});
    EXPECT_EQ(megakernel.image.rgb, wavefront.image.rgb);
    EXPECT_EQ(megakernel.stats.extension_rays, wavefront.stats.extension_rays);
    EXPECT_EQ(megakernel.stats.shadow_rays, wavefront.stats.shadow_rays);
}

TEST(Megakernel, ProfileTimesItsLaunches) {
    Scene scene = test::small_room(32, 2);
    MegakernelReport report;
    MegakernelOptions options;
    options.profile = true;
    RenderResult result = render_megakernel(scene, options, {}, &report);
    EXPECT_EQ(report.profile.kernel("megakernel").items, result.stats.samples);
    EXPECT_EQ(report.profile.kernel("megakernel").launches, 1u);
    EXPECT_GT(report.profile.kernel("megakernel").device_s, 0.0);
    EXPECT_EQ(report.profile.render_s, result.stats.time_s);
}

}  // namespace
}  // namespace wp
