#include "core/film_renderer.h"

#include <chrono>
#include <stdexcept>
#include <string>

namespace wp {

void FilmRenderer::render(const ItemRange& items, const Progress& progress) {
    if (items_.size() == 0) items_ = {items.begin, items.begin};
    if (items.begin != items_.end)
        throw std::invalid_argument("FilmRenderer::render: work items from " + std::to_string(items.begin) +
                                    ", but the film ends at " + std::to_string(items_.end));
    render_items(items, progress);
    items_.end = items.end;
}

Film FilmRenderer::film() {
    Film film = read_film(items_);
    film.round_pixels = round_pixels_;
    film.samples_before = samples_before_;
    return film;
}

void FilmRenderer::load(const Film& film) {
    load_film(film);
    items_ = film.items;
    round_pixels_ = film.round_pixels;
    samples_before_ = film.samples_before;
    use_round_pixels(round_pixels_);
}

void FilmRenderer::begin_round(std::vector<std::uint32_t> pixels) {
    Film round = film();
    round.begin_round(std::move(pixels));
    items_ = round.items;
    round_pixels_ = std::move(round.round_pixels);
    samples_before_ = std::move(round.samples_before);
    use_round_pixels(round_pixels_);
}

RenderResult render_every_item(FilmRenderer& renderer, int width, int height, int spp, const Progress& progress) {
    auto start = std::chrono::steady_clock::now();
    const std::uint64_t total = std::uint64_t(width) * std::uint64_t(height) * std::uint64_t(spp);
    progress.report(0.0);
    renderer.render({0, total}, progress);
    RenderResult result;
    result.image = renderer.film().image();
    result.stats = renderer.stats();
    result.stats.samples = total;
    result.stats.time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    renderer.finish(result.stats.time_s);
    return result;
}

}  // namespace wp
