// The non-finite guards (docs/robustness.md, "Guards"): a value that would
// overflow float in one stage is dropped and counted in that stage, on the
// float reference, the wavefront and the megakernel alike, and the image
// stays finite. The scenes are built in code with values the loader would
// not take (albedo 3e38, an infinite emission), the only way to reach each
// stage deterministically; in double nothing here overflows, so the float
// reference stands for the reference.
#include <gtest/gtest.h>

#include <limits>

#include "megakernel/megakernel_renderer.h"
#include "robustness_support.h"
#include "support/analytic_scenes.h"

namespace wp::test {
namespace {

enum class GuardBackend { ReferenceFloat, Wavefront, Megakernel };

struct GuardBackendNames {
    std::string operator()(const ::testing::TestParamInfo<GuardBackend>& info) const {
        switch (info.param) {
            case GuardBackend::ReferenceFloat:
                return "ReferenceFloat";
            case GuardBackend::Wavefront:
                return "Wavefront";
            case GuardBackend::Megakernel:
                return "Megakernel";
        }
        return "";
    }
};

RenderResult render_guarded(GuardBackend backend, const Scene& scene) {
    use_build_tree_program_cache();
    switch (backend) {
        case GuardBackend::ReferenceFloat:
            return render_reference(scene, ReferenceOptions{0, false});
        case GuardBackend::Wavefront:
            return render_wavefront(scene, {}, {});
        case GuardBackend::Megakernel:
            return render_megakernel(scene, {}, {});
    }
    return {};
}

// Every sample drops exactly one value, in `stage`; the other stages drop nothing.
NonfiniteCounts every_sample_in(NonfiniteStage stage, std::uint64_t samples) {
    NonfiniteCounts counts{};
    counts[static_cast<std::size_t>(stage)] = samples;
    return counts;
}

class NonfiniteGuards : public ::testing::TestWithParam<GuardBackend> {
 protected:
    static constexpr RenderBlock kBlock{.width = 8, .height = 8, .spp = 2, .max_depth = 0};
    static constexpr double kHugeAlbedo = 3e38;  // just below float's maximum

    void expect_counted(const Scene& scene, NonfiniteStage stage, float pixel_value) {
        RenderResult result = render_guarded(GetParam(), scene);
        EXPECT_EQ(result.stats.nonfinite_by_stage, every_sample_in(stage, result.stats.samples));
        EXPECT_EQ(result.stats.nonfinite, result.stats.samples);
        for (float v : result.image.rgb) ASSERT_EQ(v, pixel_value);
    }
};

// The camera inside an emitter of infinite radiance: the emission seen at depth 0 is dropped.
TEST_P(NonfiniteGuards, InfiniteEmissionIsDroppedInTheEmissionStage) {
    const double inf = std::numeric_limits<double>::infinity();
    expect_counted(inside_emissive_sphere(kBlock, {0.5, 0.5, 0.5}, {inf, 1.0, 1.0}), NonfiniteStage::emission, 0.0f);
}

// Inside a sphere of albedo 3e38 emitting 10: the light sample adds
// albedo * Le = 3e39 (see inside_emissive_sphere), which overflows float and
// is dropped; the emission seen from the camera (10) stays. Without MIS, so
// that the bounce's own find of the emission (3e39 too, dropped in the
// emission stage) does not count as well.
TEST_P(NonfiniteGuards, OverflowingLightSampleIsDroppedInTheDirectStage) {
    RenderBlock block = kBlock;
    block.max_depth = 1;
    Scene scene = inside_emissive_sphere(block, glm::dvec3(kHugeAlbedo), glm::dvec3(10.0));
    scene.render.mis = false;
    expect_counted(scene, NonfiniteStage::direct, 10.0f);
}

// Inside a dark sphere of albedo 3e38 (no light, so no light sample): the
// throughput reaches 3e38 after the first bounce and overflows at the
// second, which ends the path there.
TEST_P(NonfiniteGuards, OverflowingThroughputEndsThePathInTheScatterStage) {
    RenderBlock block = kBlock;
    block.max_depth = 4;
    expect_counted(inside_emissive_sphere(block, glm::dvec3(kHugeAlbedo), glm::dvec3(0.0)), NonfiniteStage::scatter,
                   0.0f);
}

INSTANTIATE_TEST_SUITE_P(Backends, NonfiniteGuards,
                         ::testing::Values(GuardBackend::ReferenceFloat, GuardBackend::Wavefront,
                                           GuardBackend::Megakernel),
                         GuardBackendNames());

}  // namespace
}  // namespace wp::test
