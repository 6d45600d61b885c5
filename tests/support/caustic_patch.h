// The analytic caustic (issue 22): a small diffuse patch under a wide glass
// slab, lit from above by a small square light. Every path from the light to
// the patch crosses the slab, so next-event estimation sees nothing and path
// tracing finds the light only by sampling the patch's BSDF through the
// glass; SPPM's photons find the patch through it. The patch's radiance has
// an integral over directions that the test computes itself by quadrature.
//
// World frame (y up), shifted so that the camera sits at the origin:
//   patch     the square |x|, |z| <= kPatchHalf at y = 0, facing up, albedo rho;
//   slab      glass of index `ior` between y = kSlabBottom and kSlabTop, two
//             quads of half-width kSlabHalf (wide enough that every path
//             from the light to the patch crosses both);
//   light     the square |x|, |z| <= kLightHalf at y = kLightHeight, facing down;
//   camera    at (0, kCameraHeight, kCameraHeight), below the slab, looking at
//             the patch's centre through a 0.01 degree field of view.
//
// The irradiance at a patch point x from the light through the slab is
//   E(x) = sum_k Le int cos(theta) (1 - F)^2 F^(2k) [the ray lands on the light] dw,
// F = F(theta) our unpolarised Fresnel reflectance (the same at both faces of
// a parallel slab), k the round trips inside the slab. A ray leaving x at
// zenith angle theta and azimuth phi leaves the slab parallel to itself,
// displaced: it meets the light's plane at the horizontal distance
//   D_k(theta) = (g1 + g2) tan(theta) + (2k + 1) h tan(theta_t),  sin(theta_t) = sin(theta) / n,
// g1 and g2 the air gaps below and above the slab, h its thickness. D_k
// grows with theta, so the directions that land on the light are, at each
// azimuth, those below theta_k(phi) = D_k^-1(s(phi)), s(phi) the distance
// from x to the light square's edge along phi; the integral over theta is
// smooth (Gauss-Legendre), the one over phi smooth between the corners.
// The patch's radiance is rho / pi E. Paths that scatter at the patch
// more than once (up off it, back from the slab's underside onto it) are
// left out; they need a second patch vertex and the mirror image of a patch
// of half-size 0.04 seen from 2 g1 = 0.5 away: under rho F(0) (0.08 / 0.5)^2 / pi
// = 3e-4 of the value.
//
// bench/scenes/caustic_patch.json is this scene in JSON, unshifted (the patch
// at the origin), at max_depth 8 and with a 7 degree field of view, in which
// the patch fills the image (bench/sppm_caustic.py).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <vector>

#include "core/shared_math.h"
#include "support/analytic_scenes.h"

