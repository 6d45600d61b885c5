#include "reference/sppm_renderer.h"

#include <algorithm>
#include <atomic>
#include <stdexcept>
#include <vector>

#include "reference/path_tracer.h"
#include "reference/photon_tracer.h"
#include "reference/reference_threads.h"

namespace wp {
namespace {

// Pixels or photons a thread takes at a time.
constexpr std::uint64_t kChunk = 1024;

// Runs work(index, thread) for every index below `count` on `threads` threads.
template <class Work>
void for_each_index(int threads, std::uint64_t count, const Work& work) {
    std::atomic<std::uint64_t> next{0};
    reference::on_threads(threads, [&](int thread) {
        for (std::uint64_t first = next.fetch_add(kChunk); first < count; first = next.fetch_add(kChunk))
            for (std::uint64_t i = first; i < std::min(first + kChunk, count); ++i) work(i, thread);
    });
}

template <class Real>
class ReferenceSppmRenderer : public FilmRenderer {
    using M = SharedMath<Real>;
    using vec3 = typename M::vec3;

 public:
    ReferenceSppmRenderer(const Scene& source, const ReferenceOptions& options)
        : scene_(source, options.intersector),
          width_(source.camera.width),
          pixels_(std::uint64_t(source.camera.width) * std::uint64_t(source.camera.height)),
          photons_(sppm_photons(source)),
          alpha_(Real(source.render.sppm.alpha)),
          radius_override_(Real(source.render.sppm.radius)),
          pixel_spread_(Real(sppm_pixel_spread(source))),
          threads_(reference::worker_count(options.threads, pixels_)),
          counts_(threads_),
          film_(Film::empty(source.camera.width, source.camera.height, 0, false)),
          visible_(pixels_),
          count_(pixels_, Real(0)),
          radius_(pixels_, Real(0)),
          footprint_(pixels_, Real(0)),
          flux_(pixels_, vec3(Real(0))),
          photon_counts_(pixels_),
          photon_flux_(pixels_ * kFilmChannels * WP_FILM_WORDS) {
        if (options.film_squares)
            throw std::invalid_argument("sppm: no sums of squares, its iterations are not independent samples");
    }

    std::uint64_t pass_items() const override { return pixels_; }

    RenderStats stats() const override { return reference::summed_stats(counts_); }

 protected:
    void render_items(const ItemRange& items, const Progress& progress) override {
        if (items.begin % pixels_ != 0 || items.end % pixels_ != 0)
            throw std::invalid_argument("sppm: work items must be whole iterations (every pixel's next sample)");
        const std::uint64_t first = items.begin / pixels_, end = items.end / pixels_;
        for (std::uint64_t iteration = first; iteration < end; ++iteration) {
            run_iteration(static_cast<std::uint32_t>(iteration));
            progress.report(double(iteration + 1 - first) / double(end - first));
        }
        film_.items.end = items.end;
    }

    Film read_film(const ItemRange& items) override {
        Film film = film_;
        film.items = items;
        film.photons = PhotonEstimate::start(pixels_, photons_);
        for (std::uint64_t p = 0; p < pixels_; ++p) {
            film.photons.count[p] = double(count_[p]);
            film.photons.radius[p] = double(radius_[p]);
            film.photons.footprint[p] = double(footprint_[p]);
            for (int c = 0; c < kFilmChannels; ++c) film.photons.flux[kFilmChannels * p + c] = double(flux_[p][c]);
        }
        return film;
    }

    void load_film(const Film& film) override {
        if (film.width != film_.width || film.height != film_.height || !film.squares.empty())
            throw std::invalid_argument("sppm: a film of another size, or with sums of squares");
        if (film.photons.photons_per_iteration != photons_)
            throw std::invalid_argument("sppm: a film without this render's photons per iteration");
        film_ = film;
        for (std::uint64_t p = 0; p < pixels_; ++p) {
            count_[p] = Real(film.photons.count[p]);
            radius_[p] = Real(film.photons.radius[p]);
            footprint_[p] = Real(film.photons.footprint[p]);
            for (int c = 0; c < kFilmChannels; ++c) flux_[p][c] = Real(film.photons.flux[kFilmChannels * p + c]);
        }
    }

