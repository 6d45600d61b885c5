// shade (its light sample, its shadow ray traced by shade itself or by
// intersect_shadow, and its BSDF sample) against the reference's matching
// functions, on hand-built paths.
#include <gtest/gtest.h>

#include <cmath>

#include "opencl/device.h"
#include "reference/path_tracer.h"
#include "wavefront/pipeline.h"
#include "wavefront_test_support.h"

namespace wp {
namespace {

using M = SharedMath<float>;
using vec3 = M::vec3;

// Runs intersect on the started paths, which queues their hits for shade.
std::vector<std::uint32_t> intersect_started_paths(Pipeline& pipeline) {
    pipeline.run_alone(Stage::intersect);
    return pipeline.queues().read_queue(WP_QUEUE_HIT);
}

constexpr const char* kLitPlane = R"({
  "camera": {"position": [0, 0, 0], "look_at": [0, 0, -1], "up": [0, 1, 0], "fov_y": 40, "width": 8, "height": 8},
  "render": {"spp": 1, "max_depth": 4, "rr_depth": 8, "seed": 11},
  "materials": {"floor": {"type": "diffuse", "albedo": [0.6, 0.5, 0.4]},
                "light": {"type": "emitter", "radiance": [5, 4, 3]}},
  "shapes": [{"type": "sphere", "center": [0.2, 0.3, -3], "radius": 0.25, "material": "floor"},
             {"type": "plane", "point": [0, -1, 0], "normal": [0, 1, 0], "material": "floor"},
             {"type": "quad", "corner": [-0.5, 1, -3.5], "edge1": [1, 0, 0], "edge2": [0, 0, 1], "material": "light"}]
})";

// Next-event estimation: light selection, the point on the light, the
// geometry terms (cosines, distance, solid-angle pdf), the shadow ray and its
// occlusion by the small sphere, per path against reference
// sample_direct_light; the shadow ray traced by intersect_shadow (shadow_stage) or by shade.
void expect_light_sample_matches_reference(bool shadow_stage) {
    Scene scene = test::scene_from_json(kLitPlane);
    reference::ReferenceScene<float> ref(scene);
    constexpr int kPaths = 2048;
    std::vector<test::TestRay> rays;
    for (int i = 0; i < kPaths; ++i) {  // a fan of rays onto the floor below the light
        float u = (i % 64) / 63.0f, v = (i / 64) / 31.0f;
        rays.push_back({vec3(0), glm::normalize(vec3(-1 + 2 * u, -1, -2.5f - 1.5f * v))});
    }
    FeatureSet features = scene.features();
    features.shadow_stage = shadow_stage;
    Pipeline pipeline(scene, choose_device(""), kPaths, kPaths, features);
    test::start_paths(pipeline, rays, 100);
    ASSERT_EQ(intersect_started_paths(pipeline).size(), std::size_t(kPaths));
    pipeline.run_alone(Stage::shade);
    EXPECT_EQ(pipeline.queues().read_queue(WP_QUEUE_RAY).size(), std::size_t(kPaths));  // max_depth 4, rr_depth 8
    if (shadow_stage) pipeline.run_alone(Stage::intersect_shadow);
    std::vector<float> radiance[3] = {pipeline.read_field<float>("radiance", 0),
                                      pipeline.read_field<float>("radiance", 1),
                                      pipeline.read_field<float>("radiance", 2)};
    int lit = 0, shadowed = 0;
    for (int i = 0; i < kPaths; ++i) {
        reference::Ray<float> ray{rays[i].origin, rays[i].direction};
        auto surface = reference::surface_at(ref, ray, reference::closest_hit(ref, ray));
        vec3 nf = glm::dot(ray.direction, surface.normal) < 0 ? surface.normal : -surface.normal;
        reference::SampleRng<float> rng = reference::sample_rng(ref, 0u, std::uint32_t(100 + i));
        reference::RayCounts counts;
        bool front = glm::dot(ray.direction, surface.normal) < 0;
        vec3 expected = reference::sample_direct_light(ref, surface.point, surface.error, nf, nf, front, -ray.direction,
                                                       vec3(1), ref.materials[surface.material], rng, 0u, counts);
        for (int c = 0; c < 3; ++c)
            ASSERT_NEAR(radiance[c][i], expected[c], 1e-6f * expected[c]) << "path " << i << " channel " << c;
        (expected.x > 0 ? lit : shadowed)++;
    }
    EXPECT_GT(lit, kPaths / 2);
    EXPECT_GT(shadowed, 20);  // the sphere's shadow is part of the fan
}

