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

// Pipeline::start_paths for these rays.
inline void start_paths(Pipeline& pipeline, const std::vector<TestRay>& rays, std::uint32_t first_sample = 0) {
    std::vector<glm::vec3> origins, directions;
    for (const TestRay& r : rays) origins.push_back(r.origin), directions.push_back(r.direction);
    pipeline.start_paths(origins, directions, first_sample);
}

}  // namespace wp::test