    void use_round_pixels(const std::vector<std::uint32_t>& pixels) override {
        if (!pixels.empty()) throw std::invalid_argument("sppm: every iteration renders every pixel");
    }

 private:
    // The visible points listed by the cells their spheres meet (counting
    // sort into the buckets of shared/photon_grid.h): entries[starts[b] ..
    // starts[b + 1]) are bucket b's pixels.
    struct Grid {
        typename M::GridFrame frame;
        std::uint32_t buckets = 0;
        std::vector<std::uint32_t> starts, entries;
    };

    void run_iteration(std::uint32_t iteration) {
        camera_pass(iteration);
        std::fill(photon_counts_.begin(), photon_counts_.end(), 0u);
        std::fill(photon_flux_.begin(), photon_flux_.end(), film_word(0));
        if (!scene_.lights.empty() && build_grid()) photon_pass(iteration);
        update();
    }

    // Each pixel's camera sample `iteration`: its emission and direct light
    // into the film, and its visible point; the pixel's first visible point
    // sets its radius (sppm_first_radius).
    void camera_pass(std::uint32_t iteration) {
        for_each_index(threads_, pixels_, [&](std::uint64_t p, int thread) {
            visible_[p] = {};
            const int px = int(p % std::uint64_t(width_)), py = int(p / std::uint64_t(width_));
            reference::Vec3<Real> radiance =
                reference::trace_camera_sample(scene_, px, py, int(iteration), counts_[thread], &visible_[p]);
            if (visible_[p].found() && radius_[p] == Real(0)) {
                footprint_[p] = M::sppm_footprint(pixel_spread_, visible_[p].distance);
                radius_[p] = M::sppm_first_radius(radius_override_, footprint_[p]);
            }
            for (int c = 0; c < kFilmChannels; ++c) {
                film_sum& sum = film_.sums[kFilmChannels * p + c];
                sum = film_sum_add(sum, reference::film_value(radiance[c]));
            }
        });
    }

    // False when no pixel has a visible point.
    bool build_grid() {
        bool any = false;
        vec3 lowest(M::real_max);
        Real largest = 0;
        for (std::uint64_t p = 0; p < pixels_; ++p) {
            if (!visible_[p].found()) continue;
            any = true;
            lowest = glm::min(lowest, visible_[p].point);
            largest = std::max(largest, radius_[p]);
        }
        if (!any) return false;
        grid_.frame = M::grid_frame(lowest, largest);
        grid_.buckets = M::photon_grid_buckets(static_cast<std::uint32_t>(pixels_));
        grid_.starts.assign(std::size_t(grid_.buckets) + 1, 0u);
        auto each_listed_cell = [&](const auto& visit) {
            for (std::uint64_t p = 0; p < pixels_; ++p) {
                if (!visible_[p].found()) continue;
                for (std::uint32_t k = 0; k < WP_GRID_CELLS_PER_SPHERE; ++k) {
                    typename M::GridCell cell =
                        M::grid_cell_of_sphere(grid_.frame, visible_[p].point, radius_[p], grid_.buckets, k);
                    if (cell.listed) visit(cell.bucket, std::uint32_t(p));
                }
            }
        };
        each_listed_cell([&](std::uint32_t bucket, std::uint32_t) { ++grid_.starts[bucket + 1]; });
        for (std::uint32_t b = 0; b < grid_.buckets; ++b) grid_.starts[b + 1] += grid_.starts[b];
        grid_.entries.resize(grid_.starts.back());
        std::vector<std::uint32_t> cursor(grid_.starts.begin(), grid_.starts.end() - 1);
        each_listed_cell([&](std::uint32_t bucket, std::uint32_t p) { grid_.entries[cursor[bucket]++] = p; });
        return true;
    }

