// A film on the host: each pixel's RGB sums over a range of work items, kept
// exactly (kernels/shared/film_sum.h), so that films of adjacent ranges add
// up to the bits of the film of their union. Work item w is pixel w % pixels,
// sample w / pixels (docs/architecture.md, "Work, passes and determinism").
//
// Adaptive sampling (docs/long-renders.md) renders in rounds over the pixels
// still active: in a round over n pixels, work item w is pixel
// round_pixels[w % n], sample w / n, so that a pixel's samples are the same
// samples (same random numbers) as without adaptive sampling. Such a film's
// range is the round's, and each pixel's samples before the round are kept.
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

// SPPM's progressive estimate of the light photons bring to each pixel
// (docs/architecture.md, "Photon mapping"), beside the film's sums of the
// camera passes' emission and direct light: per pixel the photon count N,
// the radius r and the flux tau (kFilmChannels), as the float backends keep
// them (doubles hold their floats exactly), and the pixel's footprint at its
// first visible point, which set its radius (sppm_first_radius,
// kernels/shared/sppm.h). A pixel that has had no visible point yet has
// radius and footprint 0 (and no photon). Empty for path tracing.
struct PhotonEstimate {
    std::uint64_t photons_per_iteration = 0;       // 0: none (path tracing)
    std::vector<double> count, radius, footprint;  // per pixel
    std::vector<double> flux;                      // kFilmChannels per pixel

    // Every pixel without a visible point yet (radius 0), no photon.
    static PhotonEstimate start(std::uint64_t pixels, std::uint64_t photons_per_iteration);
    bool empty() const { return photons_per_iteration == 0; }
    bool operator==(const PhotonEstimate&) const = default;
};

// SPPM's radii at the end of a render, over the pixels that have had a
// visible point (footprint > 0): the mean radius, the mean footprint and
// the mean of each pixel's radius over its footprint (2 at the start by
// default, WP_SPPM_FOOTPRINTS; shrinking as the photons come).
struct SppmRadii {
    std::uint64_t pixels = 0;  // with a footprint
    double mean_radius = 0.0, mean_footprint = 0.0, radius_in_footprints = 0.0;
};
SppmRadii sppm_radii(const PhotonEstimate& photons);

struct Film {
    int width = 0, height = 0;
    ItemRange items;             // the work items whose samples are summed
    std::vector<film_sum> sums;  // kFilmChannels per pixel
    // Sums of the samples' squares, kFilmChannels per pixel; empty unless a
    // feature needs per-pixel variance (--target-error).
    std::vector<film_sum> squares;
    // Adaptive sampling's round, both empty otherwise: the pixels the range's
    // work items sample (ascending), and every pixel's samples before the round.
    std::vector<std::uint32_t> round_pixels;
    std::vector<std::uint32_t> samples_before;
    // SPPM: the photons' estimate after the range's iterations (each sample
    // of a pixel is an iteration: the range is whole iterations).
    PhotonEstimate photons;

    // An empty film of items [at, at): every sum zero.
    static Film empty(int width, int height, std::uint64_t at, bool with_squares);

    std::uint64_t pixel_count() const { return std::uint64_t(width) * std::uint64_t(height); }
    bool in_round() const { return !samples_before.empty(); }
    // The pixels work items sample: round_pixels' size, or every pixel.
    std::uint64_t round_pixel_count() const { return in_round() ? round_pixels.size() : pixel_count(); }
    // How many samples `pixel` holds, and each pixel.
    std::uint64_t samples_of(std::uint64_t pixel) const;
    std::vector<std::uint64_t> sample_counts() const;
    // The fewest and most samples any pixel holds.
    std::uint64_t min_samples() const;
    std::uint64_t max_samples() const;

    // Adds `next`, which must start where this film ends and match its size
    // and squares, neither in a round nor with photons (throws
    // std::invalid_argument otherwise).
    void append(const Film& next);
    // Starts a round over `pixels` (ascending), which must all hold the same
    // number of samples c: the range becomes [c n, c n) for n pixels.
    void begin_round(std::vector<std::uint32_t> pixels);
    // Adds `other`'s sums and squares, whatever its range (this film's is
    // kept): the films of the interleaved slices that MPI ranks render. Same
    // size and squares, as append; neither with photons (an SPPM iteration
    // needs the last one's radii).
    void add_sums(const Film& other);

    // Each pixel's sums divided by its sample count (0 where it has none);
    // with photons, plus their estimate tau / (iterations x photons per
    // iteration x pi r^2).
    Image image() const;
};

// A film sum as a double (correctly rounded), and a double sample as a film
// sum (the double reference's samples).
double film_sum_to_double(const film_sum& sum);
film_sum film_sum_from_double(double value);

// Pixel `pixel`'s samples among `items` of an image of `pixels` pixels.
std::uint64_t samples_of_pixel(const ItemRange& items, std::uint64_t pixels, std::uint64_t pixel);

}  // namespace wp
