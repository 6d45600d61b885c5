// Queue compaction: both ways of filling a queue keep exactly the live paths;
// the prefix-sum compaction also keeps them in ascending slot order, builds
// the queue a stage pushes to while reading it (intersect_and_shade's RAY)
// as it builds any other, and only counts the queues read for their length.
#include "wavefront/compaction.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <random>

#include "opencl/program_cache.h"
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

// ScanCompaction on marks set at random over 1000 slots (three whole blocks
// and a part): FREE and RAY built, SHADOW only counted, the marks of FREE and
// SHADOW cleared. A built queue holds its marked slots in ascending order; a
// counted one gets their number as its length and keeps the entries it
// held; only the cleared queues' marks go to 0.
TEST(Compaction, PrefixSumOnlyCountsTheQueuesItCounts) {
    constexpr std::uint32_t capacity = 1000;
    constexpr std::uint32_t kUntouched = 0xdeadbeefu;
    std::vector<std::uint32_t> buffer(2 * WP_QUEUE_COUNT * capacity, kUntouched);
    std::mt19937 random(5);
    std::vector<std::vector<std::uint32_t>> marked(WP_QUEUE_COUNT);
    for (std::uint32_t queue : {WP_QUEUE_FREE, WP_QUEUE_RAY, WP_QUEUE_SHADOW})
        for (std::uint32_t slot = 0; slot < capacity; ++slot) {
            const std::uint32_t mark = random() % 3 == 0 ? 1u : 0u;
            buffer[WP_QUEUE_MARKS(queue) * capacity + slot] = mark;
            if (mark) marked[queue].push_back(slot);
        }
    DeviceInfo device = choose_device("");
    cl::Context context(device.device);
    cl::CommandQueue queue(context, device.device);
    KernelLauncher launcher(queue, false);
    BuiltProgram program = build_program(context, device, {"compact.cl"}, compaction_build_option(Compaction::Scan));
    cl::Buffer queues(context, CL_MEM_READ_WRITE | CL_MEM_COPY_HOST_PTR, sizeof(std::uint32_t) * buffer.size(),
                      buffer.data());
    std::vector<std::uint32_t> lengths(WP_COUNTS_SIZE, kUntouched);
    cl::Buffer counts(context, CL_MEM_READ_WRITE | CL_MEM_COPY_HOST_PTR, sizeof(std::uint32_t) * lengths.size(),
                      lengths.data());
    ScanCompaction scan(context, program.program, queues, counts, capacity);
    const std::uint32_t free = 1u << WP_QUEUE_FREE, ray = 1u << WP_QUEUE_RAY, shadow = 1u << WP_QUEUE_SHADOW;
    scan.compact(launcher, {.built = free | ray, .counted = shadow, .cleared = free | shadow});
    queue.enqueueReadBuffer(queues, CL_TRUE, 0, sizeof(std::uint32_t) * buffer.size(), buffer.data());
    queue.enqueueReadBuffer(counts, CL_TRUE, 0, sizeof(std::uint32_t) * lengths.size(), lengths.data());
    auto entries = [&](std::uint32_t q, std::size_t n) {
        return std::vector<std::uint32_t>(buffer.begin() + q * capacity, buffer.begin() + q * capacity + n);
    };
    auto marks = [&](std::uint32_t q) {
        const auto first = buffer.begin() + WP_QUEUE_MARKS(q) * capacity;
        return std::vector<std::uint32_t>(first, first + capacity);
    };
    for (std::uint32_t q : {WP_QUEUE_FREE, WP_QUEUE_RAY, WP_QUEUE_SHADOW}) {
        SCOPED_TRACE("queue " + std::to_string(q));
        EXPECT_GT(marked[q].size(), 250u);
        EXPECT_EQ(lengths[q], marked[q].size());
    }
    EXPECT_EQ(entries(WP_QUEUE_FREE, marked[WP_QUEUE_FREE].size()), marked[WP_QUEUE_FREE]);
    EXPECT_EQ(entries(WP_QUEUE_RAY, marked[WP_QUEUE_RAY].size()), marked[WP_QUEUE_RAY]);
    EXPECT_EQ(entries(WP_QUEUE_SHADOW, capacity), std::vector<std::uint32_t>(capacity, kUntouched));
    EXPECT_EQ(marks(WP_QUEUE_FREE), std::vector<std::uint32_t>(capacity, 0u));
    EXPECT_EQ(marks(WP_QUEUE_SHADOW), std::vector<std::uint32_t>(capacity, 0u));
    std::vector<std::uint32_t> ray_marks(capacity, 0u);  // kept: generate adds to them
    for (std::uint32_t slot : marked[WP_QUEUE_RAY]) ray_marks[slot] = 1u;
    EXPECT_EQ(marks(WP_QUEUE_RAY), ray_marks);
    EXPECT_EQ(lengths[WP_QUEUE_HIT], kUntouched);  // not selected
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
