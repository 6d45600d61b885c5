// Shadow rays (kernels/interface/stages.h): traced by shade itself (the
// default on CPU devices that trace on the device) or by their own stage,
// intersect_shadow, they make the same image, bit for bit, with the same ray
// counts; each path's light sample is added once, after its emission.
#include <gtest/gtest.h>

#include "wavefront/wavefront_renderer.h"
#include "wavefront_test_support.h"

namespace wp {
namespace {

RenderResult render_with_shadow_stage(const Scene& scene, bool shadow_stage, WavefrontReport* report = nullptr) {
    WavefrontOptions options;
    options.wavefront = 320;  // several iterations per pass, and passes that refill freed slots
    options.shadow_stage = shadow_stage;
    options.intersector = Intersector::Bvh;  // the kernels trace (meshes default to Embree on the host)
    return render_wavefront(scene, options, {}, report);
}

void expect_same_image_either_way(Scene scene, int size, int spp) {
    scene.camera.width = scene.camera.height = size;
    scene.render.spp = spp;
    WavefrontReport in_shade_report, own_stage_report;
    RenderResult in_shade = render_with_shadow_stage(scene, false, &in_shade_report);
    RenderResult own_stage = render_with_shadow_stage(scene, true, &own_stage_report);
    EXPECT_EQ(in_shade_report.features.find("shadow-stage"), std::string::npos);
    EXPECT_NE(own_stage_report.features.find("shadow-stage"), std::string::npos);
    EXPECT_GT(own_stage.stats.shadow_rays, 0u);
    EXPECT_EQ(in_shade.image.rgb, own_stage.image.rgb);
    EXPECT_EQ(in_shade.stats.extension_rays, own_stage.stats.extension_rays);
    // Counted from the SHADOW queue either way: its marks must be cleared
    // each iteration where no stage takes it, or the count grows.
    EXPECT_EQ(in_shade.stats.shadow_rays, own_stage.stats.shadow_rays);
    EXPECT_EQ(in_shade.stats.nonfinite, own_stage.stats.nonfinite);
}

TEST(ShadowRays, RoomRendersTheSameTracedInShadeOrInTheirOwnStage) {
    expect_same_image_either_way(test::scene_from_file("scenes/room.json"), 24, 4);
}

// Meshes through the BVH, and a mesh light.
TEST(ShadowRays, MeshCornellBoxRendersTheSameTracedInShadeOrInTheirOwnStage) {
    expect_same_image_either_way(test::scene_from_file("scenes/cornell_mesh.json"), 16, 2);
}

// On a CPU device tracing on the device, shade traces them; where the host
// traces (Embree), they keep their own stage, which the host's verdicts need.
TEST(ShadowRays, DefaultIsShadeOnCpusAndTheirOwnStageWhereTheHostTraces) {
    Scene scene = test::small_room(8, 1);
    WavefrontReport report;
    render_wavefront(scene, {}, {}, &report);
    EXPECT_EQ(report.features.find("shadow-stage"), std::string::npos) << report.features;
    WavefrontOptions host;
    host.intersector = Intersector::Embree;
    render_wavefront(scene, host, {}, &report);
    EXPECT_NE(report.features.find("shadow-stage"), std::string::npos) << report.features;
    host.shadow_stage = false;
    EXPECT_THROW(render_wavefront(scene, host, {}), std::invalid_argument);
}

}  // namespace
}  // namespace wp
