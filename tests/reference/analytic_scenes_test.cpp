// The reference renderer against closed-form pixel values (the scenes and
// their derivations are in support/analytic_scenes.h), in float and double.
//
// Acceptance: per channel, |mean - expected| <= 4.5 standard errors of the
// mean over pixels (pixels are independent; a normal estimate falls outside
// with probability 6.8e-6, so the ~120 channel checks here fail spuriously
// with probability < 1e-3; the seeds are fixed, so a pass is reproducible)
// plus an allowance for rounding: 2e-6 of the value in float (the path
// arithmetic; measured deviations stay below 2e-7), 1.2e-7 in double (one
// float ULP: the image stores float). Where the estimator has no variance at
// all (no roulette inside the emissive sphere) only this allowance is left.
#include "support/analytic_scenes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <glm/trigonometric.hpp>
#include <limits>
#include <numbers>
#include <string>
#include <type_traits>
#include <utility>

#include "reference/reference_renderer.h"
#include "support/image_statistics.h"
#include "support/real_types.h"
#include "support/sampling_variants.h"

namespace {

using wp::test::RenderBlock;

template <class Real>
class ReferenceAnalytic : public ::testing::Test {
 protected:
    static wp::RenderResult render(const wp::Scene& scene) {
        return wp::render_reference(scene, {.threads = 2, .double_precision = std::is_same_v<Real, double>});
    }
    static constexpr double kRounding = std::is_same_v<Real, float> ? 2e-6 : 1.2e-7;

