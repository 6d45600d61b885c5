// What every backend offers the long-render machinery (budgets, checkpoints,
// partial films): a film it keeps, to which it adds the samples of ranges of
// work items. Since film sums are exact, rendering a range in one call or in
// many, or resuming from a film read back earlier, gives the same bits.
#pragma once

#include <cstdint>
#include <vector>

#include "core/film.h"
#include "core/render.h"

namespace wp {

class FilmRenderer {
 public:
    virtual ~FilmRenderer() = default;

    // Adds the samples of `items` to the film; they must start where the
    // film's range ends, unless the film is still empty (std::invalid_argument).
    // Reports the fraction of `items` done.
    void render(const ItemRange& items, const Progress& progress);
    // The film so far.
    Film film();
    // Replaces the film (same size and squares) and its range (and round).
    void load(const Film& film);
    const ItemRange& items() const { return items_; }
    // Adaptive sampling: from now on only `pixels` (ascending, each holding
    // the same samples) receive samples (Film::begin_round); the range
    // becomes the round's.
    void begin_round(std::vector<std::uint32_t> pixels);
    // The round's pixels (empty: every pixel).
    const std::vector<std::uint32_t>& round_pixels() const { return round_pixels_; }

    // Work items per render() call that keep the backend efficient (its pass).
    virtual std::uint64_t pass_items() const = 0;
    // Rays and non-finite values so far (time and samples are the caller's).
    virtual RenderStats stats() const = 0;
    // Called once after the last render(), with the render's wall time: fills
    // the backend's report (the profile).
    virtual void finish(double /*render_seconds*/) {}

 protected:
    virtual void render_items(const ItemRange& items, const Progress& progress) = 0;
    virtual Film read_film(const ItemRange& items) = 0;
    virtual void load_film(const Film& film) = 0;
    // Work item w of the ranges rendered from now on is pixel
    // pixels[w % pixels.size()], sample w / pixels.size() (empty: every pixel).
    virtual void use_round_pixels(const std::vector<std::uint32_t>& pixels) = 0;

 private:
    ItemRange items_;
    std::vector<std::uint32_t> round_pixels_, samples_before_;  // Film's, when in a round
};

// Renders every work item of the scene (pixels x spp) into `renderer`'s
// empty film and returns the image and figures: the one-shot render.
RenderResult render_every_item(FilmRenderer& renderer, int width, int height, int spp, const Progress& progress);

}  // namespace wp
