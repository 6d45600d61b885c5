// Queue compaction: both ways of filling a queue keep exactly the live paths;
// the prefix-sum compaction also keeps them in ascending slot order, and
// builds the queue a stage pushes to while reading it (intersect_and_shade's
// RAY) as it builds any other.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <random>

#include "wavefront/wavefront_renderer.h"
#include "wavefront_test_support.h"

namespace wp {
namespace {

// A sphere in front of the camera: rays in random directions hit it or miss.
constexpr const char* kScene = R"({
  "camera": {"position": [0, 0, 0], "look_at": [0, 0, -1], "up": [0, 1, 0], "fov_y": 40, "width": 8, "height": 8},
  "render": {"spp": 1, "max_depth": 4, "rr_depth": 3, "seed": 0},
  "background": [0.1, 0.2, 0.3],
  "materials": {"white": {"type": "diffuse", "albedo": [0.5, 0.5, 0.5]}},
  "shapes": [{"type": "sphere", "center": [0, 0, -3], "radius": 1.5, "material": "white"}]
})";

constexpr std::uint32_t kCapacity = 4096;  // 16 compaction blocks

// What shade leaves in two queues it pushes to, and what they should hold.
struct QueuesAfterShade {
    std::vector<std::uint32_t> free, expected_free;  // the paths that ended: here, those whose ray missed
    std::vector<std::uint32_t> ray, expected_ray;    // the paths that go on: those whose ray hit the sphere
};

// Whether a ray from the origin along unit `direction` hits kScene's sphere:
// its closest approach to the centre is inside the radius, and ahead.
bool hits_the_sphere(glm::vec3 direction) {
    const glm::vec3 centre(0.0f, 0.0f, -3.0f);
    const float along = glm::dot(centre, direction);
    return along > 0.0f && glm::dot(centre, centre) - along * along < 1.5f * 1.5f;
}

// How shade runs: after intersect, each a stage of its own, or in one kernel with it.
enum class Shading { AfterIntersect, IntersectAndShade };

// Runs intersect and shade on `queued` (in that order, or as one kernel);
// the expected queues in ascending order, from the rays and the sphere. The
// sphere is diffuse and the paths at depth 0, before roulette, so every hit
// goes on and every miss ends.
QueuesAfterShade queues_after_shade(Compaction compaction, const std::vector<std::uint32_t>& queued,
                                    Shading shading = Shading::AfterIntersect) {
    Scene scene = test::scene_from_json(kScene);
    PipelineOptions options;
    options.compaction = compaction;
    options.lanes = 1;
    FeatureSet features = scene.features();
    features.intersect_and_shade = shading == Shading::IntersectAndShade;
    Pipeline pipeline(scene, choose_device(""), kCapacity, kCapacity, features, options);
    std::mt19937 random(7);
    std::uniform_real_distribution<float> coordinate(-1.0f, 1.0f);
    std::vector<test::TestRay> rays(kCapacity);
    for (test::TestRay& r : rays)
        r = test::TestRay{glm::vec3(0.0f), glm::normalize(glm::vec3(coordinate(random), coordinate(random), -1.0f))};
    test::start_paths(pipeline, rays);
    pipeline.queues().set_queue(WP_QUEUE_RAY, queued);
    if (shading == Shading::IntersectAndShade) {
        pipeline.run_alone(Stage::intersect_and_shade);
    } else {
        pipeline.run_alone(Stage::intersect);
        pipeline.run_alone(Stage::shade);
    }
    QueuesAfterShade q;
    for (std::uint32_t slot : queued)
        (hits_the_sphere(rays[slot].direction) ? q.expected_ray : q.expected_free).push_back(slot);
    std::sort(q.expected_free.begin(), q.expected_free.end());
    std::sort(q.expected_ray.begin(), q.expected_ray.end());
    q.free = pipeline.queues().read_queue(WP_QUEUE_FREE);
    q.ray = pipeline.queues().read_queue(WP_QUEUE_RAY);
    return q;
}

// 3000 of the 4096 slots, shuffled.
std::vector<std::uint32_t> shuffled_subset() {
    std::vector<std::uint32_t> slots(kCapacity);
    for (std::uint32_t i = 0; i < kCapacity; ++i) slots[i] = i;
    std::mt19937 random(11);
    std::shuffle(slots.begin(), slots.end(), random);
    slots.resize(3000);
    return slots;
}

TEST(Compaction, PrefixSumKeepsExactlyTheLivePathsInAscendingOrder) {
    QueuesAfterShade q = queues_after_shade(Compaction::Scan, shuffled_subset());
    EXPECT_GT(q.expected_ray.size(), 300u);
    EXPECT_GT(q.expected_free.size(), 300u);  // both outcomes occur
    EXPECT_EQ(q.ray, q.expected_ray);         // the same slots, in ascending order
    EXPECT_EQ(q.free, q.expected_free);
}

// RAY is both the queue intersect_and_shade takes and one it pushes to.
TEST(Compaction, PrefixSumBuildsTheQueueAStageTakesAndPushesTo) {
    QueuesAfterShade q = queues_after_shade(Compaction::Scan, shuffled_subset(), Shading::IntersectAndShade);
    EXPECT_GT(q.expected_ray.size(), 300u);
    EXPECT_GT(q.expected_free.size(), 300u);
    EXPECT_EQ(q.ray, q.expected_ray);
    EXPECT_EQ(q.free, q.expected_free);
}

TEST(Compaction, AtomicPushKeepsExactlyTheLivePaths) {
    QueuesAfterShade q = queues_after_shade(Compaction::Atomic, shuffled_subset());
    std::sort(q.ray.begin(), q.ray.end());  // their order is not stable
    std::sort(q.free.begin(), q.free.end());
    EXPECT_EQ(q.ray, q.expected_ray);
    EXPECT_EQ(q.free, q.expected_free);
}

// The image does not depend on how the queues are filled (nor on their order).
TEST(Compaction, BothCompactionsRenderTheSameImage) {
    Scene scene = test::scene_from_file("scenes/room.json");
    scene.camera.width = scene.camera.height = 32;
    scene.render.spp = 3;
    WavefrontOptions options;
    options.wavefront = 512;
    options.compaction = Compaction::Scan;
    options.lanes = 1;  // as atomic compaction needs
    RenderResult scan = render_wavefront(scene, options, {});
    options.compaction = Compaction::Atomic;
    RenderResult atomic = render_wavefront(scene, options, {});
    EXPECT_EQ(scan.image.rgb, atomic.image.rgb);
    EXPECT_EQ(scan.stats.extension_rays, atomic.stats.extension_rays);
    EXPECT_EQ(scan.stats.shadow_rays, atomic.stats.shadow_rays);
}

}  // namespace
}  // namespace wp
