// Multiple importance sampling in the reference (src/reference/path_tracer.h).
//
// Unbiasedness with MIS is checked against closed forms by the analytic tests
// (analytic_scenes_test.cpp, mesh_analytic_test.cpp: MIS is the default, and
// "mis off" is one of the sampling variants) and against Mitsuba 3 by the
// oracle test. Here: the two densities the power heuristic combines are the
// ones the two strategies really have, and the combination pays where it
// should.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <random>
#include <vector>

#include "reference/path_tracer.h"
#include "support/analytic_scenes.h"
#include "support/meshes.h"
#include "support/statistics.h"

namespace {

using M = wp::SharedMath<double>;
using vec3 = M::vec3;
using wp::reference::ReferenceScene;

// feature_room (a quad light, a sphere light, an emissive diffuse sphere) and
// an emissive icosphere: every light kind, with unequal selection
// probabilities.
wp::Scene every_light_kind() {
    wp::Scene scene = wp::test::feature_room({});
    wp::Material glow;
    glow.type = wp::MaterialType::Emitter;
    glow.emission = {3, 2, 1};
    scene.materials.push_back(glow);
    scene.meshes.push_back(wp::test::transformed(wp::test::icosphere(1, static_cast<int>(scene.materials.size()) - 1),
                                                 0.15, {-0.2, 1.1, -3.6}));
    wp::build_light_table(scene);
    return scene;
}

// For points on the room's diffuse surfaces and every light: a light sample
// that reaches its point unoccluded is also a ray the BSDF could have traced,
// and light_pdf_at_hit must give that ray's hit the density the light sample
// had (selection probability times point density). This is what makes the two
// power-heuristic weights of one path sum to 1; a missing selection
// probability, a sphere's cone density from the wrong point or a mesh light's
// wrong area breaks it.
TEST(ReferenceMis, LightDensityAtAHitIsTheLightSamplesDensity) {
    wp::Scene scene = every_light_kind();
    ReferenceScene<double> reference(scene);
    ASSERT_EQ(reference.lights.size(), 4u);
    std::mt19937 random(7);
    std::uniform_real_distribution<double> uniform(0.0, 1.0);
    int compared_per_light[4] = {0, 0, 0, 0};
    for (int i = 0; i < 4000; ++i) {
        // A point seen by a random camera ray, if diffuse.
        wp::reference::Ray<double> camera{
            reference.camera.position, M::camera_direction(reference.camera.frame, uniform(random), uniform(random))};
        auto hit = wp::reference::closest_hit(reference, camera);
        if (!hit.found()) continue;
        auto x = wp::reference::surface_at(reference, camera, hit);
        if (reference.materials[x.material].type != wp::MaterialType::Diffuse) continue;
        vec3 nf = glm::dot(camera.direction, x.normal) < 0 ? x.normal : -x.normal;
        vec3 origin = M::offset_ray_origin(x.point, nf, x.error);
        for (std::uint32_t l = 0; l < reference.lights.size(); ++l) {
            auto p = wp::reference::sample_light(reference, reference.lights[l], origin, uniform(random),
                                                 uniform(random), uniform(random));
            if (p.sample.pdf_solid_angle == 0) continue;
            vec3 to_light = p.sample.point - origin;
            wp::reference::Ray<double> ray{origin, glm::normalize(to_light)};
            auto light_hit = wp::reference::closest_hit(reference, ray);
            if (!light_hit.found() || std::abs(light_hit.t - glm::length(to_light)) > 1e-6 * glm::length(to_light))
                continue;  // occluded, or the light's own far side
            auto y = wp::reference::surface_at(reference, ray, light_hit);
            double expected = p.sample.pdf_solid_angle * M::light_selection_pmf(reference.light_cdf.data(), l);
            double found = wp::reference::light_pdf_at_hit(reference, light_hit, origin, y.point, y.normal);
            // The hit point is the sampled point moved by rounding (relative 1e-12 in double); the density's
            // distance^2 / cos changes by a few times that.
            ASSERT_NEAR(found, expected, 1e-8 * expected) << "light " << l << " sample " << i;
            ++compared_per_light[l];
        }
    }
    for (int l = 0; l < 4; ++l) EXPECT_GE(compared_per_light[l], 50) << "light " << l << " was rarely visible";
}

// Where a light fills much of the sky, a diffuse bounce finds it with a
// density far above the light sample's in the grazing directions the light
// sample rarely picks (and whose contributions it divides by a small
// density); MIS then has much less variance than the light sample alone. A
// floor pixel under an 8x8 light 1.2 above it, direct light only: the sample variance of one camera
// sample's radiance, from 40,000 samples each (relative standard error of a
// variance estimate about sqrt(2 / n) = 0.7% for normal data, a few percent
// for these heavy tails). Measured ratio: 0.041; the test asks for below 0.5.
TEST(ReferenceMis, LowersTheVarianceUnderALargeCloseLight) {
    wp::test::RenderBlock block{.width = 1, .height = 1, .spp = 1, .max_depth = 1};
    wp::Scene scene = wp::test::plane_under_square_light(block, {0.5, 0.5, 0.5}, {1, 1, 1}, 4.0, 1.2);
    double variance[2];
    for (bool mis : {false, true}) {
        scene.render.mis = mis;
        ReferenceScene<double> reference(scene);
        wp::test::RunningMean radiance;
        wp::reference::RayCounts counts;
        for (int s = 0; s < 40000; ++s) radiance.add(wp::reference::trace_camera_sample(reference, 0, 0, s, counts).x);
        variance[mis] = radiance.variance();
        double expected = wp::test::plane_under_square_light_radiance(0.5, 1.0, 4.0, 1.2);
        EXPECT_NEAR(radiance.mean(), expected, 4.5 * radiance.standard_error()) << "mis " << mis;
    }
    EXPECT_LT(variance[1], 0.5 * variance[0]) << "variance with MIS " << variance[1] << ", without " << variance[0];
}

// The sample variance of `values` and its standard error, sqrt((m4 - m2^2) /
// n) from their central moments (the variance estimate's own spread, for any
// distribution with a fourth moment).
struct VarianceEstimate {
    double variance, standard_error;
};
VarianceEstimate variance_of(const std::vector<double>& values) {
    const double n = double(values.size());
    double mean = 0.0, m2 = 0.0, m4 = 0.0;
    for (double v : values) mean += v / n;
    for (double v : values) {
        const double d2 = (v - mean) * (v - mean);
        m2 += d2 / n;
        m4 += d2 * d2 / n;
    }
    return {m2 * n / (n - 1.0), std::sqrt(std::max(0.0, m4 - m2 * m2) / n)};
}

// Where one strategy is nearly perfect, the power heuristic keeps its low
// variance and the balance heuristic does not (Veach's thesis, chapter 9): a
// floor pixel under a 0.4x0.4 light 2 above it, direct light only. The light
// sample's contribution varies only with the light's small spread of
// distances and angles; a diffuse bounce finds the light with probability
// about 1.3%, with a density p_bounce about 1/80 of the light sample's
// p_light. The balance heuristic gives such a hit the value f / (p_bounce +
// p_light), nearly that of a whole light sample; the power heuristic f
// p_bounce / (p_bounce^2 + p_light^2), about 1/80 of it. So with balance the
// rare hits multiply the variance of light sampling alone by about 175, with
// power by 1.03 (this geometry's two estimators written apart from the
// renderer, in numpy, 2e6 samples each; measured here: 1.030, and 202 with
// the balance heuristic swapped into sampling.h). The test asks the variance
// with MIS to stay below 1.5 times the light sample's alone, at the ends of
// both variances' 4.5-standard-error intervals (the standard errors from
// the samples' fourth moments, about 1% here): a correct renderer fails with
// probability below 1.4e-5. 20,000 samples each, fixed seed.
TEST(ReferenceMis, KeepsTheVarianceOfANearlyPerfectLightSample) {
    wp::test::RenderBlock block{.width = 1, .height = 1, .spp = 1, .max_depth = 1};
    const double half_side = 0.2, height = 2.0;
    wp::Scene scene = wp::test::plane_under_square_light(block, {0.5, 0.5, 0.5}, {100, 100, 100}, half_side, height);
    const double expected = wp::test::plane_under_square_light_radiance(0.5, 100.0, half_side, height);
    VarianceEstimate estimate[2];
    for (bool mis : {false, true}) {
        scene.render.mis = mis;
        ReferenceScene<double> reference(scene);
        wp::reference::RayCounts counts;
        std::vector<double> radiance;
        wp::test::RunningMean mean;
        for (int s = 0; s < 20000; ++s) {
            radiance.push_back(wp::reference::trace_camera_sample(reference, 0, 0, s, counts).x);
            mean.add(radiance.back());
        }
        EXPECT_NEAR(mean.mean(), expected, 4.5 * mean.standard_error()) << "mis " << mis;
        estimate[mis] = variance_of(radiance);
    }
    const double mis_high = estimate[1].variance + 4.5 * estimate[1].standard_error;
    const double light_low = estimate[0].variance - 4.5 * estimate[0].standard_error;
    std::printf("[figure] variance with MIS %.4g (+- %.2g), light sample alone %.4g (+- %.2g): ratio %.3f\n",
                estimate[1].variance, estimate[1].standard_error, estimate[0].variance, estimate[0].standard_error,
                estimate[1].variance / estimate[0].variance);
    EXPECT_LT(mis_high, 1.5 * light_low) << "variance with MIS " << estimate[1].variance << ", light sample alone "
                                         << estimate[0].variance;
}

}  // namespace
