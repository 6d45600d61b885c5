// The intersect stage against the reference's closest_hit on hand-built rays.
#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>

#include "opencl/device.h"
#include "reference/path_tracer.h"
#include "wavefront/pipeline.h"
#include "wavefront_test_support.h"

namespace wp {
namespace {

using M = SharedMath<float>;
using vec3 = M::vec3;

// A sphere, a plane and a quad in front of the camera.
constexpr const char* kScene = R"({
  "camera": {"position": [0, 0, 0], "look_at": [0, 0, -1], "up": [0, 1, 0], "fov_y": 40, "width": 8, "height": 8},
  "render": {"spp": 1, "max_depth": 4, "rr_depth": 8, "seed": 1},
  "materials": {"white": {"type": "diffuse", "albedo": [0.5, 0.5, 0.5]}},
  "shapes": [
    {"type": "sphere", "center": [0, 0, -5], "radius": 1, "material": "white"},
    {"type": "plane", "point": [0, -2, 0], "normal": [0, 1, 0], "material": "white"},
    {"type": "quad", "corner": [2, -1, -6], "edge1": [2, 0, 0], "edge2": [0, 2, 0], "material": "white"}
  ]
})";

std::vector<test::TestRay> hand_built_rays() {
    auto ray = [](vec3 o, vec3 d) { return test::TestRay{o, glm::normalize(d)}; };
    return {
        ray({0, 0, 0}, {0, 0, -1}),         // sphere, head on
        ray({0, 0, 0}, {0, 1, 0}),          // miss: up into the sky
        ray({0, 0, 0}, {0, -1, -0.1f}),     // plane
        ray({0, 0, 0}, {3, 0, -6}),         // quad, inside
        ray({0, 0, 0}, {2, -1, -6}),        // quad, exactly at its corner
        ray({0, 1, 0}, {0, 0, -1}),         // grazing: tangent to the sphere's top
        ray({0, 1.0001f, 0}, {0, 0, -1}),   // just above the sphere: misses it
        ray({0, 0, -5}, {0.3f, 0.2f, -1}),  // from the sphere's centre: exits
        ray({0, 0.5f, -5.2f}, {1, 0, 0}),   // from inside, off centre
        ray({0, 0, -4.5f}, {0, 0, 1}),      // inside, heading back towards the camera
        ray({0, -2, -3}, {1, 0, 0}),        // lying in the plane: misses it
        ray({0, 0, -7}, {0, 0, -1}),        // behind everything
    };
}

TEST(IntersectStage, MatchesReferenceClosestHit) {
    Scene scene = test::scene_from_json(kScene);
    std::vector<test::TestRay> rays = hand_built_rays();
    Pipeline pipeline(scene, choose_device(""), 64, 64, scene.features());
    test::start_paths(pipeline, rays);
    pipeline.run_alone(Stage::intersect);

    std::vector<float> t = pipeline.read_field<float>("hit_t");
    std::vector<std::uint32_t> shape = pipeline.read_field<std::uint32_t>("hit_shape");
    std::vector<std::uint32_t> for_shade = pipeline.queues().read_queue(WP_QUEUE_HIT);
    std::sort(for_shade.begin(), for_shade.end());

    reference::ReferenceScene<float> ref(scene);
    std::vector<std::uint32_t> expected_hits, expected_misses;
    static const std::uint32_t type_code[] = {WP_SHAPE_SPHERE, WP_SHAPE_PLANE, WP_SHAPE_QUAD};
    for (std::uint32_t i = 0; i < rays.size(); ++i) {
        auto hit = reference::closest_hit(ref, reference::Ray<float>{rays[i].origin, rays[i].direction});
        SCOPED_TRACE("ray " + std::to_string(i));
        (hit.found() ? expected_hits : expected_misses).push_back(i);
        if (!hit.found()) {
            EXPECT_EQ(shape[i], WP_NO_HIT);
            continue;
        }
        // The same float operations in the same order: the same bits.
        EXPECT_EQ(t[i], hit.t);
        EXPECT_EQ(shape[i], (type_code[int(hit.shape)] << WP_SHAPE_TYPE_SHIFT) | std::uint32_t(hit.index));
    }
    // Every path goes on to shade, a miss too (which takes the background there).
    std::vector<std::uint32_t> every_ray(rays.size());
    std::iota(every_ray.begin(), every_ray.end(), 0u);
    EXPECT_EQ(for_shade, every_ray);
    // The hand-built cases cover both outcomes and every shape type.
    EXPECT_GE(expected_hits.size(), 8u);
    EXPECT_GE(expected_misses.size(), 3u);
}

}  // namespace
}  // namespace wp
