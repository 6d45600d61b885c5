// SPPM's photon emission against the density it claims (issue 22): the
// reference's emit_photon (src/reference/photon_tracer.h), which calls the
// shared emit_photon of kernels/shared/photons.h that kernels/emit_photons.cl
// calls too, over five lights of unequal power, shape and colour: a sphere, a
// small bright quad, a sheared, tilted two-sided quad, a large dim quad and a
// box-shaped mesh light whose faces differ in area. The photons are read back
// from what emit_photon returns alone (origin, direction, flux): the light is
// the one the origin lies on, the side the one the direction leaves.
//
// Checks (Pearson's chi-square, support/statistics.h, dof = bins - 1):
//  (a) which light: 5 bins, expected in proportion to power, pi L A sides
//      (L the Rec. 709 luminance of the radiance, as build_light_table
//      weighs it), dof 4;
//  (b) where on each light, uniform by area: a quad's (s, t) on 8x8 bins, the
//      sphere's z and phi on 8x8 equal-area bins, the box's six faces x 3x3
//      bins each in proportion to the face's area; dof 63, 63, 63, 63, 53;
//  (c) the direction about the normal of the side it leaves, cosine-
//      distributed: 8x8 equal-probability bins in sin^2(theta) and phi, per
//      light and, for the two-sided quad, per side; 6 tests of dof 63;
//  (d) the two-sided quad's side: 2 bins of 1/2, dof 1;
//  (e) the flux: its mean over the photons equals the scene's emitted power
//      sum L pi A sides per channel, within the standard error of the
//      photons' own sample variance (normal, two-sided; 3 channels).
// Sixteen tests in all, each rejected at p < kWholeTestAlpha / 16
// (Bonferroni): a correct emitter fails the whole test with probability at
// most 1e-3 (the seed is fixed, so every run draws the same photons). Every
// photon must also leave a one-sided light from its front.
//
// Cost: 2^20 photons, about 0.15 s (reference, float).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <glm/geometric.hpp>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include "reference/photon_tracer.h"
#include "support/meshes.h"
#include "support/statistics.h"

namespace wp {
namespace {

using test::ChiSquare;
using test::Histogram2D;
using test::RunningMean;
using Real = float;  // as the kernels
using M = SharedMath<Real>;

constexpr std::uint32_t kPhotons = 1u << 20, kSeed = 7;
constexpr int kChecks = 16;
constexpr double kWholeTestAlpha = 1e-3, kCheckAlpha = kWholeTestAlpha / kChecks;
constexpr int kBins = 8;                   // per axis of every 2D histogram
constexpr double kSpacing = 10.0;          // light k lies within kSpacing / 2 of x = k kSpacing
const glm::dvec3 kBoxSize{0.5, 1.0, 1.5};  // the mesh light: an axis-aligned box of this size

double luminance(const glm::dvec3& c) { return 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z; }

// The box's faces are numbered 2 axis + (1 at the far side).
double box_face_area(int face) {
    const int axis = face / 2;
    return kBoxSize[(axis + 1) % 3] * kBoxSize[(axis + 2) % 3];
}

double box_area() {
    double area = 0.0;
    for (int face = 0; face < 6; ++face) area += box_face_area(face);
    return area;
}

enum class LightShape { Sphere, Quad, Box };

// A light as the test knows it, independently of the scene's light table.
struct TestLight {
    std::string name;
    LightShape shape;
    glm::dvec3 origin;        // the sphere's centre, the quad's corner, the box's lowest corner
    glm::dvec3 edge1, edge2;  // a quad's
    double radius = 0.0;      // the sphere's
    glm::dvec3 radiance;
    bool two_sided = false;

