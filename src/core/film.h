// A film on the host: each pixel's RGB sums over a range of work items, kept
// exactly (kernels/shared/film_sum.h), so that films of adjacent ranges add
// up to the bits of the film of their union. Work item w is pixel w % pixels,
// sample w / pixels (docs/architecture.md, "Work, passes and determinism").
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/render.h"
#include "shared/film_sum.h"

namespace wp {

// Work items [begin, end).
struct ItemRange {
    std::uint64_t begin = 0, end = 0;
    std::uint64_t size() const { return end - begin; }
    bool operator==(const ItemRange&) const = default;
};

inline constexpr int kFilmChannels = 3;

struct Film {
    int width = 0, height = 0;
    ItemRange items;             // the work items whose samples are summed
    std::vector<film_sum> sums;  // kFilmChannels per pixel
    // Sums of the samples' squares, kFilmChannels per pixel; empty unless a
    // feature needs per-pixel variance (--target-error).
    std::vector<film_sum> squares;

    // An empty film of items [at, at): every sum zero.
    static Film empty(int width, int height, std::uint64_t at, bool with_squares);

    std::uint64_t pixel_count() const { return std::uint64_t(width) * std::uint64_t(height); }
    // How many samples of `pixel` the range holds.
    std::uint64_t samples_of(std::uint64_t pixel) const;
    // The fewest and most samples any pixel holds.
    std::uint64_t min_samples() const;
    std::uint64_t max_samples() const;

    // Adds `next`, which must start where this film ends and match its size
    // and squares (throws std::invalid_argument otherwise).
    void append(const Film& next);
    // Adds `other`'s sums and squares, whatever its range (this film's is
    // kept): the films of the interleaved slices that MPI ranks render. Same
    // size and squares, as append.
    void add_sums(const Film& other);

    // Each pixel's sums divided by its sample count (0 where it has none).
    Image image() const;
};

// A film sum as a double (correctly rounded), and a double sample as a film
// sum (the double reference's samples).
double film_sum_to_double(const film_sum& sum);
film_sum film_sum_from_double(double value);

// Pixel `pixel`'s samples among `items` of an image of `pixels` pixels.
std::uint64_t samples_of_pixel(const ItemRange& items, std::uint64_t pixels, std::uint64_t pixel);

}  // namespace wp
