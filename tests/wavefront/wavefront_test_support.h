// Shared by the wavefront tests: scenes from JSON text, and a program cache
// kept in the build tree, so that each scene's feature set compiles once
// (PoCL takes seconds per program) and later runs hit the cache.
#pragma once

#include <cstdlib>
#include <filesystem>
#include <string>

#include "scene/scene.h"

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

}  // namespace wp::test