    double area() const {
        if (shape == LightShape::Sphere) return 4.0 * std::numbers::pi * radius * radius;
        if (shape == LightShape::Quad) return glm::length(glm::cross(edge1, edge2));
        return box_area();
    }
    glm::dvec3 power() const { return radiance * std::numbers::pi * area() * (two_sided ? 2.0 : 1.0); }
};

std::vector<TestLight> test_lights() {
    const glm::dvec3 none{0.0};
    return {
        {"sphere", LightShape::Sphere, {0.0, 1.0, 0.0}, none, none, 0.5, {4.0, 2.0, 1.0}},
        {"small bright quad",
         LightShape::Quad,
         {kSpacing, 0.0, 0.0},
         {0.5, 0.0, 0.0},
         {0.0, 0.0, -0.25},
         0.0,
         {20.0, 30.0, 10.0}},
        {"two-sided sheared quad",
         LightShape::Quad,
         {2 * kSpacing, 0.0, 0.0},
         {1.0, 0.5, 0.0},
         {0.3, 0.2, 1.2},
         0.0,
         {1.0, 2.0, 6.0},
         true},
        {"large dim quad",
         LightShape::Quad,
         {3 * kSpacing, 0.0, 0.0},
         {0.0, 0.0, 3.0},
         {2.0, 0.0, 0.0},
         0.0,
         {0.5, 0.4, 0.3}},
        {"box mesh", LightShape::Box, {4 * kSpacing, 0.0, 0.0}, none, none, 0.0, {2.0, 3.0, 1.0}},
    };
}

Scene emission_scene(const std::vector<TestLight>& lights) {
    Scene scene;
    scene.camera.width = scene.camera.height = 1;
    for (const TestLight& light : lights) {
        const int material = static_cast<int>(scene.materials.size());
        scene.materials.push_back({.name = light.name,
                                   .type = MaterialType::Emitter,
                                   .emission = light.radiance,
                                   .two_sided = light.two_sided});
        if (light.shape == LightShape::Sphere) scene.spheres.push_back({light.origin, light.radius, material});
        if (light.shape == LightShape::Quad) scene.quads.push_back({light.origin, light.edge1, light.edge2, material});
        if (light.shape == LightShape::Box) {
            Mesh box = test::unit_cube(material);
            for (glm::dvec3& p : box.positions) p = light.origin + p * kBoxSize;
            scene.meshes.push_back(box);
        }
    }
    build_light_table(scene);
    return scene;
}

// Where a photon left its light: coordinates in [0, 1]^2 uniform by area on
// the light (or on the box's face `face`), and the unit normal of the
// surface there (outward; a quad's edge1 x edge2).
struct LightPosition {
    double s, t;
    glm::dvec3 normal;
    int face = 0;  // the box's
};

LightPosition position_on(const TestLight& light, const glm::dvec3& p) {
    const double two_pi = 2.0 * std::numbers::pi;
    if (light.shape == LightShape::Sphere) {
        const glm::dvec3 n = glm::normalize(p - light.origin);
        // Archimedes: z is uniform on [-1, 1] for points uniform on the sphere.
        return {0.5 * (n.z + 1.0), std::atan2(n.y, n.x) / two_pi + 0.5, n};
    }
    if (light.shape == LightShape::Quad) {
        // p - corner = s edge1 + t edge2 (+ the offset along the normal): the
        // normal equations of the 2x2 least-squares problem.
        const glm::dvec3 d = p - light.origin;
        const double a = glm::dot(light.edge1, light.edge1), b = glm::dot(light.edge1, light.edge2),
                     c = glm::dot(light.edge2, light.edge2);
        const double x = glm::dot(d, light.edge1), y = glm::dot(d, light.edge2), det = a * c - b * b;
        return {(c * x - b * y) / det, (a * y - b * x) / det, glm::normalize(glm::cross(light.edge1, light.edge2))};
    }
    // The box: the photon starts a little outside the face it left
    // (offset_ray_origin moves it along the normal by more than the point's
    // rounding error), so the face is the one it lies furthest outside of;
    // the nearest face plane would misread points near an edge.
    const glm::dvec3 q = (p - light.origin) / kBoxSize;
    int face = 0;
    double furthest = -INFINITY;
    for (int axis = 0; axis < 3; ++axis)
        for (int far = 0; far < 2; ++far) {
            const double outside = (far ? q[axis] - 1.0 : -q[axis]) * kBoxSize[axis];
            if (outside > furthest) furthest = outside, face = 2 * axis + far;
        }
    const int axis = face / 2;
    glm::dvec3 normal{0.0};
    normal[axis] = face % 2 ? 1.0 : -1.0;
    return {q[(axis + 1) % 3], q[(axis + 2) % 3], normal, face};
}

// (sin^2 theta, phi / 2 pi) of `direction` about the unit `normal`: both
// uniform on [0, 1] for a cosine-distributed direction, since the share of
// cos(theta) / pi within theta of the normal is sin^2(theta).
std::pair<double, double> cosine_coordinates(const glm::dvec3& direction, const glm::dvec3& normal) {
    const glm::dvec3 helper = std::fabs(normal.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
    const glm::dvec3 tangent = glm::normalize(glm::cross(helper, normal)), bitangent = glm::cross(normal, tangent);
    const double cos_theta = glm::dot(direction, normal);
    const double phi = std::atan2(glm::dot(direction, bitangent), glm::dot(direction, tangent));
    return {1.0 - cos_theta * cos_theta, phi / (2.0 * std::numbers::pi) + 0.5};
}

bool passes(const char* what, const ChiSquare& chi) {
    std::printf("[figure] photon emission, %s: chi-square %.1f, dof %d, p %.3g\n", what, chi.statistic, chi.dof,
                chi.p_value);
    return chi.p_value >= kCheckAlpha;
}

TEST(PhotonEmission, FollowsPowerAreaCosineAndSideAndCarriesTheEmittedPower) {
    const std::vector<TestLight> lights = test_lights();
    const Scene scene = emission_scene(lights);
    const reference::ReferenceScene<Real> reference(scene);

    std::vector<std::uint64_t> chosen(lights.size(), 0), box_bins(6 * 9, 0), sides(2, 0);
    std::vector<Histogram2D> positions(lights.size(), Histogram2D(kBins, kBins));
    // Per light its front's directions; the two-sided quad's back's last.
    std::vector<Histogram2D> directions(lights.size() + 1, Histogram2D(kBins, kBins));
    std::array<RunningMean, 3> flux;
    std::uint64_t behind_one_sided = 0, outside = 0;
    for (std::uint32_t i = 0; i < kPhotons; ++i) {
        const M::EmittedPhoton photon = reference::emit_photon(reference, reference::PhotonRng<Real>{kSeed, 0, i});
        for (int c = 0; c < 3; ++c) flux[c].add(photon.flux[c]);
        const glm::dvec3 origin(photon.origin), direction(photon.direction);
        const long k = std::lround(origin.x / kSpacing);  // the light the photon left
        if (k < 0 || k >= static_cast<long>(lights.size())) {
            ++outside;
            continue;
        }
        const TestLight& light = lights[k];
        ++chosen[k];
        const LightPosition at = position_on(light, origin);
        if (light.shape == LightShape::Box) {
            const bool on_face = at.s >= 0 && at.s <= 1 && at.t >= 0 && at.t <= 1;
            const int s = std::min(static_cast<int>(at.s * 3), 2), t = std::min(static_cast<int>(at.t * 3), 2);
            if (on_face) ++box_bins[at.face * 9 + t * 3 + s];
            outside += !on_face;
        } else {
            positions[k].add(at.s, at.t);
        }
        const bool back = glm::dot(direction, at.normal) < 0.0;
        if (back && !light.two_sided) ++behind_one_sided;
        if (light.two_sided) ++sides[back];
        const auto [sin2, phi] = cosine_coordinates(direction, back ? -at.normal : at.normal);
        directions[back ? lights.size() : k].add(sin2, phi);
    }

    glm::dvec3 total_power{0.0};
    for (const TestLight& light : lights) total_power += light.power();
    std::vector<double> selection;
    for (const TestLight& light : lights) selection.push_back(luminance(light.power()) / luminance(total_power));
    std::vector<double> box_probability;
    for (int face = 0; face < 6; ++face)
        for (int bin = 0; bin < 9; ++bin) box_probability.push_back(box_face_area(face) / box_area() / 9.0);

    EXPECT_EQ(outside, 0u) << "photons that left no light, or from outside its surface";
    EXPECT_EQ(behind_one_sided, 0u) << "photons that left a one-sided light from its back";
    EXPECT_TRUE(passes("(a) light chosen by power", test::chi_square_test(chosen, selection)));
    for (std::size_t k = 0; k < lights.size(); ++k) {
        const std::string name = lights[k].name;
        if (lights[k].shape == LightShape::Box) {
            EXPECT_TRUE(passes("(b) box mesh: face and 3x3 bins", test::chi_square_test(box_bins, box_probability)));
        } else {
            EXPECT_EQ(positions[k].out_of_range(), 0u) << name;
            EXPECT_TRUE(passes(("(b) " + name + ": position").c_str(), positions[k].uniformity())) << name;
        }
        EXPECT_TRUE(passes(("(c) " + name + (lights[k].two_sided ? ", front" : "") + ": direction").c_str(),
                           directions[k].uniformity()))
            << name;
    }
    EXPECT_TRUE(passes("(c) two-sided sheared quad, back: direction", directions[lights.size()].uniformity()));
    EXPECT_TRUE(passes("(d) two-sided sheared quad: side", test::chi_square_test(sides, {0.5, 0.5})));
    for (int c = 0; c < 3; ++c) {
        const double z = (flux[c].mean() - total_power[c]) / flux[c].standard_error();
        const double p = std::erfc(std::fabs(z) / std::numbers::sqrt2);
        std::printf("[figure] photon emission, (e) flux, channel %c: mean %.4f +- %.4f, emitted power %.4f, z %+.2f\n",
                    "RGB"[c], flux[c].mean(), flux[c].standard_error(), total_power[c], z);
        EXPECT_GE(p, kCheckAlpha) << "channel " << c << ": z " << z;
    }
}

}  // namespace
}  // namespace wp