    static void expect_channel(const wp::test::RunningMean& mean, double expected, const std::string& what) {
        double tolerance = wp::test::kSigmaTolerance * mean.standard_error() + kRounding * expected;
        EXPECT_NEAR(mean.mean(), expected, tolerance) << what << ", standard error " << mean.standard_error();
    }
};
TYPED_TEST_SUITE(ReferenceAnalytic, wp::test::RealTypes, wp::test::RealTypeNames);

const glm::dvec3 kRho(0.3, 0.5, 0.8);
const glm::dvec3 kLe(1.0, 2.0, 0.5);

TYPED_TEST(ReferenceAnalytic, InsideEmissiveSphereTruncatedNeumannSeries) {
    for (int max_depth : {0, 1, 2, 5, 20}) {
        RenderBlock block{.width = 16, .height = 16, .spp = 4, .max_depth = max_depth};
        wp::RenderResult result = this->render(wp::test::inside_emissive_sphere(block, kRho, kLe));
        EXPECT_EQ(result.stats.nonfinite, 0u);
        for (int c = 0; c < 3; ++c) {
            double expected = wp::test::inside_emissive_sphere_radiance(kRho[c], kLe[c], max_depth);
            this->expect_channel(wp::test::channel_mean(result.image, c), expected,
                                 "max_depth " + std::to_string(max_depth) + " channel " + std::to_string(c));
        }
    }
}

// NEE off (emission counted at every hit) and uniform hemisphere sampling
// (weight 2 cos albedo) estimate the same truncated series.
TYPED_TEST(ReferenceAnalytic, InsideEmissiveSphereSamplingVariantsAgree) {
    for (const wp::test::SamplingVariant& variant : wp::test::kSamplingVariants) {
        for (int max_depth : {1, 5}) {
            RenderBlock block{.width = 32, .height = 32, .spp = 16, .max_depth = max_depth};
            wp::RenderResult result =
                this->render(wp::test::with_sampling(wp::test::inside_emissive_sphere(block, kRho, kLe), variant));
            EXPECT_EQ(result.stats.nonfinite, 0u);
            if (!variant.nee) {
                EXPECT_EQ(result.stats.shadow_rays, 0u);
            }
            for (int c = 0; c < 3; ++c) {
                double expected = wp::test::inside_emissive_sphere_radiance(kRho[c], kLe[c], max_depth);
                this->expect_channel(wp::test::channel_mean(result.image, c), expected,
                                     std::string(variant.name) + " max_depth " + std::to_string(max_depth) +
                                         " channel " + std::to_string(c));
            }
        }
    }
}

// Russian roulette from the first or the second bounce on: noisier, same mean.
TYPED_TEST(ReferenceAnalytic, InsideEmissiveSphereWithRouletteIsUnbiased) {
    for (int rr_depth : {0, 1}) {
        for (int max_depth : {3, 20}) {
            RenderBlock block{.width = 32, .height = 32, .spp = 16, .max_depth = max_depth, .rr_depth = rr_depth};
            wp::RenderResult result = this->render(wp::test::inside_emissive_sphere(block, kRho, kLe));
            for (int c = 0; c < 3; ++c) {
                double expected = wp::test::inside_emissive_sphere_radiance(kRho[c], kLe[c], max_depth);
                wp::test::RunningMean mean = wp::test::channel_mean(result.image, c);
                EXPECT_GT(mean.standard_error(), 0.0);  // roulette did act
                this->expect_channel(mean, expected,
                                     "rr_depth " + std::to_string(rr_depth) + " max_depth " +
                                         std::to_string(max_depth) + " channel " + std::to_string(c));
            }
        }
    }
}

// Exact (support/analytic_scenes.h, (b)): each pixel is background * (1 - f
// (1 - factor)) with one hit fraction f in [0, 1] for all channels; the
// sphere's centre shows factor * background, the image corner background.
// Tolerance: the float image and a few roundings of the Real product.
template <class Real>
void expect_sphere_over_background(const wp::Image& image, const glm::dvec3& factor, const glm::dvec3& background) {
    const double tol = 4.0 * std::numeric_limits<float>::epsilon();
    int inside = 0, outside = 0;
    for (int y = 0; y < image.height; ++y) {
        for (int x = 0; x < image.width; ++x) {
            double hit_fraction[3];
            for (int c = 0; c < 3; ++c) {
                double v = wp::test::pixel_channel(image, x, y, c);
                double sphere = static_cast<double>(Real(factor[c]) * Real(background[c]));
                hit_fraction[c] = (background[c] - v) / (background[c] - sphere);
            }
            for (int c = 0; c < 3; ++c) {
                ASSERT_GE(hit_fraction[c], -tol) << x << ", " << y;
                ASSERT_LE(hit_fraction[c], 1.0 + tol) << x << ", " << y;
                ASSERT_NEAR(hit_fraction[c], hit_fraction[0], 2.0 * tol) << x << ", " << y << " channel " << c;
            }
            inside += hit_fraction[0] > 1.0 - tol;
            outside += hit_fraction[0] < tol;
        }
    }
    // The sphere (radius 1 at distance 4.03: 11 pixels of radius in a 32
    // pixel, 40 degree field of view) covers about a third of the image.
    EXPECT_GT(inside, 200);
    EXPECT_GT(outside, 500);
    EXPECT_NEAR(wp::test::pixel_channel(image, 17, 17, 1), factor.y * background.y, tol * background.y);
    EXPECT_EQ(wp::test::pixel_channel(image, 0, 0, 2), static_cast<float>(background.z));
}

const RenderBlock kSphereBlock{.width = 32, .height = 32, .spp = 8, .max_depth = 6};
const glm::dvec3 kBackground(1.0, 0.5, 2.0);

// Every pixel equals value, up to `relative` (float image, Real rounding).
void expect_uniform_image(const wp::Image& image, const glm::dvec3& value, double relative, const std::string& what) {
    for (std::size_t i = 0; i < image.rgb.size(); ++i) {
        int c = static_cast<int>(i % 3);
        ASSERT_NEAR(image.rgb[i], value[c], relative * value[c]) << what << " pixel " << i / 3 << " channel " << c;
    }
}

// Each channel's image mean equals expected within kSigmaTolerance of its
// standard error, which must not be 0: a light chosen at random among
// several (one hidden) makes the pixels vary.
void expect_mean_where_the_choice_varies(const wp::Image& image, const glm::dvec3& expected) {
    for (int c = 0; c < 3; ++c) {
        wp::test::RunningMean mean = wp::test::channel_mean(image, c);
        EXPECT_GT(mean.standard_error(), 0.0);  // the light choice does vary
        EXPECT_NEAR(mean.mean(), expected[c], wp::test::kSigmaTolerance * mean.standard_error()) << "channel " << c;
    }
}

TYPED_TEST(ReferenceAnalytic, DiffuseSphereUnderBackgroundShowsAlbedoTimesBackground) {
    const glm::dvec3 albedo(0.2, 0.5, 0.9);
    wp::RenderResult result =
        this->render(wp::test::sphere_under_background(kSphereBlock, wp::test::diffuse(albedo), kBackground));
    expect_sphere_over_background<TypeParam>(result.image, albedo, kBackground);
}

TYPED_TEST(ReferenceAnalytic, MirrorSphereUnderBackgroundShowsReflectanceTimesBackground) {
    const glm::dvec3 reflectance(0.9, 0.4, 0.1);
    wp::RenderResult result =
        this->render(wp::test::sphere_under_background(kSphereBlock, wp::test::mirror(reflectance), kBackground));
    expect_sphere_over_background<TypeParam>(result.image, reflectance, kBackground);
}

// Every sample returns the background: 1/eta^2 entering, eta^2 leaving. Also
// with Russian roulette from the first bounce on: its survival factors the
// refractions' 1/eta^2 out (roulette_survival), so no path inside the glass is
// at risk and the image stays noiseless (a survival from the throughput
// alone, 1/eta^2 inside, kills paths there and makes noise).
TYPED_TEST(ReferenceAnalytic, GlassSphereUnderBackgroundIsInvisible) {
    for (int rr_depth : {1 << 30, 1}) {
        for (double ior : {1.0, 1.5, 2.4}) {
            RenderBlock block = kSphereBlock;
            block.max_depth = 64;
            block.rr_depth = rr_depth;
            wp::RenderResult result =
                this->render(wp::test::sphere_under_background(block, wp::test::glass(ior), kBackground));
            expect_uniform_image(result.image, kBackground, 1e-5,
                                 "ior " + std::to_string(ior) + ", rr_depth " + std::to_string(rr_depth));
        }
    }
}

TYPED_TEST(ReferenceAnalytic, FloorUnderBackgroundShowsAlbedoTimesBackgroundFromEitherSide) {
    const glm::dvec3 albedo(0.2, 0.5, 0.9);
    for (double normal_sign : {1.0, -1.0}) {
        RenderBlock block{.width = 16, .height = 16, .spp = 4, .max_depth = 3};
        wp::RenderResult result =
            this->render(wp::test::floor_under_background(block, albedo, kBackground, normal_sign));
        expect_uniform_image(result.image, albedo * kBackground, 4 * std::numeric_limits<float>::epsilon(),
                             "normal sign " + std::to_string(normal_sign));
    }
}

// The white furnace with the environment as a light: next-event estimation
// with and without MIS, and with a brighter light below the floor that no
// floor point sees (the environment's selection probability, from its power
// over the scene's bounding sphere, is then below 1 and divides its light
// samples). Per channel, the image mean of independent pixels against
// albedo * L within kSigmaTolerance of its own standard errors (a false
// failure with probability 6.8e-6 per check, 12 checks).
TYPED_TEST(ReferenceAnalytic, FloorUnderEnvironmentLightShowsAlbedoTimesRadiance) {
    const glm::dvec3 albedo(0.2, 0.5, 0.9), radiance(1.0, 0.5, 2.0);
    for (bool mis : {false, true}) {
        for (bool hidden_light : {false, true}) {
            RenderBlock block{.width = 32, .height = 32, .spp = 4, .max_depth = 3};
            wp::Scene scene = wp::test::floor_under_environment(block, albedo, radiance, mis);
            if (hidden_light) wp::test::add_hidden_light_below_floor(scene, glm::dvec3(40.0));
            ASSERT_TRUE(scene.features().constant_environment);
            wp::RenderResult result = this->render(scene);
            for (int c = 0; c < 3; ++c) {
                wp::test::RunningMean mean = wp::test::channel_mean(result.image, c);
                EXPECT_GT(mean.standard_error(), 0.0);  // the light samples do vary
                EXPECT_NEAR(mean.mean(), albedo[c] * radiance[c], wp::test::kSigmaTolerance * mean.standard_error())
                    << "mis " << mis << ", hidden light " << hidden_light << ", channel " << c;
            }
        }
    }
}

// The white furnace under a constant environment map (importance-sampled
// by its cells, the density's sin(t) and the map's frame included) shows
// what it shows under the constant environment: albedo * L, next-event
// estimation with and without MIS, with and without a hidden brighter
// light dividing the choice, within kSigmaTolerance standard errors (as above).
TYPED_TEST(ReferenceAnalytic, FloorUnderConstantEnvironmentMapShowsAlbedoTimesRadiance) {
    const glm::dvec3 albedo(0.2, 0.5, 0.9), radiance(1.0, 0.5, 2.0);
    for (bool mis : {false, true}) {
        for (bool hidden_light : {false, true}) {
            RenderBlock block{.width = 32, .height = 32, .spp = 4, .max_depth = 3};
            wp::Scene scene = wp::test::floor_under_constant_environment_map(block, albedo, radiance, mis);
            if (hidden_light) wp::test::add_hidden_light_below_floor(scene, glm::dvec3(40.0));
            ASSERT_TRUE(scene.features().environment_map);
            ASSERT_FALSE(scene.features().constant_environment);
            wp::RenderResult result = this->render(scene);
            for (int c = 0; c < 3; ++c) {
                wp::test::RunningMean mean = wp::test::channel_mean(result.image, c);
                EXPECT_GT(mean.standard_error(), 0.0);  // the light samples do vary
                EXPECT_NEAR(mean.mean(), albedo[c] * radiance[c], wp::test::kSigmaTolerance * mean.standard_error())
                    << "mis " << mis << ", hidden light " << hidden_light << ", channel " << c;
            }
        }
    }
}

// A directional light on a diffuse floor: exactly albedo / pi * E cos(theta)
// in every pixel (a few roundings); with a light below the floor
// that no floor point sees, the directional light's selection probability
// (its power pi r^2 luminance(E) over the bounding sphere against the
// sphere light's) divides its samples and the image mean stays, within
// kSigmaTolerance standard errors.
TYPED_TEST(ReferenceAnalytic, FloorUnderDirectionalLightShowsAlbedoTimesIrradianceCosineOverPi) {
    const glm::dvec3 albedo(0.2, 0.5, 0.9), irradiance(3.0, 2.0, 1.0);
    const double theta = 0.6;
    const glm::dvec3 expected = albedo / std::numbers::pi * irradiance * std::cos(theta);
    RenderBlock block{.width = 16, .height = 16, .spp = 4, .max_depth = 3};
    wp::Scene scene = wp::test::floor_under_directional_light(block, albedo, irradiance, theta);
    ASSERT_TRUE(scene.features().directional_lights);
    expect_uniform_image(this->render(scene).image, expected, 1e-5, "directional light alone");

    block.spp = 16;
    scene = wp::test::floor_under_directional_light(block, albedo, irradiance, theta);
    wp::test::add_hidden_light_below_floor(scene, glm::dvec3(0.2));  // chosen with probability 0.55
    expect_mean_where_the_choice_varies(this->render(scene).image, expected);
}

// A point light at the centre of a diffuse sphere (radius R) seen from the
// centre: exactly albedo / pi * I / R^2 in every pixel (a few roundings), at
// two radii (the inverse square law); with a light outside the sphere that
// no inside point sees, the point light's selection probability (its power
// 4 pi luminance(I) against the sphere light's) divides its samples and the
// image mean stays, within kSigmaTolerance standard errors.
TYPED_TEST(ReferenceAnalytic, PointLightInsideSphereShowsAlbedoTimesIntensityOverPiRSquared) {
    const glm::dvec3 albedo(0.2, 0.5, 0.9), intensity(3.0, 2.0, 1.0);
    for (double radius : {2.0, 0.5}) {
        RenderBlock block{.width = 16, .height = 16, .spp = 4};
        wp::Scene scene = wp::test::inside_sphere_around_point_light(block, albedo, radius, intensity, std::nullopt);
        ASSERT_TRUE(scene.features().point_lights);
        expect_uniform_image(this->render(scene).image, albedo / std::numbers::pi * intensity / (radius * radius), 1e-5,
                             "radius " + std::to_string(radius));
    }
    RenderBlock block{.width = 16, .height = 16, .spp = 16};
    wp::Scene scene = wp::test::inside_sphere_around_point_light(block, albedo, 2.0, intensity, std::nullopt);
    scene.spheres.push_back({{0.3, 5.0, 0.2}, 0.5, wp::test::add_material(scene, wp::test::emitter(glm::dvec3(1.0)))});
    wp::build_light_table(scene);
    ASSERT_GT(scene.light_cdf[0], 0.1);  // the hidden light takes a share of the choice ...
    ASSERT_LT(scene.light_cdf[0], 0.9);  // ... and so does the point light
    expect_mean_where_the_choice_varies(this->render(scene).image, albedo / std::numbers::pi * intensity / 4.0);
}

// The same with a spot pointing along the view, Mitsuba's falloff: 1 within
// the beam width, falling linearly in the angle to 0 at the cutoff angle.
// Each pixel's samples take directions between its nearest and farthest
// angle from the axis (the image plane's distances tan(angle) from its
// centre to the pixel's rectangle), so its value lies between the falloffs
// there times albedo / pi * I / R^2: exactly that within the beam, exactly 0
// beyond the cutoff, and in between across the transition. A cone of 90
// degrees and no beam makes the transition the whole image, where a falloff
// linear in the cosine instead (cos theta, 0.87 at 30 degrees against 0.67)
// leaves every pixel's bounds.
TYPED_TEST(ReferenceAnalytic, SpotInsideSphereFallsOffLinearlyInAngle) {
    const glm::dvec3 albedo(0.2, 0.5, 0.9), intensity(3.0, 2.0, 1.0);
    const double radius = 2.0;
    const int size = 16;
    const glm::dvec3 full = albedo / std::numbers::pi * intensity / (radius * radius);
    for (const std::pair<double, double>& cone : {std::pair{35.0, 20.0}, std::pair{90.0, 0.0}}) {
        // named copies, not a structured binding: clang 15 (the sanitizer build) lets no lambda capture one
        const double cutoff = cone.first, beam = cone.second;
        SCOPED_TRACE("cutoff " + std::to_string(cutoff) + ", beam width " + std::to_string(beam));
        RenderBlock block{.width = size, .height = size, .spp = 4};
        const wp::Image image = this->render(wp::test::inside_sphere_around_point_light(
                                                 block, albedo, radius, intensity,
                                                 wp::SpotCone{.cutoff_angle = cutoff, .beam_width = beam}))
                                    .image;
        auto falloff = [&](double distance) {  // at the angle atan(distance) from the axis
            return std::clamp((cutoff - glm::degrees(std::atan(distance))) / (cutoff - beam), 0.0, 1.0);
        };
        int inside = 0, transition = 0, outside = 0;
        for (int row = 0; row < size; ++row) {
            for (int column = 0; column < size; ++column) {
                // The pixel's rectangle on the image plane at distance 1 (fov 90: [-1, 1]^2).
                const double x0 = 2.0 * column / size - 1.0, x1 = 2.0 * (column + 1) / size - 1.0;
                const double y0 = 1.0 - 2.0 * (row + 1) / size, y1 = 1.0 - 2.0 * row / size;
                const double near = std::hypot(std::clamp(0.0, x0, x1), std::clamp(0.0, y0, y1));
                const double far =
                    std::hypot(std::max(std::fabs(x0), std::fabs(x1)), std::max(std::fabs(y0), std::fabs(y1)));
                const double most = falloff(near), least = falloff(far);
                inside += least == 1.0;
                outside += most == 0.0;
                transition += least < 1.0 && most > 0.0;
                for (int c = 0; c < 3; ++c) {
                    const double value = image.rgb[3 * std::size_t(row * size + column) + c];
                    EXPECT_GE(value, full[c] * least * (1 - 1e-5)) << "pixel " << column << ", " << row;
                    EXPECT_LE(value, full[c] * most * (1 + 1e-5)) << "pixel " << column << ", " << row;
                }
            }
        }
        if (beam == 0.0) continue;
        EXPECT_GE(inside, 12);  // every region has pixels
        EXPECT_GE(transition, 12);
        EXPECT_GE(outside, 100);
    }
}

// The n^2 law of radiance: tolerance a few float ULPs per Fresnel bounce.
TYPED_TEST(ReferenceAnalytic, InsideGlassSphereRadianceGrowsByIorSquared) {
    for (double ior : {1.0, 1.5, 2.4}) {
        RenderBlock block{.width = 16, .height = 16, .spp = 4, .max_depth = 64};
        wp::RenderResult result = this->render(wp::test::inside_glass_sphere(block, ior, kBackground));
        expect_uniform_image(result.image, ior * ior * kBackground, 1e-5, "ior " + std::to_string(ior));
    }
}

TYPED_TEST(ReferenceAnalytic, FloorUnderSquareLightMatchesFormFactor) {
    const glm::dvec3 albedo(0.9, 0.6, 0.3), radiance(5.0, 10.0, 20.0);
    const double half_side = 0.5, height = 1.5;
    for (int max_depth : {1, 4}) {  // bounces beyond the first only reach the light's front or escape
        for (bool hidden_light : {false, true}) {
            RenderBlock block{.width = 32, .height = 32, .spp = 32, .max_depth = max_depth};
            wp::Scene scene = wp::test::plane_under_square_light(block, albedo, radiance, half_side, height);
            if (hidden_light) wp::test::add_hidden_light_below_floor(scene, radiance);
            wp::RenderResult result = this->render(scene);
            for (int c = 0; c < 3; ++c) {
                double expected =
                    wp::test::plane_under_square_light_radiance(albedo[c], radiance[c], half_side, height);
                this->expect_channel(wp::test::channel_mean(result.image, c), expected,
                                     "max_depth " + std::to_string(max_depth) + " hidden light " +
                                         std::to_string(hidden_light) + " channel " + std::to_string(c));
            }
        }
    }
}

// Without NEE only the bounce rays that hit the light carry Le: under cosine
// sampling with probability the form factor and weight albedo; under uniform
// sampling the weight albedo * 2 cos makes up for the different probability
// (here, unlike inside the emissive sphere, a wrong weight changes the mean).
// A sample is Le albedo or 0 (the form factor is 0.12), so the estimate is
// noisy: 1024 spp bound the mean within 1.2% (cosine) and 1.7% (uniform)
// of the truth, 4.5 standard errors (at 64 spp: 4.7% and 6.7%), for about
// 1 s per precision on the loaded 2-core machine (0.04 s at 64 spp).
TYPED_TEST(ReferenceAnalytic, FloorUnderSquareLightWithoutNeeMatchesFormFactor) {
    const glm::dvec3 albedo(0.9, 0.6, 0.3), radiance(5.0, 10.0, 20.0);
    const double half_side = 0.5, height = 1.5;
    for (wp::Hemisphere hemisphere : {wp::Hemisphere::Cosine, wp::Hemisphere::Uniform}) {
        RenderBlock block{.width = 32, .height = 32, .spp = 1024, .max_depth = 2};
        wp::Scene scene = wp::test::plane_under_square_light(block, albedo, radiance, half_side, height);
        scene.render.nee = false;
        scene.render.hemisphere = hemisphere;
        wp::RenderResult result = this->render(scene);
        EXPECT_EQ(result.stats.shadow_rays, 0u);
        for (int c = 0; c < 3; ++c) {
            double expected = wp::test::plane_under_square_light_radiance(albedo[c], radiance[c], half_side, height);
            this->expect_channel(
                wp::test::channel_mean(result.image, c), expected,
                "uniform " + std::to_string(hemisphere == wp::Hemisphere::Uniform) + " channel " + std::to_string(c));
        }
    }
}

TYPED_TEST(ReferenceAnalytic, FloorUnderSphereLightMatchesSubtendedCone) {
    const glm::dvec3 albedo(0.9, 0.6, 0.3), radiance(50.0, 100.0, 200.0);
    for (double radius : {0.25, 1e-3}) {  // a small light: 1 - cos theta_max = 1.25e-7
        const double height = 2.0;
        RenderBlock block{.width = 32, .height = 32, .spp = 16, .max_depth = 2};
        glm::dvec3 scaled = radiance * (0.25 * 0.25 / (radius * radius));  // same irradiance for both sizes
        wp::RenderResult result =
            this->render(wp::test::plane_under_sphere_light(block, albedo, scaled, radius, height));
        for (int c = 0; c < 3; ++c) {
            double expected = wp::test::plane_under_sphere_light_radiance(albedo[c], scaled[c], radius, height);
            this->expect_channel(wp::test::channel_mean(result.image, c), expected,
                                 "radius " + std::to_string(radius) + " channel " + std::to_string(c));
        }
    }
}

}  // namespace
