// Adaptive sampling (--adaptive THRESHOLD, docs/long-renders.md, "Adaptive
// sampling"), in the manner of Cycles' noise threshold: every pixel gets a
// minimum number of samples, then at the error checks' sample counts
// (next_error_check) the pixels whose estimated error is at most the
// threshold, and whose neighbours' is too, stop receiving samples. Every
// decision is made from the film at a whole sample count of the pixels still
// active, so it depends on the scene, settings and seed alone.
#pragma once

#include <cstdint>
#include <vector>

#include "core/film.h"

namespace wp {

struct AdaptiveSampling {
    double threshold = 0.0;     // 0: off
    std::uint64_t min_spp = 0;  // no pixel stops before this many samples
    bool on() const { return threshold > 0.0; }
};

// The minimum samples of a render of `spp`: max(8, spp / 16).
std::uint64_t adaptive_min_spp(std::uint64_t spp);

// The floor that keeps dark pixels' relative error finite (Cycles' 0.0001).
inline constexpr double kAdaptiveDarkFloor = 1e-4;

// A pixel's estimated error from its own n >= 2 samples: with channel c's
// sum S_c and sum of squares Q_c, s_c^2 = (Q_c - S_c^2 / n) / (n - 1),
//   error = sqrt(mean over c of s_c^2 / n) / (0.0001 + sqrt(mean over c of S_c / n)),
// the root-mean-square standard error of its channel means over the square
// root of its mean (Cycles' form: relative for bright pixels, less strict
// for dark ones, finite for black ones). The film must keep squares.
double pixel_error(const Film& film, std::uint64_t pixel, std::uint64_t n);

// The pixels of the round after `film`'s (ascending): those of its round
// (every pixel outside one) whose error is above `threshold`, and their eight
// neighbours among its round's pixels (dilation, as Cycles does: a pixel
// stops only when its whole neighbourhood has). Every pixel of the round
// must hold the same number of samples.
std::vector<std::uint32_t> pixels_still_active(const Film& film, double threshold);

}  // namespace wp
