// The render settings nee=off, hemisphere=uniform and sampler=independent on the OpenCL backends:
// the analytic emissive-sphere interior, and path-for-path agreement with the
// reference (which reads the same settings at run time).
//
// Acceptance of the analytic test: per channel, |mean - expected| <= 4.5
// standard errors of the pixel mean (normal: false failure 6.8e-6 per check,
// < 1.3e-4 over the 18 checks; fixed seeds) plus 2e-5 of the value for float
// rounding, as the default-settings test allows.
#include "support/sampling_variants.h"

#include <gtest/gtest.h>

#include <string>

#include "megakernel/megakernel_renderer.h"
#include "reference/reference_renderer.h"
#include "support/analytic_scenes.h"
#include "support/image_statistics.h"
#include "support/path_agreement.h"
#include "wavefront/wavefront_renderer.h"
#include "wavefront_test_support.h"

namespace wp {
namespace {

TEST(WavefrontSamplingVariants, EmissiveSphereInteriorKeepsItsValue) {
    const glm::dvec3 rho(0.3, 0.5, 0.8), le(1.0, 2.0, 0.5);
    const int max_depth = 4;
    test::RenderBlock block{.width = 32, .height = 32, .spp = 16, .max_depth = max_depth};
    for (const test::SamplingVariant& variant : test::kSamplingVariants) {
        RenderResult result =
            render_wavefront(test::with_sampling(test::inside_emissive_sphere(block, rho, le), variant), {}, {});
        EXPECT_EQ(result.stats.nonfinite, 0u) << variant.name;
        if (!variant.nee) {
            EXPECT_EQ(result.stats.shadow_rays, 0u) << variant.name;
        }
        for (int c = 0; c < 3; ++c) {
            double expected = test::inside_emissive_sphere_radiance(rho[c], le[c], max_depth);
            test::RunningMean mean = test::channel_mean(result.image, c);
            EXPECT_NEAR(mean.mean(), expected, test::kSigmaTolerance * mean.standard_error() + 2e-5 * expected)
                << variant.name << " channel " << c;
        }
    }
}

// As ImageAgreement.OneSampleMatchesReferencePathForPath, for each variant;
// the megakernel runs the same per-vertex code, so it matches bit for bit.
TEST(WavefrontSamplingVariants, OneSampleMatchesReferencePathForPath) {
    for (const test::SamplingVariant& variant : test::kSamplingVariants) {
        Scene scene = test::with_sampling(test::small_room(48, 1), variant);
        RenderResult wavefront = render_wavefront(scene, {}, {});
        test::expect_path_for_path_agreement(wavefront, render_reference(scene, ReferenceOptions{2, false}),
                                             variant.name);
        if (!variant.nee) {
            EXPECT_EQ(wavefront.stats.shadow_rays, 0u) << variant.name;
        }
        EXPECT_EQ(render_megakernel(scene, {}, {}).image.rgb, wavefront.image.rgb) << variant.name;
    }
}

}  // namespace
}  // namespace wp
