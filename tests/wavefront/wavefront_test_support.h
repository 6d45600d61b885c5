// Shared by the wavefront tests: scenes from JSON text, and a program cache
// kept in the build tree, so that each scene's feature set compiles once
// (PoCL takes seconds per program) and later runs hit the cache.
#pragma once

#include <cstdlib>
#include <filesystem>
#include <glm/vec3.hpp>
#include <string>
#include <vector>

#include "scene/scene.h"
#include "wavefront/pipeline.h"

namespace wp::test {

inline void use_build_tree_program_cache() {
    std::filesystem::path dir = std::filesystem::path(WAVEPATH_BINARY).parent_path() / "test-program-cache";
    ::setenv("WAVEPATH_CACHE_DIR", dir.c_str(), 1);
}

// A scene from JSON, with the camera block defaulted to a small image.
inline Scene scene_from_json(const std::string& json, const std::string& name = "test") {
    use_build_tree_program_cache();
    return parse_scene(json, name);
}

inline Scene scene_from_file(const std::string& relative_path) {
    use_build_tree_program_cache();
    return load_scene(std::string(WAVEPATH_SOURCE_DIR) + "/" + relative_path);
}

// scenes/room.json at size x size pixels and `spp` samples per pixel.
inline Scene small_room(int size, int spp) {
    Scene scene = scene_from_file("scenes/room.json");
    scene.camera.width = size;
    scene.camera.height = size;
    scene.render.spp = spp;
    return scene;
}

struct TestRay {
    glm::vec3 origin, direction;
};

// Puts fresh paths (depth 0, throughput 1, no radiance, after a "specular"
// camera vertex) with these rays into slots 0..n-1, path i being sample
// `first_sample + i` of pixel 0, and queues them all for intersect.
inline void start_paths(Pipeline& pipeline, const std::vector<TestRay>& rays, std::uint32_t first_sample = 0) {
    std::size_t n = rays.size();
    std::vector<float> o[3], d[3];
    std::vector<std::uint32_t> slots(n), samples(n);
    for (std::size_t i = 0; i < n; ++i) {
        for (int a = 0; a < 3; ++a) o[a].push_back(rays[i].origin[a]), d[a].push_back(rays[i].direction[a]);
        slots[i] = std::uint32_t(i);
        samples[i] = first_sample + std::uint32_t(i);
    }
    for (std::size_t a = 0; a < 3; ++a) {
        pipeline.write_field("origin", o[a], a);
        pipeline.write_field("direction", d[a], a);
        pipeline.write_field("radiance", std::vector<float>(n, 0.0f), a);
        pipeline.write_field("throughput", std::vector<float>(n, 1.0f), a);
    }
    pipeline.write_field("pixel", std::vector<std::uint32_t>(n, 0u));
    pipeline.write_field("sample", samples);
    pipeline.write_field("pass_item", slots);
    pipeline.write_field("depth", std::vector<std::uint32_t>(n, 0u));
    if (pipeline.state().has_field("specular")) pipeline.write_field("specular", std::vector<std::uint32_t>(n, 1u));
    pipeline.begin_pass(0, std::uint32_t(n));
    pipeline.queues().set_queue(WP_QUEUE_FREE, {});  // no slot free: misses and ended paths land there
    pipeline.queues().set_queue(WP_QUEUE_RAY, slots);
}

}  // namespace wp::test
