// The reference with the Embree intersector (ReferenceOptions::intersector):
// the same images as with the BVH on the mesh scenes, pixel for pixel (the
// two differ only where a ray meets two shapes at one distance, and no path
// of these renders does), the same for any thread count, and refused in
// double precision.
#include <gtest/gtest.h>

#include <stdexcept>

#include "reference/reference_renderer.h"

namespace {

wp::Scene shipped(const char* name) {
    wp::Scene scene = wp::load_scene(std::string(WAVEPATH_SOURCE_DIR "/scenes/") + name + ".json");
    scene.camera.width = scene.camera.height = 64;
    scene.render.spp = 4;
    return scene;
}

wp::RenderResult render(const wp::Scene& scene, wp::Intersector intersector, int threads = 2) {
    return wp::render_reference(scene, {.threads = threads, .intersector = intersector});
}

TEST(ReferenceIntersector, EmbreeRendersTheMeshScenesAsTheBvhDoes) {
    for (const char* name : {"bunny", "cornell_mesh"}) {
        wp::Scene scene = shipped(name);
        wp::RenderResult bvh = render(scene, wp::Intersector::Bvh);
        wp::RenderResult embree = render(scene, wp::Intersector::Embree);
        int differing = 0;
        for (std::size_t i = 0; i < bvh.image.rgb.size(); ++i) differing += bvh.image.rgb[i] != embree.image.rgb[i];
        EXPECT_EQ(differing, 0) << name;
        EXPECT_EQ(embree.stats.extension_rays, bvh.stats.extension_rays) << name;
        EXPECT_EQ(embree.stats.shadow_rays, bvh.stats.shadow_rays) << name;
        EXPECT_GT(embree.stats.shadow_rays, 0u) << name;
    }
}

TEST(ReferenceIntersector, EmbreeImageIsTheSameForAnyThreadCount) {
    wp::Scene scene = shipped("bunny");
    scene.camera.width = 37, scene.camera.height = 23;  // partial tiles
    wp::RenderResult one = render(scene, wp::Intersector::Embree, 1);
    EXPECT_EQ(render(scene, wp::Intersector::Embree, 3).image.rgb, one.image.rgb);
}

TEST(ReferenceIntersector, EmbreeIsFloatOnly) {
    wp::Scene scene = shipped("cornell_mesh");
    EXPECT_THROW(wp::render_reference(scene, {.double_precision = true, .intersector = wp::Intersector::Embree}),
                 std::invalid_argument);
    EXPECT_EQ(wp::fastest_reference_intersector(false), wp::Intersector::Embree);
    EXPECT_EQ(wp::fastest_reference_intersector(true), wp::Intersector::Bvh);
}

}  // namespace
