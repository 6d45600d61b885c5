// Intersect and shade as one kernel (kernels/interface/stages.h): the default
// on CPU devices with scan compaction, it makes the image of intersect and
// shade apart, bit for bit, with the same ray and non-finite counts, whoever
// traces (the kernels' BVH or the host's Embree) and with any lanes. The
// two share shade's code (kernels/device/shade_hits.h), so this proves the
// plumbing: the queue the stage takes and pushes to, the host's hits read
// in the fused kernel, the profile's counts. Compaction of that queue is
// tested on its own in compaction_test.cpp.
#include <gtest/gtest.h>

#include "wavefront/wavefront_renderer.h"
#include "wavefront_test_support.h"

namespace wp {
namespace {

RenderResult render_shading(const Scene& scene, bool intersect_and_shade, Intersector intersector, unsigned lanes,
                            WavefrontReport* report = nullptr) {
    WavefrontOptions options;
    options.wavefront = 320;  // several iterations per pass, and passes that refill freed slots
    options.intersect_and_shade = intersect_and_shade;
    options.intersector = intersector;
    options.lanes = lanes;
    return render_wavefront(scene, options, {}, report);
}

void expect_same_image_either_way(Scene scene, int size, int spp, Intersector intersector, unsigned lanes) {
    scene.camera.width = scene.camera.height = size;
    scene.render.spp = spp;
    WavefrontReport fused_report, apart_report;
    RenderResult fused = render_shading(scene, true, intersector, lanes, &fused_report);
    RenderResult apart = render_shading(scene, false, intersector, lanes, &apart_report);
    EXPECT_NE(fused_report.features.find("intersect-and-shade"), std::string::npos) << fused_report.features;
    EXPECT_EQ(apart_report.features.find("intersect-and-shade"), std::string::npos) << apart_report.features;
    EXPECT_GT(fused.stats.extension_rays, std::uint64_t(size) * size * spp);  // some paths bounce
    EXPECT_EQ(fused.image.rgb, apart.image.rgb);
    EXPECT_EQ(fused.stats.extension_rays, apart.stats.extension_rays);
    EXPECT_EQ(fused.stats.shadow_rays, apart.stats.shadow_rays);
    EXPECT_EQ(fused.stats.nonfinite, apart.stats.nonfinite);
}

TEST(IntersectAndShade, RoomRendersTheSameAsIntersectThenShade) {
    for (unsigned lanes : {1u, 8u}) {
        SCOPED_TRACE(std::to_string(lanes) + " lanes");
        expect_same_image_either_way(test::scene_from_file("scenes/room.json"), 24, 4, Intersector::Bvh, lanes);
    }
}

// Meshes through the kernels' BVH, and where the host traces them (Embree),
// whose hits the fused kernel reads from the path state.
TEST(IntersectAndShade, MeshCornellBoxRendersTheSameAsIntersectThenShade) {
    for (Intersector intersector : {Intersector::Bvh, Intersector::Embree}) {
        SCOPED_TRACE(intersector == Intersector::Bvh ? "bvh" : "embree");
        expect_same_image_either_way(test::scene_from_file("scenes/cornell_mesh.json"), 16, 2, intersector, 0);
    }
}

// SPPM's camera pass stores its visible points from the shading code.
TEST(IntersectAndShade, SppmRendersTheSameAsIntersectThenShade) {
    Scene scene = test::scene_from_file("scenes/cornell.json");
    scene.render.integrator = Integrator::Sppm;
    scene.render.sppm.photons = 4096;
    expect_same_image_either_way(scene, 16, 2, Intersector::Bvh, 0);
}

// The profile counts the fused stage's items as the rays it traced, and the
// rays by depth as before.
TEST(IntersectAndShade, ProfileCountsTheRaysTheStageTraced) {
    Scene scene = test::small_room(16, 2);
    WavefrontOptions options;
    options.profile = true;
    WavefrontReport report;
    RenderResult result = render_wavefront(scene, options, {}, &report);
    RenderProfile& p = report.profile;
    EXPECT_FALSE(p.has_kernel("intersect"));
    EXPECT_FALSE(p.has_kernel("shade"));
    ASSERT_TRUE(p.has_kernel("intersect_and_shade"));
    EXPECT_EQ(p.kernel("intersect_and_shade").items, result.stats.extension_rays);
    std::uint64_t by_depth = 0, shadow_by_depth = 0;
    for (std::uint64_t n : p.extension_rays_by_depth) by_depth += n;
    for (std::uint64_t n : p.shadow_rays_by_depth) shadow_by_depth += n;
    EXPECT_EQ(by_depth, result.stats.extension_rays);
    EXPECT_EQ(shadow_by_depth, result.stats.shadow_rays);
    EXPECT_GT(shadow_by_depth, 0u);
}

// One kernel on a CPU device with scan compaction; atomic compaction cannot
// build the queue the stage reads, so intersect and shade run apart there,
// and asking for both is refused.
TEST(IntersectAndShade, DefaultIsOneKernelOnCpusWithScanCompaction) {
    Scene scene = test::small_room(8, 1);
    WavefrontReport report;
    render_wavefront(scene, {}, {}, &report);
    EXPECT_NE(report.features.find("intersect-and-shade"), std::string::npos) << report.features;
    WavefrontOptions atomic;
    atomic.compaction = Compaction::Atomic;
    atomic.lanes = 1;
    render_wavefront(scene, atomic, {}, &report);
    EXPECT_EQ(report.features.find("intersect-and-shade"), std::string::npos) << report.features;
    atomic.intersect_and_shade = true;
    EXPECT_THROW(render_wavefront(scene, atomic, {}), std::invalid_argument);
}

}  // namespace
}  // namespace wp
