#include "reference/reference_renderer.h"

#include <algorithm>
#include <atomic>
#include <numeric>
#include <stdexcept>
#include <vector>

#include "reference/path_tracer.h"
#include "reference/reference_threads.h"
#include "reference/sppm_renderer.h"

namespace wp {
namespace {

constexpr int kTileSize = 16;

// Work items per render() call: a pass over a quarter of a million samples
// keeps the threads busy and the checks between passes frequent.
constexpr std::uint64_t kPassItems = std::uint64_t(1) << 18;

struct Tile {
    int x0, y0, x1, y1;  // pixel range [x0, x1) x [y0, y1)
};

struct TileGrid {
    int columns, rows;
    Tile tile(int index, int width, int height) const {
        int x0 = (index % columns) * kTileSize;
        int y0 = (index / columns) * kTileSize;
        return {x0, y0, std::min(x0 + kTileSize, width), std::min(y0 + kTileSize, height)};
    }
};

void check_settings(const Scene& scene) {
    if (scene.camera.width < 1 || scene.camera.height < 1) {
        throw std::invalid_argument("render_reference: resolution must be at least 1x1");
    }
    if (scene.render.spp < 1) throw std::invalid_argument("render_reference: spp must be >= 1");
    if (scene.render.max_depth < 0) throw std::invalid_argument("render_reference: max_depth must be >= 0");
}

template <class Real>
class ReferenceFilmRenderer : public FilmRenderer {
 public:
    ReferenceFilmRenderer(const Scene& source, const ReferenceOptions& options)
        : scene_(source, options.intersector),
          width_(source.camera.width),
          height_(source.camera.height),
          grid_{(width_ + kTileSize - 1) / kTileSize, (height_ + kTileSize - 1) / kTileSize},
          counts_(reference::worker_count(options.threads, std::size_t(grid_.columns) * grid_.rows)),
          film_(Film::empty(width_, height_, 0, options.film_squares)) {
        use_round_pixels({});
    }

    std::uint64_t pass_items() const override { return kPassItems; }

    RenderStats stats() const override { return reference::summed_stats(counts_); }

 protected:
    // Tiles go to the threads; each pixel adds its samples among `items` in
    // sample order.
    void render_items(const ItemRange& items, const Progress& progress) override {
        const int tile_count = grid_.columns * grid_.rows;
        std::atomic<int> next_tile{0}, tiles_done{0};
        auto work = [&](reference::RayCounts& mine) {
            for (int t = next_tile++; t < tile_count; t = next_tile++) {
                render_tile(grid_.tile(t, width_, height_), items, mine);
                progress.report(static_cast<double>(++tiles_done) / tile_count);
            }
        };
        reference::on_threads(int(counts_.size()), [&](int thread) { work(counts_[thread]); });
        film_.items.end = items.end;
    }
    Film read_film(const ItemRange& items) override {
        Film film = film_;
        film.items = items;
        return film;
    }
    void load_film(const Film& film) override {
        if (film.width != width_ || film.height != height_ || film.squares.empty() != film_.squares.empty())
            throw std::invalid_argument("reference: a film of another size or other squares");
        film_ = film;
    }
    void use_round_pixels(const std::vector<std::uint32_t>& pixels) override {
        round_index_.assign(film_.pixel_count(), kNotInRound);
        if (pixels.empty()) std::iota(round_index_.begin(), round_index_.end(), 0u);
        for (std::uint32_t i = 0; i < pixels.size(); ++i) round_index_[pixels[i]] = i;
        round_pixel_count_ = pixels.empty() ? film_.pixel_count() : pixels.size();
    }

 private:
    // Work item w is the pixel at round index w % round_pixel_count_, sample w / round_pixel_count_.
    void render_tile(const Tile& tile, const ItemRange& items, reference::RayCounts& counts) {
        for (int py = tile.y0; py < tile.y1; ++py) {
            for (int px = tile.x0; px < tile.x1; ++px) {
                const std::uint64_t pixel = std::uint64_t(py) * width_ + px;
                const std::uint32_t index = round_index_[pixel];
                if (index == kNotInRound) continue;
                const std::uint64_t first = samples_of_pixel({0, items.begin}, round_pixel_count_, index);
                const std::uint64_t end = samples_of_pixel({0, items.end}, round_pixel_count_, index);
                for (std::uint64_t s = first; s < end; ++s) add_sample(pixel, trace(px, py, s, counts));
            }
        }
    }

    reference::Vec3<Real> trace(int px, int py, std::uint64_t sample, reference::RayCounts& counts) const {
        return reference::trace_camera_sample(scene_, px, py, static_cast<int>(sample), counts);
    }

    void add_sample(std::uint64_t pixel, const reference::Vec3<Real>& radiance) {
        for (int c = 0; c < kFilmChannels; ++c) {
            const std::size_t i = kFilmChannels * pixel + c;
            film_.sums[i] = film_sum_add(film_.sums[i], reference::film_value(radiance[c]));
            if (!film_.squares.empty())
                film_.squares[i] = film_sum_add(film_.squares[i], reference::film_square(radiance[c]));
        }
    }

    reference::ReferenceScene<Real> scene_;
    int width_, height_;
    TileGrid grid_;
    std::vector<reference::RayCounts> counts_;  // one per thread
    Film film_;
    static constexpr std::uint32_t kNotInRound = UINT32_MAX;
    std::vector<std::uint32_t> round_index_;  // per pixel: its index among the round's pixels
    std::uint64_t round_pixel_count_ = 0;
};

}  // namespace

Intersector fastest_reference_intersector(bool double_precision) {
    return double_precision ? Intersector::Bvh : Intersector::Embree;
}

std::unique_ptr<FilmRenderer> make_reference_renderer(const Scene& scene, const ReferenceOptions& options) {
    check_settings(scene);
    if (scene.render.integrator == Integrator::Sppm) return make_reference_sppm_renderer(scene, options);
    if (options.double_precision) return std::make_unique<ReferenceFilmRenderer<double>>(scene, options);
    return std::make_unique<ReferenceFilmRenderer<float>>(scene, options);
}

RenderResult render_reference(const Scene& scene, const ReferenceOptions& options, const Progress& progress) {
    std::unique_ptr<FilmRenderer> renderer = make_reference_renderer(scene, options);
    return render_every_item(*renderer, scene.camera.width, scene.camera.height, scene.render.spp, progress);
}

template <class Real>
glm::dvec3 trace_reference_sample(const Scene& scene, int px, int py, int sample) {
    reference::RayCounts counts;
    return glm::dvec3(reference::trace_camera_sample(reference::ReferenceScene<Real>(scene), px, py, sample, counts));
}

template glm::dvec3 trace_reference_sample<float>(const Scene&, int, int, int);
template glm::dvec3 trace_reference_sample<double>(const Scene&, int, int, int);

}  // namespace wp
