#include "longrun/adaptive.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

namespace wp {

std::uint64_t adaptive_min_spp(std::uint64_t spp) { return std::max<std::uint64_t>(8, spp / 16); }

double pixel_error(const Film& film, std::uint64_t pixel, std::uint64_t n) {
    double variance_of_means = 0.0, mean = 0.0;
    for (int c = 0; c < kFilmChannels; ++c) {
        const std::size_t i = kFilmChannels * pixel + c;
        const double sum = film_sum_to_double(film.sums[i]), squares = film_sum_to_double(film.squares[i]);
        variance_of_means += std::max(0.0, (squares - sum * sum / double(n)) / double(n - 1)) / double(n);
        mean += sum / double(n);
    }
    return std::sqrt(variance_of_means / kFilmChannels) /
           (kAdaptiveDarkFloor + std::sqrt(std::max(0.0, mean / kFilmChannels)));
}

std::vector<std::uint32_t> pixels_still_active(const Film& film, double threshold) {
    if (film.squares.empty()) throw std::invalid_argument("pixels_still_active: the film keeps no squares");
    std::vector<std::uint32_t> round = film.round_pixels;
    if (!film.in_round()) {
        round.resize(film.pixel_count());
        std::iota(round.begin(), round.end(), 0u);
    }
    const std::uint64_t n = film.samples_of(round.front());
    if (n < 2) throw std::invalid_argument("pixels_still_active: needs 2 samples or more");
    // 0: not in the round; 1: in it, converged; 2: in it, not converged.
    std::vector<std::uint8_t> state(film.pixel_count(), 0);
    for (std::uint32_t p : round) state[p] = pixel_error(film, p, n) > threshold ? 2 : 1;
    std::vector<std::uint32_t> active;
    for (std::uint32_t p : round) {
        const int x = int(p % std::uint32_t(film.width)), y = int(p / std::uint32_t(film.width));
        bool noisy = false;
        for (int dy = -1; dy <= 1 && !noisy; ++dy)
            for (int dx = -1; dx <= 1 && !noisy; ++dx) {
                const int nx = x + dx, ny = y + dy;
                noisy = nx >= 0 && ny >= 0 && nx < film.width && ny < film.height &&
                        state[std::size_t(ny) * film.width + nx] == 2;
            }
        if (noisy) active.push_back(p);
    }
    return active;
}

}  // namespace wp
