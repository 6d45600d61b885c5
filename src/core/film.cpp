#include "core/film.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace wp {

namespace {

// Items w < x with w % pixels == pixel.
std::uint64_t items_below(std::uint64_t x, std::uint64_t pixels, std::uint64_t pixel) {
    return x / pixels + (x % pixels > pixel ? 1 : 0);
}

std::vector<film_sum> zero_sums(std::uint64_t pixels) {
    return std::vector<film_sum>(kFilmChannels * pixels, film_sum_zero());
}

}  // namespace

std::uint64_t samples_of_pixel(const ItemRange& items, std::uint64_t pixels, std::uint64_t pixel) {
    return items_below(items.end, pixels, pixel) - items_below(items.begin, pixels, pixel);
}

PhotonEstimate PhotonEstimate::start(std::uint64_t pixels, std::uint64_t photons_per_iteration) {
    PhotonEstimate estimate;
    estimate.photons_per_iteration = photons_per_iteration;
    estimate.count.assign(pixels, 0.0);
    estimate.radius.assign(pixels, 0.0);
    estimate.footprint.assign(pixels, 0.0);
    estimate.flux.assign(kFilmChannels * pixels, 0.0);
    return estimate;
}

SppmRadii sppm_radii(const PhotonEstimate& photons) {
    SppmRadii radii;
    for (std::size_t p = 0; p < photons.footprint.size(); ++p) {
        if (!(photons.footprint[p] > 0.0)) continue;
        ++radii.pixels;
        radii.mean_radius += photons.radius[p];
        radii.mean_footprint += photons.footprint[p];
        radii.radius_in_footprints += photons.radius[p] / photons.footprint[p];
    }
    if (radii.pixels > 0) {
        radii.mean_radius /= double(radii.pixels);
        radii.mean_footprint /= double(radii.pixels);
        radii.radius_in_footprints /= double(radii.pixels);
    }
    return radii;
}

Film Film::empty(int width, int height, std::uint64_t at, bool with_squares) {
    Film film;
    film.width = width;
    film.height = height;
    film.items = {at, at};
    film.sums = zero_sums(film.pixel_count());
    if (with_squares) film.squares = zero_sums(film.pixel_count());
    return film;
}

std::uint64_t Film::samples_of(std::uint64_t pixel) const {
    if (!in_round()) return samples_of_pixel(items, pixel_count(), pixel);
    const auto at = std::lower_bound(round_pixels.begin(), round_pixels.end(), std::uint32_t(pixel));
    const bool sampled = at != round_pixels.end() && *at == pixel;
    return samples_before[pixel] +
           (sampled ? samples_of_pixel(items, round_pixels.size(), std::uint64_t(at - round_pixels.begin())) : 0);
}

std::vector<std::uint64_t> Film::sample_counts() const {
    std::vector<std::uint64_t> counts(pixel_count());
    if (!in_round()) {
        for (std::uint64_t p = 0; p < counts.size(); ++p) counts[p] = samples_of_pixel(items, pixel_count(), p);
        return counts;
    }
    std::copy(samples_before.begin(), samples_before.end(), counts.begin());
    for (std::uint64_t i = 0; i < round_pixels.size(); ++i)
        counts[round_pixels[i]] += samples_of_pixel(items, round_pixels.size(), i);
    return counts;
}

// Without a round, samples_of is constant on the pixels below, between and
// above begin % P and end % P, so the extremes are among those two pixels, 0
// and P - 1.
std::uint64_t Film::min_samples() const {
    if (in_round()) {
        const std::vector<std::uint64_t> counts = sample_counts();
        return *std::min_element(counts.begin(), counts.end());
    }
    std::uint64_t least = items.size() / pixel_count() + 1;
    for (std::uint64_t p :
         {std::uint64_t(0), pixel_count() - 1, items.begin % pixel_count(), items.end % pixel_count()})
        least = std::min(least, samples_of(p));
    return least;
}

std::uint64_t Film::max_samples() const {
    if (in_round()) {
        const std::vector<std::uint64_t> counts = sample_counts();
        return *std::max_element(counts.begin(), counts.end());
    }
    std::uint64_t most = 0;
    for (std::uint64_t p :
         {std::uint64_t(0), pixel_count() - 1, items.begin % pixel_count(), items.end % pixel_count()})
        most = std::max(most, samples_of(p));
    return most;
}

