#include "reference/reference_renderer.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <stdexcept>
#include <thread>
#include <vector>

#include "reference/path_tracer.h"

namespace wp {
namespace {

constexpr int kTileSize = 16;

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

// Each pixel's samples are summed in double, in sample order, so the value
// depends neither on threads nor on how small the contributions are.
template <class Real>
void render_tile(const reference::ReferenceScene<Real>& scene, const Tile& tile, Image& image,
                 reference::RayCounts& counts) {
    int spp = scene.render.spp;
    for (int py = tile.y0; py < tile.y1; ++py) {
        for (int px = tile.x0; px < tile.x1; ++px) {
            glm::dvec3 sum(0.0);
            for (int s = 0; s < spp; ++s) {
                sum += glm::dvec3(reference::trace_camera_sample(scene, px, py, s, counts));
            }
            glm::dvec3 mean = sum / static_cast<double>(spp);
            float* rgb = &image.rgb[3 * (static_cast<std::size_t>(py) * image.width + px)];
            rgb[0] = static_cast<float>(mean.x);
            rgb[1] = static_cast<float>(mean.y);
            rgb[2] = static_cast<float>(mean.z);
        }
    }
}

int worker_count(const ReferenceOptions& options, int tiles) {
    int threads = options.threads > 0 ? options.threads : static_cast<int>(std::thread::hardware_concurrency());
    return std::clamp(threads, 1, std::max(tiles, 1));
}

void check_settings(const Scene& scene) {
    if (scene.camera.width < 1 || scene.camera.height < 1) {
        throw std::invalid_argument("render_reference: resolution must be at least 1x1");
    }
    if (scene.render.spp < 1) throw std::invalid_argument("render_reference: spp must be >= 1");
    if (scene.render.max_depth < 0) throw std::invalid_argument("render_reference: max_depth must be >= 0");
}

template <class Real>
RenderResult render_with(const Scene& source, const ReferenceOptions& options, const Progress& progress) {
    auto start = std::chrono::steady_clock::now();
    reference::ReferenceScene<Real> scene(source);
    int width = scene.camera.width;
    int height = scene.camera.height;
    RenderResult result;
    result.image = {width, height, std::vector<float>(3 * static_cast<std::size_t>(width) * height)};

    TileGrid grid{(width + kTileSize - 1) / kTileSize, (height + kTileSize - 1) / kTileSize};
    int tile_count = grid.columns * grid.rows;
    std::atomic<int> next_tile{0};
    std::atomic<int> tiles_done{0};
    std::vector<reference::RayCounts> counts(worker_count(options, tile_count));
    progress.report(0.0);
    auto work = [&](reference::RayCounts& mine) {
        for (int t = next_tile++; t < tile_count; t = next_tile++) {
            render_tile(scene, grid.tile(t, width, height), result.image, mine);
            int done = ++tiles_done;
            progress.report(static_cast<double>(done) / tile_count);
        }
    };
    std::vector<std::thread> workers;
    for (std::size_t i = 1; i < counts.size(); ++i) workers.emplace_back(work, std::ref(counts[i]));
    work(counts[0]);
    for (std::thread& w : workers) w.join();

    RenderStats& stats = result.stats;
    stats.samples = static_cast<std::uint64_t>(width) * height * scene.render.spp;
    for (const reference::RayCounts& c : counts) {
        stats.extension_rays += c.extension;
        stats.shadow_rays += c.shadow;
        stats.add_nonfinite(c.nonfinite);
    }
    stats.time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return result;
}

}  // namespace

RenderResult render_reference(const Scene& scene, const ReferenceOptions& options, const Progress& progress) {
    check_settings(scene);
    return options.double_precision ? render_with<double>(scene, options, progress)
                                    : render_with<float>(scene, options, progress);
}

template <class Real>
glm::dvec3 trace_reference_sample(const Scene& scene, int px, int py, int sample) {
    reference::RayCounts counts;
    return glm::dvec3(reference::trace_camera_sample(reference::ReferenceScene<Real>(scene), px, py, sample, counts));
}

template glm::dvec3 trace_reference_sample<float>(const Scene&, int, int, int);
template glm::dvec3 trace_reference_sample<double>(const Scene&, int, int, int);

}  // namespace wp
