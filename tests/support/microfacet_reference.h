// The microfacet distributions written independently of the shared code
// (kernels/shared/materials/microfacet.h), in double with std::exp and
// std::erf, and a quadrature over the microfacet normals fine where they
// crowd: the references of the microfacet and rough material tests; and
// their parameters as the shared code takes them.
#pragma once

#include <cmath>
#include <glm/geometric.hpp>
#include <glm/vec3.hpp>
#include <numbers>
#include <string>

#include "core/shared_math.h"

namespace wp::test {

struct MicrofacetParameters {
    bool beckmann;
    double alpha_u, alpha_v;
};

// The shared code's Microfacet of these parameters.
template <class Real>
typename SharedMath<Real>::Microfacet shared_microfacet(const MicrofacetParameters& m) {
    typename SharedMath<Real>::Microfacet result;
    result.distribution = m.beckmann ? WP_MICROFACET_BECKMANN : WP_MICROFACET_GGX;
    result.alpha_u = Real(m.alpha_u);
    result.alpha_v = Real(m.alpha_v);
    return result;
}

inline std::string describe(const MicrofacetParameters& m) {
    return std::string(m.beckmann ? "beckmann" : "ggx") + " alpha " + std::to_string(m.alpha_u) + ", " +
           std::to_string(m.alpha_v);
}

// D(h) per unit projected area (Walter et al. 2007, eqs. 25 and 33; the
// anisotropic forms of Heitz 2014, section 5.4), written as functions of the
// slope of h: Beckmann's is a Gaussian in the slopes, GGX's a Student-t.
inline double reference_D(const MicrofacetParameters& m, const glm::dvec3& h) {
    if (h.z <= 0.0) return 0.0;
    const double slope_x = h.x / h.z / m.alpha_u, slope_y = h.y / h.z / m.alpha_v;
    const double r2 = slope_x * slope_x + slope_y * slope_y;
    const double cos4 = h.z * h.z * h.z * h.z;
    const double slope_density =
        m.beckmann ? std::exp(-r2) / std::numbers::pi : 1.0 / (std::numbers::pi * (1.0 + r2) * (1.0 + r2));
    return slope_density / (m.alpha_u * m.alpha_v * cos4);
}

// Smith's Lambda of direction w (Heitz 2014, section 5).
inline double reference_lambda(const MicrofacetParameters& m, const glm::dvec3& w) {
    const double projected_alpha2 =
        (m.alpha_u * m.alpha_u * w.x * w.x + m.alpha_v * m.alpha_v * w.y * w.y) / (w.x * w.x + w.y * w.y + 1e-300);
    const double tan2 = (w.x * w.x + w.y * w.y) / (w.z * w.z);
    if (tan2 == 0.0) return 0.0;
    if (!m.beckmann) return 0.5 * (-1.0 + std::sqrt(1.0 + projected_alpha2 * tan2));
    const double a = 1.0 / std::sqrt(projected_alpha2 * tan2);
    return 0.5 * (std::erf(a) - 1.0) + std::exp(-a * a) / (2.0 * a * std::sqrt(std::numbers::pi));
}

inline double reference_G1(const MicrofacetParameters& m, const glm::dvec3& w, const glm::dvec3& h) {
    return glm::dot(w, h) * w.z > 0.0 ? 1.0 / (1.0 + reference_lambda(m, w)) : 0.0;
}

// The integral of f(h) over the hemisphere of normals h (z up), in
// theta = atan(alpha r), r = s / (1 - s) for s in [0, 1) and phi: the nodes
// crowd where D varies, at slopes of the order of alpha = sqrt(alpha_u
// alpha_v). Midpoint rule on `rings` x `sectors` nodes.
template <class F>
double integrate_over_normals(double alpha, const F& f, int rings = 800, int sectors = 128) {
    double sum = 0.0;
    for (int i = 0; i < rings; ++i) {
        const double s = (i + 0.5) / rings;
        const double r = s / (1.0 - s), dr_ds = 1.0 / ((1.0 - s) * (1.0 - s));
        const double theta = std::atan(alpha * r), dtheta_dr = alpha / (1.0 + alpha * alpha * r * r);
        const double weight = std::sin(theta) * dtheta_dr * dr_ds / rings * (2.0 * std::numbers::pi / sectors);
        for (int j = 0; j < sectors; ++j) {
            const double phi = (j + 0.5) * 2.0 * std::numbers::pi / sectors;
            const glm::dvec3 h(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
            sum += weight * f(h);
        }
    }
    return sum;
}

// The unit direction at cos theta and azimuth phi in the local frame.
inline glm::dvec3 local_direction(double cos_theta, double phi) {
    const double sin_theta = std::sqrt(std::max(0.0, 1.0 - cos_theta * cos_theta));
    return {sin_theta * std::cos(phi), sin_theta * std::sin(phi), cos_theta};
}

}  // namespace wp::test
