// Whole images: the wavefront against the reference renderer.
#include <gtest/gtest.h>

#include <cmath>

#include "reference/reference_renderer.h"
#include "support/image_statistics.h"
#include "support/path_agreement.h"
#include "wavefront/wavefront_renderer.h"
#include "wavefront_test_support.h"

namespace wp {
namespace {

// At 1 spp every wavefront path retraces the reference's float path.
TEST(ImageAgreement, OneSampleMatchesReferencePathForPath) {
    Scene scene = test::small_room(48, 1);
    test::expect_path_for_path_agreement(render_wavefront(scene, {}, {}),
                                         render_reference(scene, ReferenceOptions{2, false}), "wavefront");
}

}  // namespace
}  // namespace wp
