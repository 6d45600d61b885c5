// The stopping rule of --target-error: an estimate of the image's relative
// standard error from each pixel's sample variance (docs/long-renders.md,
// "Target error"), checked only at whole samples per pixel, on a schedule
// that depends on nothing but the sample count, so that every backend,
// device, lane count and wavefront size stops at the same sample.
#pragma once

#include <cstdint>

#include "core/film.h"

namespace wp {

// The fewest samples per pixel the estimate is made from.
inline constexpr std::uint64_t kFirstErrorCheckSpp = 4;

// The first sample count per pixel after `spp` at which the error is
// estimated: 4, 5, 6, 7, 8, 10, 12, 15, 18, ... (each about a quarter more
// than the last, whatever `spp` is: after 20, 22).
std::uint64_t next_error_check(std::uint64_t spp);

// sqrt(mean over pixels and channels of s^2 / n) / (mean over pixels and
// channels of the pixel means), where a pixel channel's n samples have sum
// S and sum of squares Q, s^2 = (Q - S^2 / n) / (n - 1). 0 for a black image.
// The film must keep squares and give every pixel n >= 2 samples (its own
// n with adaptive sampling; std::invalid_argument otherwise).
double relative_standard_error(const Film& film);

}  // namespace wp
