// The room at other scales and positions (issue 5): scaled by 1e-4 and 1e+4
// and translated by 1e+5, it must render as the unit room does, on both
// backends; and the float wavefront against the double reference at each of
// those extremes, with the bias measured.
#include <gtest/gtest.h>

#include "robustness_support.h"

namespace wp::test {
namespace {

constexpr int kSize = 32, kSpp = 16, kRegions = 4;

struct Extreme {
    const char* name;
    double scale;
    glm::dvec3 translation;
};
const Extreme kExtremes[] = {
    {"room scaled 1e-4", 1e-4, {0, 0, 0}},
    {"room scaled 1e+4", 1e4, {0, 0, 0}},
    {"room translated 1e+5", 1.0, {1e5, -1e5, 1e5}},
};

class RoomScale : public ::testing::TestWithParam<Backend> {};

// Independent seeds, so every region's mean difference is zero-mean noise
// with a measurable standard error (see compare_regions); 16 regions per
// extreme.
TEST_P(RoomScale, MatchesTheUnitRoomWithinNoise) {
    RenderResult unit = render_on(GetParam(), transformed_room(1.0, {0, 0, 0}, kSize, kSpp, 1));
    for (const Extreme& extreme : kExtremes) {
        SCOPED_TRACE(extreme.name);
        RenderResult moved =
            render_on(GetParam(), transformed_room(extreme.scale, extreme.translation, kSize, kSpp, 2));
        EXPECT_EQ(moved.stats.nonfinite, 0u);
        RegionComparison c = compare_regions(moved.image, unit.image, kRegions);
        report_figure(std::string(extreme.name) + " vs unit room (independent seeds)", GetParam(), describe(c));
        EXPECT_LE(c.worst_z, kSigmaTolerance);
        EXPECT_LE(std::fabs(c.whole_z), kSigmaTolerance);
    }
}

// Every shipped scene, small: no value may be dropped as non-finite, in any stage.
TEST_P(RoomScale, ShippedScenesHaveNoNonFiniteSamples) {
    for (const char* path : {"scenes/room.json", "scenes/cornell.json"}) {
        Scene scene = scene_from_file(path);
        scene.camera.width = scene.camera.height = 24;
        scene.render.spp = 8;
        RenderResult result = render_on(GetParam(), scene);
        report_figure(std::string("non-finite values in ") + path, GetParam(),
                      format("%.0f of %.0f", double(result.stats.nonfinite), double(result.stats.samples)));
        EXPECT_EQ(result.stats.nonfinite, 0u);
        EXPECT_EQ(result.stats.nonfinite_by_stage, NonfiniteCounts{});
        EXPECT_TRUE(all_finite(result.image));
    }
}

INSTANTIATE_TEST_SUITE_P(Backends, RoomScale, ::testing::Values(Backend::Reference, Backend::Wavefront),
                         BackendNames());

// Same seed: the float wavefront retraces the double reference's paths
// until rounding sends one elsewhere. Reported: the fraction of pixels
// within 1e-3, and the whole-image bias with its region z; required: no
// region's mean differs by more than kSigmaTolerance standard errors of the
// per-pixel differences plus 1e-3 of its level (float's own rounding of a
// 16-sample sum).
TEST(FloatAgainstDouble, BiasAtEachExtreme) {
    std::vector<Extreme> cases = {{"unit room", 1.0, {0, 0, 0}}};
    cases.insert(cases.end(), std::begin(kExtremes), std::end(kExtremes));
    for (const Extreme& extreme : cases) {
        SCOPED_TRACE(extreme.name);
        Scene scene = transformed_room(extreme.scale, extreme.translation, kSize, kSpp, 3);
        RenderResult dbl = render_on(Backend::Reference, scene);
        RenderResult flt = render_on(Backend::Wavefront, scene);
        RegionComparison c = compare_regions(flt.image, dbl.image, kRegions);
        double agreeing = fraction_within(flt.image, dbl.image, 1e-3);
        report_figure(std::string(extreme.name) + ": float minus double (same seed)", Backend::Wavefront,
                      format("whole image %+.2e, worst region z %.2f, pixels within 1e-3: %.3f", c.whole_relative,
                             c.worst_z, agreeing));
        EXPECT_LE(std::fabs(c.whole_relative), 1e-3) << "bias";
        EXPECT_TRUE(c.worst_z <= kSigmaTolerance || c.worst_relative <= 1e-3) << c.worst_z;
    }
}

}  // namespace
}  // namespace wp::test