TEST(ShadeStage, LightSampleTracedInShadeMatchesReference) { expect_light_sample_matches_reference(false); }

TEST(ShadeStage, LightSampleTracedByIntersectShadowMatchesReference) { expect_light_sample_matches_reference(true); }

constexpr const char* kGlassSphere = R"({
  "camera": {"position": [0, 0, 0], "look_at": [0, 0, -1], "up": [0, 1, 0], "fov_y": 40, "width": 8, "height": 8},
  "render": {"spp": 1, "max_depth": 4, "rr_depth": 8, "seed": 13},
  "materials": {"glass": {"type": "glass", "ior": 1.5}},
  "shapes": [{"type": "sphere", "center": [0, 0, -5], "radius": 1, "material": "glass"}]
})";

// The reflect/refract split of shade's BSDF sampling against exact Fresnel, for rays
// entering at 60 degrees, leaving at 25.8 degrees, and beyond the critical
// angle (always reflected). With n paths the reflected fraction has standard
// deviation sqrt(F (1 - F) / n); |z| < 5 gives a false failure of 6e-7 per
// case. Every path's new direction and weight also match reference scatter.
TEST(ShadeStage, GlassSplitFollowsFresnelAndMatchesReference) {
    Scene scene = test::scene_from_json(kGlassSphere);
    reference::ReferenceScene<float> ref(scene);
    constexpr int kPerCase = 20000;
    struct Case {
        float height;  // the ray runs along -z at this y, from outside or inside
        bool inside;
    };
    const Case cases[] = {{0.8660254f, false}, {0.4358899f, true}, {0.8f, true}};
    Pipeline pipeline(scene, choose_device(""), 3 * kPerCase, 3 * kPerCase, scene.features());
    std::vector<test::TestRay> rays;
    for (const Case& c : cases)
        for (int i = 0; i < kPerCase; ++i) rays.push_back({vec3(0, c.height, c.inside ? -5 : 0), vec3(0, 0, -1)});
    test::start_paths(pipeline, rays);
    ASSERT_EQ(intersect_started_paths(pipeline).size(), rays.size());
    pipeline.run_alone(Stage::shade);
    ASSERT_EQ(pipeline.queues().read_queue(WP_QUEUE_RAY).size(), rays.size());  // rr_depth 8: no roulette yet
    std::vector<float> dir[3] = {pipeline.read_field<float>("direction", 0), pipeline.read_field<float>("direction", 1),
                                 pipeline.read_field<float>("direction", 2)};
    std::vector<float> weight = pipeline.read_field<float>("throughput", 0);
    for (int k = 0; k < 3; ++k) {
        SCOPED_TRACE("case " + std::to_string(k));
        int reflected = 0;
        float fresnel = 0;
        for (int i = k * kPerCase; i < (k + 1) * kPerCase; ++i) {
            reference::Ray<float> ray{rays[i].origin, rays[i].direction};
            auto surface = reference::surface_at(ref, ray, reference::closest_hit(ref, ray));
            bool entering = glm::dot(ray.direction, surface.normal) < 0;
            vec3 nf = entering ? surface.normal : -surface.normal;
            fresnel = M::fresnel_dielectric(-glm::dot(ray.direction, nf), entering ? 1.5f : 1 / 1.5f);
            reference::SampleRng<float> rng = reference::sample_rng(ref, 0u, std::uint32_t(i));
            auto next = reference::scatter(ref, ref.materials[0], ray.direction, entering, nf, nf,
                                           reference::camera_bsdf_random(rng, 0u, ref.materials[0].type, ref.mask),
                                           WP_TRANSPORT_RADIANCE);
            vec3 got(dir[0][i], dir[1][i], dir[2][i]);
            ASSERT_NEAR(glm::length(got - next.direction), 0.0f, 1e-6f) << "path " << i;
            ASSERT_NEAR(weight[i], next.weight.x, 1e-6f) << "path " << i;
            reflected += glm::dot(got, nf) > 0;
        }
        double n = kPerCase, fraction = reflected / n;
        double sigma = std::sqrt(std::max(fresnel * (1.0 - fresnel), 1e-12) / n);
        EXPECT_NEAR(fraction, fresnel, 5 * sigma + 1e-12) << "Fresnel " << fresnel;
        if (k == 2) {
            EXPECT_EQ(fresnel, 1.0f);  // total internal reflection
        } else {
            EXPECT_GT(reflected, 0);
            EXPECT_LT(reflected, kPerCase);
        }
    }
}

}  // namespace
}  // namespace wp
