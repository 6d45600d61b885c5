// Lanes (kernels/device/lanes.h): the stage kernels with 4, 8 or 16 paths per
// work item as vector code compute exactly what one path per work item
// computes, in scenes with every shape kind and material, background and both
// light kinds.
#include <gtest/gtest.h>

#include "wavefront/wavefront_renderer.h"
#include "wavefront_test_support.h"

namespace wp {
namespace {

void expect_same_image_with_every_lane_count(Scene scene) {
    scene.camera.width = scene.camera.height = 24;
    scene.render.spp = 3;
    WavefrontOptions options;
    options.wavefront = 320;  // queue lengths rarely a multiple of the lanes: partly filled last lanes
    options.lanes = 1;
    RenderResult one = render_wavefront(scene, options, {});
    EXPECT_GT(one.stats.shadow_rays, 0u);
    for (unsigned lanes : {4u, 8u, 16u}) {
        options.lanes = lanes;
        WavefrontReport report;
        RenderResult many = render_wavefront(scene, options, {}, &report);
        EXPECT_EQ(report.lanes, lanes);
        EXPECT_EQ(one.image.rgb, many.image.rgb) << lanes << " lanes";
        EXPECT_EQ(one.stats.extension_rays, many.stats.extension_rays) << lanes << " lanes";
        EXPECT_EQ(one.stats.shadow_rays, many.stats.shadow_rays) << lanes << " lanes";
    }
}

TEST(StageLanes, RoomRendersTheSameWithEveryLaneCount) {
    expect_same_image_with_every_lane_count(test::scene_from_file("scenes/room.json"));
}

// Planes, a sphere light and a background.
TEST(StageLanes, PlanesSphereLightAndBackgroundRenderTheSame) {
    expect_same_image_with_every_lane_count(test::scene_from_json(R"({
      "camera": {"position": [0, 1, 4], "look_at": [0, 1, 0], "up": [0, 1, 0], "fov_y": 60, "width": 8, "height": 8},
      "render": {"spp": 1, "max_depth": 5, "rr_depth": 2, "seed": 3},
      "background": [0.2, 0.3, 0.4],
      "materials": {
        "white": {"type": "diffuse", "albedo": [0.7, 0.7, 0.7]},
        "glass": {"type": "glass", "ior": 1.5},
        "lamp": {"type": "emitter", "radiance": [8, 8, 8]}
      },
      "shapes": [
        {"type": "plane", "point": [0, 0, 0], "normal": [0, 1, 0], "material": "white"},
        {"type": "plane", "point": [0, 0, -2], "normal": [0, 0, 1], "material": "white"},
        {"type": "sphere", "center": [0.5, 0.6, 0], "radius": 0.6, "material": "glass"},
        {"type": "sphere", "center": [-1, 2.5, 0.5], "radius": 0.3, "material": "lamp"}
      ]
    })"));
}

}  // namespace
}  // namespace wp