void Film::append(const Film& next) {
    if (next.items.begin != items.end)
        throw std::invalid_argument("films not adjacent: one ends at work item " + std::to_string(items.end) +
                                    ", the next starts at " + std::to_string(next.items.begin));
    if (in_round() || next.in_round())
        throw std::invalid_argument("an adaptive film's pixels have their own sample counts: it cannot be added to");
    if (!photons.empty() || !next.photons.empty())
        throw std::invalid_argument("an SPPM film's iterations each need the one before: it cannot be added to");
    add_sums(next);
    items.end = next.items.end;
}

void Film::begin_round(std::vector<std::uint32_t> pixels) {
    if (pixels.empty()) throw std::invalid_argument("begin_round: a round needs pixels");
    const std::vector<std::uint64_t> counts = sample_counts();
    const std::uint64_t c = counts[pixels.front()];
    for (std::uint32_t p : pixels)
        if (p >= pixel_count() || counts[p] != c)
            throw std::invalid_argument("begin_round: pixel " + std::to_string(p) +
                                        " is outside the film or holds another sample count");
    samples_before.assign(counts.begin(), counts.end());
    round_pixels = std::move(pixels);
    items = {c * round_pixels.size(), c * round_pixels.size()};
}

void Film::add_sums(const Film& other) {
    if (other.width != width || other.height != height)
        throw std::invalid_argument("films of different sizes: " + std::to_string(width) + "x" +
                                    std::to_string(height) + " and " + std::to_string(other.width) + "x" +
                                    std::to_string(other.height));
    if (other.squares.empty() != squares.empty())
        throw std::invalid_argument("one film has second moments and the other has not");
    if (!photons.empty() || !other.photons.empty())
        throw std::invalid_argument("SPPM films cannot be summed: each iteration needs the one before");
    for (std::size_t i = 0; i < sums.size(); ++i) sums[i] = film_sum_add(sums[i], other.sums[i]);
    for (std::size_t i = 0; i < squares.size(); ++i) squares[i] = film_sum_add(squares[i], other.squares[i]);
}

Image Film::image() const {
    Image image{width, height, std::vector<float>(sums.size())};
    const std::vector<std::uint64_t> counts = sample_counts();
    for (std::uint64_t p = 0; p < pixel_count(); ++p) {
        std::uint64_t count = counts[p];
        // SPPM: every photon emitted so far stands for the flux it carries over
        // the disc of radius r (Hachisuka and Jensen 2009, eq. 8).
        const double photon_area = photons.empty() ? 0.0
                                                   : double(count) * double(photons.photons_per_iteration) *
                                                         std::numbers::pi * photons.radius[p] * photons.radius[p];
        for (int c = 0; c < kFilmChannels; ++c) {
            std::size_t i = kFilmChannels * p + c;
            double value = count == 0 ? 0.0 : film_sum_to_double(sums[i]) / double(count);
            if (photon_area > 0.0) value += photons.flux[i] / photon_area;
            image.rgb[i] = static_cast<float>(value);
        }
    }
    return image;
}

// The top 64 bits of the magnitude from its highest set bit, with every bit
// below them ORed into the lowest (a sticky bit), round once to a double.
double film_sum_to_double(const film_sum& sum) {
    const bool negative = (sum.limb[WP_FILM_LIMBS - 1] >> 63) != 0;
    const film_sum magnitude = negative ? film_sum_negate(sum) : sum;
    int top = WP_FILM_LIMBS - 1;
    while (top >= 0 && magnitude.limb[top] == 0) --top;
    if (top < 0) return 0.0;
    const int lead = 64 - film_bit_length(magnitude.limb[top]);  // leading zeros of the top limb
    std::uint64_t window = magnitude.limb[top] << lead;
    bool sticky = false;
    if (top > 0) {
        if (lead != 0) window |= magnitude.limb[top - 1] >> (64 - lead);
        sticky = (magnitude.limb[top - 1] << lead) != 0;
        for (int i = top - 2; i >= 0; --i) sticky = sticky || magnitude.limb[i] != 0;
    }
    const double value =
        std::ldexp(static_cast<double>(window | (sticky ? 1 : 0)), 64 * top - lead - WP_FILM_FRACTION_BITS);
    return negative ? -value : value;
}

film_sum film_sum_from_double(double value) {
    if (!std::isfinite(value)) return film_sum_from_scaled(1, WP_FILM_CLAMP_BITS, value < 0);
    int exponent = 0;
    const double fraction = std::frexp(std::fabs(value), &exponent);  // in [0.5, 1)
    const auto m = static_cast<film_limb>(std::ldexp(fraction, 53));
    return film_sum_from_scaled(m, exponent - 53, value < 0);
}

}  // namespace wp