namespace wp::test {

struct CausticPatch {
    static constexpr double kPatchHalf = 0.04;
    static constexpr double kSlabBottom = 0.25, kSlabTop = 0.35, kSlabHalf = 50.0;
    static constexpr double kLightHeight = 0.55, kLightHalf = 0.1;
    static constexpr double kCameraHeight = 0.2;
    double albedo = 0.8;
    double radiance = 10.0;
    double ior = 1.5;  // 1: no slab (the quadrature's closed-form check)
};

// The scene, with the block's render settings (max_depth 3 + 2K keeps the
// round trips k <= K, and no path of other kind but the left-out ones), seen
// from `camera` (below the slab) through a field of view of `fov_y` degrees
// about the patch's centre: by default the view above, 45 degrees from the
// patch's normal.
inline Scene caustic_patch_scene(const RenderBlock& block, const CausticPatch& c,
                                 const glm::dvec3& camera = glm::dvec3(0.0, CausticPatch::kCameraHeight,
                                                                       CausticPatch::kCameraHeight),
                                 double fov_y = 0.01) {
    Scene scene = empty_scene(block, -camera, fov_y);
    auto at = [&](double x, double y, double z) { return glm::dvec3(x, y, z) - camera; };
    const double p = CausticPatch::kPatchHalf, w = CausticPatch::kSlabHalf, a = CausticPatch::kLightHalf;
    int patch = add_material(scene, diffuse(glm::dvec3(c.albedo)));
    int crown = add_material(scene, glass(c.ior));
    int lamp = add_material(scene, emitter(glm::dvec3(c.radiance)));
    // edge1 x edge2: up for the patch and the slab's top, down for its bottom and the light.
    scene.quads.push_back({at(-p, 0, p), {2 * p, 0, 0}, {0, 0, -2 * p}, patch});
    scene.quads.push_back({at(-w, CausticPatch::kSlabBottom, -w), {2 * w, 0, 0}, {0, 0, 2 * w}, crown});
    scene.quads.push_back({at(-w, CausticPatch::kSlabTop, -w), {0, 0, 2 * w}, {2 * w, 0, 0}, crown});
    scene.quads.push_back({at(-a, CausticPatch::kLightHeight, -a), {2 * a, 0, 0}, {0, 0, 2 * a}, lamp});
    build_light_table(scene);
    return scene;
}

// Gauss-Legendre nodes and weights on [-1, 1] (Newton on the Legendre
// recurrence), for smooth integrands.
inline std::vector<std::array<double, 2>> gauss_legendre(int n) {
    std::vector<std::array<double, 2>> rule;
    for (int i = 1; i <= n; ++i) {
        double x = std::cos(std::numbers::pi * (i - 0.25) / (n + 0.5)), derivative = 0.0;
        for (int step = 0; step < 100; ++step) {
            double p0 = 1.0, p1 = x;
            for (int k = 2; k <= n; ++k) {
                double p2 = ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k;
                p0 = p1;
                p1 = p2;
            }
            derivative = n * (x * p1 - p0) / (x * x - 1.0);
            double dx = p1 / derivative;
            x -= dx;
            if (std::fabs(dx) < 1e-16) break;
        }
        rule.push_back({x, 2.0 / ((1.0 - x * x) * derivative * derivative)});
    }
    return rule;
}

// The integral of f over [lo, hi] by a 48-point Gauss-Legendre rule.
template <class F>
double integrate(const F& f, double lo, double hi) {
    static const std::vector<std::array<double, 2>> rule = gauss_legendre(48);
    double sum = 0.0;
    for (const auto& [x, w] : rule) sum += w * f(0.5 * (lo + hi) + 0.5 * (hi - lo) * x);
    return 0.5 * (hi - lo) * sum;
}

// The irradiance at the patch point (x, 0, z) over paths with k <= max_round_trips.
inline double caustic_patch_irradiance(const CausticPatch& c, double x, double z, int max_round_trips) {
    using M = SharedMath<double>;
    const double gaps = CausticPatch::kSlabBottom + (CausticPatch::kLightHeight - CausticPatch::kSlabTop);
    const double h = CausticPatch::kSlabTop - CausticPatch::kSlabBottom, n = c.ior;
    const double a = CausticPatch::kLightHalf, pi = std::numbers::pi;
    auto displacement = [&](double theta, int k) {
        double sin_t = std::sin(theta) / n;
        return gaps * std::tan(theta) + (2 * k + 1) * h * sin_t / std::sqrt(1.0 - sin_t * sin_t);
    };
    // s(phi): from (x, z) along (cos phi, sin phi) to the square's edge.
    auto edge_distance = [&](double phi) {
        double dx = std::cos(phi), dz = std::sin(phi);
        double sx = dx > 0 ? (a - x) / dx : dx < 0 ? (-a - x) / dx : INFINITY;
        double sz = dz > 0 ? (a - z) / dz : dz < 0 ? (-a - z) / dz : INFINITY;
        return std::min(sx, sz);
    };
    // Azimuths of the corners: s(phi) is smooth between them.
    std::vector<double> cuts{0.0, 2.0 * pi};
    for (double cx : {-a, a})
        for (double cz : {-a, a}) {
            double phi = std::atan2(cz - z, cx - x);
            cuts.push_back(phi < 0 ? phi + 2.0 * pi : phi);
        }
    std::sort(cuts.begin(), cuts.end());
    double total = 0.0;
    for (int k = 0; k <= max_round_trips; ++k) {
        auto theta_max = [&](double phi) {  // D_k(theta) = s(phi), by bisection
            double lo = 0.0, hi = pi / 2 - 1e-12, target = edge_distance(phi);
            for (int i = 0; i < 200; ++i) {
                double mid = 0.5 * (lo + hi);
                (displacement(mid, k) < target ? lo : hi) = mid;
            }
            return 0.5 * (lo + hi);
        };
        auto transmitted = [&](double theta) {
            double f = M::fresnel_dielectric(std::cos(theta), n);
            return std::cos(theta) * std::sin(theta) * (1 - f) * (1 - f) * std::pow(f, 2 * k);
        };
        for (std::size_t i = 0; i + 1 < cuts.size(); ++i)
            total += integrate([&](double phi) { return integrate(transmitted, 0.0, theta_max(phi)); }, cuts[i],
                               cuts[i + 1]);
    }
    return c.radiance * total;
}

// The patch's radiance at (x, 0, z), rho / pi E.
inline double caustic_patch_radiance(const CausticPatch& c, double x, double z, int max_round_trips) {
    return c.albedo / std::numbers::pi * caustic_patch_irradiance(c, x, z, max_round_trips);
}

// The mean radiance over the square |x|, |z| <= half of the patch: what a
// camera looking straight down at it, its view covering that square, sees
// in the image's mean (a plane parallel to the film maps onto it affinely,
// so pixels jittered uniformly sample the square uniformly). The radiance
// is smooth over the patch and even in x and z (the light is centred over
// it): a 6-point Gauss-Legendre rule on [0, half] per axis.
inline double caustic_patch_square_mean(const CausticPatch& c, double half, int max_round_trips) {
    static const std::vector<std::array<double, 2>> rule = gauss_legendre(6);
    double sum = 0.0;
    for (const auto& [u, wu] : rule)
        for (const auto& [v, wv] : rule)
            sum += wu * wv * caustic_patch_radiance(c, 0.5 * half * (1.0 + u), 0.5 * half * (1.0 + v), max_round_trips);
    return sum / 4.0;  // the weights sum to 2 per axis
}

}  // namespace wp::test
