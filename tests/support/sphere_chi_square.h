// A chi-square goodness-of-fit test of a direction sampler against its own
// density over the sphere, as Mitsuba 3's mitsuba.chi2.ChiSquareTest does it:
// a histogram of the samples in cells of equal solid angle (cos theta x phi
// about a pole), the expected count of each cell from the density integrated
// over it (adaptive quadrature), the cells expected to hold fewer than 5
// samples pooled, Pearson's statistic and its p-value. Samples the sampler
// rejects (a reflection below the surface) fill one more cell, expected to
// hold the density's missing mass, and those of a delta lobe (a smooth
// coat's mirror reflection) another, expected to hold the lobe's probability
// (sphere_chi_square_with_delta).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <glm/geometric.hpp>
#include <glm/vec3.hpp>
#include <limits>
#include <numbers>
#include <optional>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "support/statistics.h"

namespace wp::test {

// Uniform numbers in [0, 1) with as many random bits as Real's significand,
// so that none rounds up to 1 in Real.
template <class Real>
class UnitRandom {
 public:
    explicit UnitRandom(std::uint64_t seed) : engine_(seed) {}
    Real operator()() {
        constexpr int bits = std::numeric_limits<Real>::digits;
        return static_cast<Real>(static_cast<double>(engine_() >> (64 - bits)) * std::ldexp(1.0, -bits));
    }

 private:
    std::mt19937_64 engine_;
};

struct SphereChiSquare {
    ChiSquare chi_square;
    double sampled_fraction = 0.0;  // of the samples the sampler accepted
    double pdf_integral = 0.0;      // the density's integral over the sphere
    std::string failure;            // samples where the density is 0, or too few cells: empty if none
    std::string describe() const {
        std::ostringstream out;
        out << "chi^2 " << chi_square.statistic << " with " << chi_square.dof << " dof, p " << chi_square.p_value
            << "; accepted " << sampled_fraction << " of the samples, density integral " << pdf_integral << ' '
            << failure;
        return out.str();
    }
};

// The cells of the histogram: `rows` bands of equal cos theta in [-1, 1] times
// `columns` sectors of phi, about the pole `pole` (a unit vector).
class SphereCells {
 public:
    SphereCells(const glm::dvec3& pole, int rows, int columns) : rows_(rows), columns_(columns) {
        n_ = pole;
        t_ = glm::normalize(glm::cross(std::fabs(n_.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0), n_));
        b_ = glm::cross(n_, t_);
    }
    int count() const { return rows_ * columns_; }
    double cell_solid_angle() const { return (2.0 / rows_) * (2.0 * std::numbers::pi / columns_); }
    int cell_of(const glm::dvec3& w) const {
        double cos_theta = std::clamp(glm::dot(w, n_), -1.0, 1.0);
        double phi = std::atan2(glm::dot(w, b_), glm::dot(w, t_));
        if (phi < 0.0) phi += 2.0 * std::numbers::pi;
        int row = std::min(static_cast<int>((cos_theta + 1.0) * 0.5 * rows_), rows_ - 1);
        int column = std::min(static_cast<int>(phi / (2.0 * std::numbers::pi) * columns_), columns_ - 1);
        return row * columns_ + column;
    }
    glm::dvec3 direction(double cos_theta, double phi) const {
        double sin_theta = std::sqrt(std::max(0.0, 1.0 - cos_theta * cos_theta));
        return sin_theta * std::cos(phi) * t_ + sin_theta * std::sin(phi) * b_ + cos_theta * n_;
    }
    // The integral of `pdf` over cell `cell`: the midpoint rule on 4 x 4
    // points, refined by quartering the cell wherever quartering changes the
    // estimate by more than `tolerance` (absolute, per cell) and by more than
    // 1e-4 of itself (a relative error that moves no count by a tenth of its
    // standard deviation at the tests' sample counts, up to 10^6 in a cell).
    double integrate(const std::function<double(const glm::dvec3&)>& pdf, int cell, double tolerance) const {
        int row = cell / columns_, column = cell % columns_;
        double c0 = -1.0 + 2.0 * row / rows_, c1 = -1.0 + 2.0 * (row + 1) / rows_;
        double p0 = 2.0 * std::numbers::pi * column / columns_, p1 = 2.0 * std::numbers::pi * (column + 1) / columns_;
        return refine(pdf, c0, c1, p0, p1, midpoint(pdf, c0, c1, p0, p1), tolerance, 0);
    }

