#include "longrun/error_estimate.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace wp {

std::uint64_t next_error_check(std::uint64_t spp) {
    if (spp < kFirstErrorCheckSpp) return kFirstErrorCheckSpp;
    return spp + std::max<std::uint64_t>(1, spp / 4);
}

double relative_standard_error(const Film& film) {
    const std::uint64_t n = film.min_samples();
    if (film.squares.empty() || n < 2 || film.max_samples() != n)
        throw std::invalid_argument("relative_standard_error: needs squares and the same n >= 2 samples per pixel");
    double variance_of_means = 0.0, means = 0.0;
    for (std::size_t i = 0; i < film.sums.size(); ++i) {
        const double sum = film_sum_to_double(film.sums[i]), squares = film_sum_to_double(film.squares[i]);
        const double sample_variance = std::max(0.0, (squares - sum * sum / double(n)) / double(n - 1));
        variance_of_means += sample_variance / double(n);
        means += sum / double(n);
    }
    if (means <= 0.0) return 0.0;
    const double count = double(film.sums.size());
    return std::sqrt(variance_of_means / count) / (means / count);
}

}  // namespace wp
