#include "longrun/error_estimate.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace wp {

// Walked from the first check, so that a render resumed between two checks
// (at 20 spp: the next is 22, not 25) keeps the uninterrupted render's.
std::uint64_t next_error_check(std::uint64_t spp) {
    std::uint64_t check = kFirstErrorCheckSpp;
    while (check <= spp) check += std::max<std::uint64_t>(1, check / 4);
    return check;
}

double relative_standard_error(const Film& film) {
    const std::vector<std::uint64_t> counts = film.sample_counts();
    if (film.squares.empty() || *std::min_element(counts.begin(), counts.end()) < 2)
        throw std::invalid_argument("relative_standard_error: needs squares and n >= 2 samples per pixel");
    double variance_of_means = 0.0, means = 0.0;
    for (std::size_t i = 0; i < film.sums.size(); ++i) {
        const std::uint64_t n = counts[i / kFilmChannels];
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
