// Shared by the extreme-case tests: one render call for either backend (the
// reference in double, the wavefront in float, so that every comparison
// between them measures float against double), region statistics, the
// room transformed before loading, and the figure lines that
// docs/robustness.md quotes.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "reference/reference_renderer.h"
#include "scene/scene.h"
#include "support/image_statistics.h"
#include "support/statistics.h"
#include "wavefront/wavefront_renderer.h"
#include "wavefront/wavefront_test_support.h"

namespace wp::test {

enum class Backend { Reference, Wavefront };

inline std::string backend_name(Backend backend) {
    return backend == Backend::Reference ? "reference(double)" : "wavefront(float)";
}

struct BackendNames {
    std::string operator()(const ::testing::TestParamInfo<Backend>& info) const {
        return info.param == Backend::Reference ? "Reference" : "Wavefront";
    }
};

inline RenderResult render_on(Backend backend, const Scene& scene) {
    if (backend == Backend::Reference) return render_reference(scene, ReferenceOptions{0, true});
    use_build_tree_program_cache();
    return render_wavefront(scene, {}, {});
}

// One measured figure, printed for docs/robustness.md and kept in the test's XML report.
inline void report_figure(const std::string& name, Backend backend, const std::string& text) {
    std::printf("[figure] %s | %s | %s\n", name.c_str(), backend_name(backend).c_str(), text.c_str());
    ::testing::Test::RecordProperty(name, text);
}

inline std::string format(const char* pattern, double a, double b = 0.0, double c = 0.0) {
    char buffer[256];
    std::snprintf(buffer, sizeof buffer, pattern, a, b, c);
    return buffer;
}

inline double pixel_sum(const Image& image, int x, int y) {
    return pixel_channel(image, x, y, 0) + pixel_channel(image, x, y, 1) + pixel_channel(image, x, y, 2);
}

inline bool all_finite(const Image& image) {
    for (float v : image.rgb)
        if (!std::isfinite(v)) return false;
    return true;
}

// Two renders of scenes that should look the same, from independent seeds
// or from the same one (common random numbers), compared region by region: in each of regions x regions blocks, the
// mean of the per-pixel differences (zero in expectation, independent across pixels) over its standard error. |z| <=
// kSigmaTolerance rejects a correct pair with probability 6.8e-6 per region.
struct RegionComparison {
    double worst_z = 0.0;         // largest |mean difference| / standard error
    double worst_relative = 0.0;  // largest |mean difference| / region mean
    double whole_relative = 0.0;  // whole-image mean difference / mean
    double whole_z = 0.0;         // whole-image mean difference / its standard error
};

inline RegionComparison compare_regions(const Image& a, const Image& b, int regions) {
    RegionComparison result;
    auto region_of = [&](int x, int y, int rx, int ry) {
        return x * regions / a.width == rx && y * regions / a.height == ry;
    };
    RunningMean whole_difference, whole_level;
    for (int ry = 0; ry < regions; ++ry) {
        for (int rx = 0; rx < regions; ++rx) {
            RunningMean difference, level;
            for (int y = 0; y < a.height; ++y) {
                for (int x = 0; x < a.width; ++x) {
                    if (!region_of(x, y, rx, ry)) continue;
                    difference.add(pixel_sum(a, x, y) - pixel_sum(b, x, y));
                    level.add(pixel_sum(b, x, y));
                }
            }
            if (level.mean() <= 0.0) continue;
            double z = difference.standard_error() > 0 ? std::fabs(difference.mean()) / difference.standard_error()
                                                       : (difference.mean() == 0.0 ? 0.0 : INFINITY);
            result.worst_z = std::max(result.worst_z, z);
            result.worst_relative = std::max(result.worst_relative, std::fabs(difference.mean()) / level.mean());
        }
    }
    for (int y = 0; y < a.height; ++y)
        for (int x = 0; x < a.width; ++x)
            whole_difference.add(pixel_sum(a, x, y) - pixel_sum(b, x, y)), whole_level.add(pixel_sum(b, x, y));
    result.whole_relative = whole_difference.mean() / whole_level.mean();
    result.whole_z =
        whole_difference.standard_error() > 0 ? whole_difference.mean() / whole_difference.standard_error() : 0.0;
    return result;
}

inline std::string describe(const RegionComparison& c) {
    return format("worst region z %.2f, worst region |diff| %.4f, ", c.worst_z, c.worst_relative) +
           format("whole image diff %+.5f (z %+.2f)", c.whole_relative, c.whole_z);
}

// Fraction of pixels whose three channels agree within `relative`.
inline double fraction_within(const Image& a, const Image& b, double relative, double scale_b = 1.0) {
    std::size_t pixels = a.rgb.size() / 3, agreeing = 0;
    for (std::size_t p = 0; p < pixels; ++p) {
        bool all = true;
        for (int c = 0; c < 3; ++c) {
            double x = a.rgb[3 * p + c], y = scale_b * b.rgb[3 * p + c];
            all = all && std::fabs(x - y) <= relative * std::max(std::fabs(x), std::fabs(y));
        }
        agreeing += all;
    }
    return double(agreeing) / double(pixels);
}

// scenes/room.json with every position scaled by `scale` about the world
// origin and moved by `translation`, sizes scaled, at a small resolution;
// the loader then rebases it to the camera in double.
inline Scene transformed_room(double scale, const glm::dvec3& translation, int size, int spp, std::uint32_t seed,
                              const std::function<void(nlohmann::json&)>& edit = {}) {
    std::ifstream file(std::string(WAVEPATH_SOURCE_DIR) + "/scenes/room.json");
    nlohmann::json room = nlohmann::json::parse(file);
    auto point = [&](nlohmann::json& v) {
        for (int i = 0; i < 3; ++i) v[i] = v[i].get<double>() * scale + translation[i];
    };
    auto vector = [&](nlohmann::json& v) {
        for (int i = 0; i < 3; ++i) v[i] = v[i].get<double>() * scale;
    };
    point(room["camera"]["position"]);
    point(room["camera"]["look_at"]);
    room["camera"]["width"] = size;
    room["camera"]["height"] = size;
    room["render"]["spp"] = spp;
    room["render"]["seed"] = seed;
    for (auto& shape : room["shapes"]) {
        if (shape["type"] == "quad") {
            point(shape["corner"]);
            vector(shape["edge1"]);
            vector(shape["edge2"]);
        } else {
            point(shape["center"]);
            shape["radius"] = shape["radius"].get<double>() * scale;
        }
    }
    if (edit) edit(room);
    return parse_scene(room.dump(), "room");
}

}  // namespace wp::test
