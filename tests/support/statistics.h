// Statistics for the Monte Carlo tests: chi-square goodness of fit with an
// exact p-value, and running means with their standard errors.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <vector>

namespace wp::test {

// Regularised upper incomplete gamma Q(a, x) (Numerical Recipes, ch. 6.2):
// the series below a + 1, the continued fraction (modified Lentz) above.
inline double gamma_q(double a, double x) {
    if (x <= 0.0) return 1.0;
    double log_prefactor = -x + a * std::log(x) - std::lgamma(a);
    if (x < a + 1.0) {
        double term = 1.0 / a, sum = term;
        for (int n = 1; n < 10000 && std::fabs(term) > std::fabs(sum) * 1e-16; ++n) {
            term *= x / (a + n);
            sum += term;
        }
        return 1.0 - sum * std::exp(log_prefactor);
    }
    const double tiny = std::numeric_limits<double>::min() / std::numeric_limits<double>::epsilon();
    double b = x + 1.0 - a, c = 1.0 / tiny, d = 1.0 / b, h = d;
    for (int i = 1; i < 10000; ++i) {
        double an = -i * (i - a);
        b += 2.0;
        d = an * d + b;
        if (std::fabs(d) < tiny) d = tiny;
        c = b + an / c;
        if (std::fabs(c) < tiny) c = tiny;
        d = 1.0 / d;
        double delta = d * c;
        h *= delta;
        if (std::fabs(delta - 1.0) < 1e-16) break;
    }
    return std::exp(log_prefactor) * h;
}

// Probability that a chi-square variable with `dof` degrees of freedom
// exceeds `statistic`.
inline double chi_square_p_value(double statistic, int dof) { return gamma_q(0.5 * dof, 0.5 * statistic); }

struct ChiSquare {
    double statistic = 0.0;
    int dof = 0;
    double p_value = 1.0;
};

// Pearson's test of observed bin counts against bin probabilities that sum
// to 1. Every expected count should be at least ~5 for the chi-square law to
// hold; the tests size their bins for hundreds.
inline ChiSquare chi_square_test(const std::vector<std::uint64_t>& observed, const std::vector<double>& probability) {
    if (observed.size() != probability.size() || observed.size() < 2) {
        throw std::invalid_argument("chi_square_test: need matching bins, at least two");
    }
    double total = 0.0;
    for (std::uint64_t o : observed) total += static_cast<double>(o);
    ChiSquare result;
    for (std::size_t i = 0; i < observed.size(); ++i) {
        double expected = total * probability[i];
        double diff = static_cast<double>(observed[i]) - expected;
        result.statistic += diff * diff / expected;
    }
    result.dof = static_cast<int>(observed.size()) - 1;
    result.p_value = chi_square_p_value(result.statistic, result.dof);
    return result;
}

// Counts of samples over a grid of equal-probability bins in [0,1)^2.
class Histogram2D {
 public:
    Histogram2D(int bins_x, int bins_y) : bins_x_(bins_x), bins_y_(bins_y), counts_(bins_x * bins_y, 0) {}
    // Coordinates outside [0, 1] count as a test failure through out_of_range().
    void add(double x, double y) {
        if (!(x >= 0.0 && x <= 1.0 && y >= 0.0 && y <= 1.0)) {
            ++out_of_range_;
            return;
        }
        int i = std::min(static_cast<int>(x * bins_x_), bins_x_ - 1);
        int j = std::min(static_cast<int>(y * bins_y_), bins_y_ - 1);
        ++counts_[j * bins_x_ + i];
    }
    std::uint64_t out_of_range() const { return out_of_range_; }
    ChiSquare uniformity() const {
        return chi_square_test(counts_, std::vector<double>(counts_.size(), 1.0 / static_cast<double>(counts_.size())));
    }

 private:
    int bins_x_, bins_y_;
    std::vector<std::uint64_t> counts_;
    std::uint64_t out_of_range_ = 0;
};

// Mean and standard error of independent samples (Welford's update).
class RunningMean {
 public:
    void add(double x) {
        ++n_;
        double delta = x - mean_;
        mean_ += delta / static_cast<double>(n_);
        m2_ += delta * (x - mean_);
    }
    double mean() const { return mean_; }
    double variance() const { return n_ > 1 ? m2_ / static_cast<double>(n_ - 1) : 0.0; }  // of one value
    double standard_error() const {
        return n_ > 1 ? std::sqrt(m2_ / static_cast<double>(n_ - 1) / static_cast<double>(n_)) : 0.0;
    }
    std::uint64_t count() const { return n_; }

 private:
    std::uint64_t n_ = 0;
    double mean_ = 0.0, m2_ = 0.0;
};

// Significance level of every chi-square test: a correct sampler fails one
// such test with probability 1e-3. The seeds are fixed, so a passing test
// passes on every run; the level bounds how likely a correct routine is to
// have drawn a failing seed.
inline constexpr double kChiSquareAlpha = 1e-3;

// Mean tests accept |mean - expected| <= 4.5 standard errors: for a normal
// estimate that rejects a correct result with probability 6.8e-6 per
// comparison.
inline constexpr double kSigmaTolerance = 4.5;

}  // namespace wp::test