 private:
    static constexpr int kPoints = 4;
    static constexpr int kMaxDepth = 6;
    double midpoint(const std::function<double(const glm::dvec3&)>& pdf, double c0, double c1, double p0,
                    double p1) const {
        double sum = 0.0;
        for (int i = 0; i < kPoints; ++i) {
            for (int j = 0; j < kPoints; ++j) {
                sum += pdf(direction(c0 + (c1 - c0) * (i + 0.5) / kPoints, p0 + (p1 - p0) * (j + 0.5) / kPoints));
            }
        }
        return sum * (c1 - c0) * (p1 - p0) / (kPoints * kPoints);
    }
    double refine(const std::function<double(const glm::dvec3&)>& pdf, double c0, double c1, double p0, double p1,
                  double whole, double tolerance, int depth) const {
        double cm = 0.5 * (c0 + c1), pm = 0.5 * (p0 + p1);
        double quarters[4] = {midpoint(pdf, c0, cm, p0, pm), midpoint(pdf, cm, c1, p0, pm),
                              midpoint(pdf, c0, cm, pm, p1), midpoint(pdf, cm, c1, pm, p1)};
        double sum = quarters[0] + quarters[1] + quarters[2] + quarters[3];
        if (std::fabs(sum - whole) <= std::max(tolerance, 1e-4 * std::fabs(sum)) || depth == kMaxDepth) return sum;
        return refine(pdf, c0, cm, p0, pm, quarters[0], tolerance / 4, depth + 1) +
               refine(pdf, cm, c1, p0, pm, quarters[1], tolerance / 4, depth + 1) +
               refine(pdf, c0, cm, pm, p1, quarters[2], tolerance / 4, depth + 1) +
               refine(pdf, cm, c1, pm, p1, quarters[3], tolerance / 4, depth + 1);
    }
    int rows_, columns_;
    glm::dvec3 n_, t_, b_;
};

// Pearson's chi-square of observed against expected counts, the cells
// expected to hold fewer than kMinExpected pooled (from the smallest up, the
// pool growing until it holds kMinExpected), as Mitsuba's chi2 does. A sample
// in a cell whose expected count is 0 is a failure by itself.
inline SphereChiSquare pooled_chi_square(const std::vector<std::uint64_t>& observed,
                                         const std::vector<double>& expected) {
    constexpr double kMinExpected = 5.0;
    std::vector<std::size_t> order(observed.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return expected[a] < expected[b]; });
    SphereChiSquare result;
    double pooled_expected = 0.0, pooled_observed = 0.0;
    int cells = 0;
    for (std::size_t i : order) {
        if (expected[i] == 0.0 && observed[i] > 0) {
            result.failure +=
                std::to_string(observed[i]) + " samples in cell " + std::to_string(i) + ", where the density is 0; ";
        }
        if (expected[i] < kMinExpected || (pooled_expected > 0.0 && pooled_expected < kMinExpected)) {
            pooled_expected += expected[i];
            pooled_observed += static_cast<double>(observed[i]);
            continue;
        }
        double diff = static_cast<double>(observed[i]) - expected[i];
        result.chi_square.statistic += diff * diff / expected[i];
        ++cells;
    }
    if (pooled_expected >= kMinExpected) {
        double diff = pooled_observed - pooled_expected;
        result.chi_square.statistic += diff * diff / pooled_expected;
        ++cells;
    }
    result.chi_square.dof = cells - 1;
    if (cells < 2) result.failure += "fewer than two cells; ";
    result.chi_square.p_value = chi_square_p_value(result.chi_square.statistic, std::max(result.chi_square.dof, 1));
    return result;
}

// A sampler's outcome where it may also pick a delta lobe (a mirror
// reflection, which has no density over the sphere): a direction, nothing
// (rejected), or the delta lobe.
struct SphereSample {
    std::optional<glm::dvec3> direction;
    bool delta = false;
};

// The test with a delta lobe: the delta lobe's samples fill a cell of their
// own, expected to hold `delta_probability` of them (its probability
// averaged over the sampler's random numbers, known in closed form); the
// rejected samples' cell the mass left, 1 - delta_probability - the
// density's integral.
inline SphereChiSquare sphere_chi_square_with_delta(const std::function<SphereSample()>& sample,
                                                    const std::function<double(const glm::dvec3&)>& pdf,
                                                    double delta_probability, const glm::dvec3& pole, int samples,
                                                    int rows = 32, int columns = 64) {
    SphereCells cells(pole, rows, columns);
    const int rejected = cells.count(), delta = cells.count() + 1;
    std::vector<std::uint64_t> observed(cells.count() + 2, 0);
    for (int i = 0; i < samples; ++i) {
        SphereSample s = sample();
        ++observed[s.delta ? delta : s.direction ? cells.cell_of(*s.direction) : rejected];
    }
    // Each cell's integral to a tenth of a sample: no more than 0.05 standard
    // deviations where it is expected to hold 5.
    const double tolerance = 0.1 / samples;
    std::vector<double> expected(cells.count() + 2);
    double integral = 0.0;
    for (int c = 0; c < cells.count(); ++c) {
        double probability = cells.integrate(pdf, c, tolerance);
        integral += probability;
        expected[c] = probability * samples;
    }
    expected[rejected] = std::max(0.0, 1.0 - integral - delta_probability) * samples;
    expected[delta] = delta_probability * samples;
    SphereChiSquare result = pooled_chi_square(observed, expected);
    result.pdf_integral = integral;
    result.sampled_fraction = 1.0 - static_cast<double>(observed[rejected]) / samples;
    return result;
}

// The test: `samples` draws of `sample` (a direction, or nothing where the
// sampler rejects its random numbers) against `pdf`, in rows x columns
// cells about `pole`.
inline SphereChiSquare sphere_chi_square(const std::function<std::optional<glm::dvec3>()>& sample,
                                         const std::function<double(const glm::dvec3&)>& pdf, const glm::dvec3& pole,
                                         int samples, int rows = 32, int columns = 64) {
    SphereCells cells(pole, rows, columns);
    std::vector<std::uint64_t> observed(cells.count() + 1, 0);  // the last: rejected samples
    for (int i = 0; i < samples; ++i) {
        std::optional<glm::dvec3> w = sample();
        ++observed[w ? cells.cell_of(*w) : cells.count()];
    }
    // Each cell's integral to a tenth of a sample: no more than 0.05 standard
    // deviations where it is expected to hold 5.
    const double tolerance = 0.1 / samples;
    std::vector<double> expected(cells.count() + 1);
    double integral = 0.0;
    for (int c = 0; c < cells.count(); ++c) {
        double probability = cells.integrate(pdf, c, tolerance);
        integral += probability;
        expected[c] = probability * samples;
    }
    expected[cells.count()] = std::max(0.0, 1.0 - integral) * samples;
    SphereChiSquare result = pooled_chi_square(observed, expected);
    result.pdf_integral = integral;
    result.sampled_fraction = 1.0 - static_cast<double>(observed[cells.count()]) / samples;
    return result;
}

}  // namespace wp::test
