// The reference renderer's contract: determinism across thread counts,
// precision agreement, statistics, progress, non-finite samples, and the
// single-sample entry point the wavefront backend is compared with.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <mutex>
#include <stdexcept>
#include <vector>

#include "reference/reference_renderer.h"
#include "support/analytic_scenes.h"
#include "support/image_statistics.h"

namespace {

using wp::test::RenderBlock;

// 37 x 23 leaves partial tiles at the right and bottom edges.
wp::Scene room(std::uint32_t seed = 1) {
    return wp::test::feature_room({.width = 37, .height = 23, .spp = 4, .max_depth = 6, .rr_depth = 2, .seed = seed});
}

wp::RenderResult render(const wp::Scene& scene, int threads, bool double_precision = false) {
    return wp::render_reference(scene, {.threads = threads, .double_precision = double_precision});
}

TEST(ReferenceRenderer, ImageIsBitIdenticalForAnyThreadCount) {
    for (bool double_precision : {false, true}) {
        wp::RenderResult one = render(room(), 1, double_precision);
        for (int threads : {2, 3}) {
            wp::RenderResult many = render(room(), threads, double_precision);
            EXPECT_EQ(many.image.rgb, one.image.rgb) << threads << " threads, double " << double_precision;
            EXPECT_EQ(many.stats.extension_rays, one.stats.extension_rays);
            EXPECT_EQ(many.stats.shadow_rays, one.stats.shadow_rays);
        }
    }
}

TEST(ReferenceRenderer, DifferentSeedsGiveDifferentImages) {
    wp::Image a = render(room(1), 2).image;
    wp::Image b = render(room(2), 2).image;
    int differing = 0;
    for (std::size_t i = 0; i < a.rgb.size(); ++i) differing += a.rgb[i] != b.rgb[i];
    // Pixels that see only black or a directly viewed emitter agree; most do not.
    EXPECT_GT(differing, static_cast<int>(a.rgb.size() / 2));
}

// Float and double trace nearly the same paths (identical random numbers);
// paired over pixels, the mean difference must vanish within 4.5 standard
// errors of the differences (false failure 6.8e-6 per channel) plus 1e-5 of
// the value for float rounding, on a scene with every feature.
TEST(ReferenceRenderer, FloatAndDoubleAgreeStatistically) {
    wp::Scene scene = wp::test::feature_room({.width = 32, .height = 32, .spp = 16, .max_depth = 8, .rr_depth = 3});
    wp::Image f = render(scene, 2, false).image;
    wp::Image d = render(scene, 2, true).image;
    for (int c = 0; c < 3; ++c) {
        wp::test::RunningMean difference, value;
        for (int y = 0; y < f.height; ++y) {
            for (int x = 0; x < f.width; ++x) {
                double fv = wp::test::pixel_channel(f, x, y, c), dv = wp::test::pixel_channel(d, x, y, c);
                difference.add(fv - dv);
                value.add(dv);
            }
        }
        EXPECT_NEAR(difference.mean(), 0.0,
                    wp::test::kSigmaTolerance * difference.standard_error() + 1e-5 * value.mean())
            << "channel " << c;
        EXPECT_GT(value.mean(), 0.05) << "channel " << c;  // the room is lit
    }
}

// Camera sample, bounce ray; the floor under the light is always lit from
// the front and always seen, so each sample casts exactly one shadow ray.
TEST(ReferenceRenderer, CountsSamplesAndRays) {
    RenderBlock block{.width = 8, .height = 8, .spp = 5, .max_depth = 1};
    wp::Scene scene = wp::test::plane_under_square_light(block, {0.5, 0.5, 0.5}, {1, 1, 1}, 0.5, 1.5);
    wp::RenderStats stats = render(scene, 2).stats;
    EXPECT_EQ(stats.samples, 8u * 8u * 5u);
    EXPECT_EQ(stats.extension_rays, 2 * stats.samples);
    EXPECT_EQ(stats.shadow_rays, stats.samples);
    EXPECT_EQ(stats.nonfinite, 0u);
    EXPECT_GE(stats.time_s, 0.0);
}

TEST(ReferenceRenderer, SingleSampleMatchesTheImage) {
    wp::Scene scene = room();
    scene.render.spp = 1;
    for (bool double_precision : {false, true}) {
        wp::Image image = render(scene, 2, double_precision).image;
        for (int y = 0; y < image.height; y += 3) {
            for (int x = 0; x < image.width; x += 4) {
                glm::dvec3 sample = double_precision ? wp::trace_reference_sample<double>(scene, x, y, 0)
                                                     : wp::trace_reference_sample<float>(scene, x, y, 0);
                for (int c = 0; c < 3; ++c) {
                    EXPECT_EQ(wp::test::pixel_channel(image, x, y, c), static_cast<float>(sample[c]))
                        << x << ", " << y << " double " << double_precision;
                }
            }
        }
    }
}

// An emitter of infinite radiance makes every sample that sees it
// non-finite: those are dropped (count 0) and counted, the image stays finite.
TEST(ReferenceRenderer, DropsAndCountsNonFiniteSamples) {
    RenderBlock block{.width = 8, .height = 8, .spp = 3, .max_depth = 0};
    const double inf = std::numeric_limits<double>::infinity();
    wp::Scene scene = wp::test::inside_emissive_sphere(block, {0.5, 0.5, 0.5}, {inf, 1.0, 1.0});
    wp::RenderResult result = render(scene, 2);
    EXPECT_EQ(result.stats.nonfinite, result.stats.samples);
    EXPECT_EQ(result.stats.nonfinite_by_stage[static_cast<std::size_t>(wp::NonfiniteStage::emission)],
              result.stats.samples);
    for (float v : result.image.rgb) EXPECT_EQ(v, 0.0f);
}

TEST(ReferenceRenderer, ReportsProgressPerTileUpToOne) {
    wp::Scene scene = room();  // 37 x 23: 3 x 2 tiles of 16
    std::mutex mutex;
    std::vector<double> fractions;
    wp::Progress progress;
    progress.samples = [&](double f) {
        std::lock_guard<std::mutex> lock(mutex);
        fractions.push_back(f);
    };
    wp::render_reference(scene, {.threads = 2}, progress);
    // 0 as sampling starts, then one fraction per tile.
    ASSERT_EQ(fractions.size(), 7u);
    EXPECT_EQ(fractions.front(), 0.0);
    std::sort(fractions.begin(), fractions.end());
    for (std::size_t i = 0; i < fractions.size(); ++i) EXPECT_DOUBLE_EQ(fractions[i], i / 6.0);
}

TEST(ReferenceRenderer, RejectsImpossibleSettings) {
    wp::Scene scene = room();
    scene.render.spp = 0;
    EXPECT_THROW(render(scene, 1), std::invalid_argument);
    scene = room();
    scene.camera.width = 0;
    EXPECT_THROW(render(scene, 1), std::invalid_argument);
    scene = room();
    scene.render.max_depth = -1;
    EXPECT_THROW(render(scene, 1), std::invalid_argument);
}

}  // namespace