    // Every photon of the iteration, its deposits added to the pixels'
    // photon counts and flux sums (exact, in any order: film_words_add).
    void photon_pass(std::uint32_t iteration) {
        const auto max_depth = static_cast<std::uint32_t>(scene_.render.max_depth);
        for_each_index(threads_, photons_, [&](std::uint64_t photon, int thread) {
            reference::RayCounts& counts = counts_[thread];
            auto deposit = [&](const vec3& x, const vec3& direction, const vec3& power, std::uint32_t depth) {
                const std::uint32_t bucket = M::grid_bucket_of(grid_.frame, x, grid_.buckets);
                for (std::uint32_t e = grid_.starts[bucket]; e < grid_.starts[bucket + 1]; ++e) {
                    const std::uint32_t p = grid_.entries[e];
                    const reference::VisiblePoint<Real>& vp = visible_[p];
                    if (!M::photon_depth_counts(vp.depth, depth, max_depth) ||
                        !M::photon_within(vp.point, radius_[p], x))
                        continue;
                    const vec3 flux = M::photon_deposit(reference::visible_point_f(scene_, vp, -direction), vp.nf,
                                                        vp.ns, reference::transmits(vp.material.type), direction, power,
                                                        scene_.shading_normals);
                    std::atomic_ref<std::uint32_t>(photon_counts_[p]).fetch_add(1u);
                    for (int c = 0; c < kFilmChannels; ++c)
                        film_words_add(&photon_flux_[(kFilmChannels * p + c) * WP_FILM_WORDS],
                                       reference::film_value(flux[c]));
                    ++counts.photon_deposits;
                }
            };
            reference::trace_photon(scene_, {scene_.render.seed, iteration, std::uint32_t(photon)}, deposit, counts);
        });
    }

    // Every pixel's N, r and tau after the iteration (sppm_update).
    void update() {
        for (std::uint64_t p = 0; p < pixels_; ++p) {
            vec3 deposited;
            for (int c = 0; c < kFilmChannels; ++c)
                deposited[c] = reference::film_sum_to_real<Real>(
                    film_sum_from_words(&photon_flux_[(kFilmChannels * p + c) * WP_FILM_WORDS]));
            typename M::SppmPixel pixel{count_[p], radius_[p], flux_[p]};
            pixel = M::sppm_pixel_update(pixel, photon_counts_[p], deposited, alpha_);
            count_[p] = pixel.count;
            radius_[p] = pixel.radius;
            flux_[p] = pixel.flux;
        }
    }

    reference::ReferenceScene<Real> scene_;
    int width_;
    std::uint64_t pixels_, photons_;
    Real alpha_;
    Real radius_override_;  // render.sppm.radius (0: none)
    Real pixel_spread_;     // sppm_pixel_spread
    int threads_;
    std::vector<reference::RayCounts> counts_;  // one per thread
    Film film_;                                 // the camera passes' sums
    std::vector<reference::VisiblePoint<Real>> visible_;
    std::vector<Real> count_, radius_;          // N, r (0 before the pixel's first visible point)
    std::vector<Real> footprint_;               // at the pixel's first visible point
    std::vector<vec3> flux_;                    // tau
    std::vector<std::uint32_t> photon_counts_;  // M of the iteration
    std::vector<film_word> photon_flux_;        // Phi of the iteration, WP_FILM_WORDS per pixel and channel
    Grid grid_;
};

}  // namespace

std::unique_ptr<FilmRenderer> make_reference_sppm_renderer(const Scene& scene, const ReferenceOptions& options) {
    if (options.double_precision) return std::make_unique<ReferenceSppmRenderer<double>>(scene, options);
    return std::make_unique<ReferenceSppmRenderer<float>>(scene, options);
}

}  // namespace wp
