// What the reference's renderers share: the threads they render on, their
// figures, and how a value they computed enters a film's exact sums.
#pragma once

#include <algorithm>
#include <cstddef>
#include <thread>
#include <vector>

#include "core/film.h"
#include "core/render.h"
#include "reference/path_tracer.h"

namespace wp::reference {

// `requested` threads (0: one per hardware thread), at least 1 and no more
// than the pieces of `work` there are.
inline int worker_count(int requested, std::size_t work) {
    int threads = requested > 0 ? requested : static_cast<int>(std::thread::hardware_concurrency());
    return std::clamp(threads, 1, static_cast<int>(std::max<std::size_t>(std::min<std::size_t>(work, 1 << 20), 1)));
}

// Runs work(thread) on `threads` threads, this one as thread 0, and waits for all.
template <class Work>
void on_threads(int threads, const Work& work) {
    std::vector<std::thread> workers;
    for (int i = 1; i < threads; ++i) workers.emplace_back(work, i);
    work(0);
    for (std::thread& w : workers) w.join();
}

// The figures of a render's threads (one RayCounts each), summed.
inline RenderStats summed_stats(const std::vector<RayCounts>& counts) {
    RenderStats stats;
    stats.threads = counts.size();
    for (const RayCounts& c : counts) {
        stats.extension_rays += c.extension;
        stats.shadow_rays += c.shadow;
        stats.photons += c.photons;
        stats.photon_rays += c.photon_rays;
        stats.photon_deposits += c.photon_deposits;
        stats.add_nonfinite(c.nonfinite);
    }
    return stats;
}

// A value as the film sums it: a float exactly as the kernels' film does, a
// double with its own 53 bits; and back.
inline film_sum film_value(float x) { return film_sum_from_float(x); }
inline film_sum film_value(double x) { return film_sum_from_double(x); }
inline film_sum film_square(float x) { return film_sum_from_float_squared(x); }
inline film_sum film_square(double x) { return film_sum_from_double(x * x); }
template <class Real>
Real film_sum_to_real(const film_sum& sum) {
    if constexpr (std::is_same_v<Real, float>)
        return film_sum_to_float(sum);
    else
        return film_sum_to_double(sum);
}

}  // namespace wp::reference
