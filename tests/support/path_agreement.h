// The path-for-path check of an OpenCL backend against the reference at 1 spp.
// Both draw the same random numbers for every path, so only float rounding
// (the OpenCL built-ins against libm) can separate them, and it rarely changes
// a path's course: at least 99% of the pixels agree within 1e-4 relative, and
// the sample and ray counts are equal.
#pragma once

#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include "core/render.h"
#include "support/image_statistics.h"

namespace wp::test {

inline void expect_path_for_path_agreement(const RenderResult& backend, const RenderResult& reference,
                                           const std::string& label) {
    ASSERT_EQ(backend.image.rgb.size(), reference.image.rgb.size()) << label;
    double fraction = fraction_of_pixels_within(backend.image, reference.image, 1e-4);
    std::printf("%s: pixels within 1e-4 relative of the reference: %.4f\n", label.c_str(), fraction);
    EXPECT_GE(fraction, 0.99) << label;
    EXPECT_EQ(backend.stats.samples, reference.stats.samples) << label;
    EXPECT_EQ(backend.stats.extension_rays, reference.stats.extension_rays) << label;
    EXPECT_EQ(backend.stats.shadow_rays, reference.stats.shadow_rays) << label;
}

}  // namespace wp::test
