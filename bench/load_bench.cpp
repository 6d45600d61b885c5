// load_bench: where a scene's load goes, phase by phase, in one process, as
// wavepath's render takes the steps (bench/big_scenes.py runs it once per
// measurement, so that each figure of memory is one load's):
//  - load: the scene file and every mesh file (load_scene or, for .xml,
//    load_mitsuba_scene: the contained import included);
//  - bvh: build_scene_bvh (Embree's SAH builder, flattened) and its layout
//    for the device (traversable_bvh<float>: triangles and nodes as the
//    kernels read them);
//  - embree: the Embree intersector over the same triangles (the CPU
//    devices' default tracer, which builds Embree's own BVH).
// After each: the process's resident memory (/proc/self/statm); at the end
// its peak (VmHWM) and that of its children (getrusage: the import helper
// and its importers); and the bytes of each structure that holds triangles.
//
// Usage: load_bench SCENE   (prints one JSON object)
#include <sys/resource.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <iostream>
#include <nlohmann/json.hpp>
#include <string>

#include "accel/bvh.h"
#include "accel/bvh_layout.h"
#include "accel/embree_intersector.h"
#include "scene/mitsuba_xml.h"
#include "scene/scene.h"

namespace {

using namespace wp;
using json = nlohmann::json;
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

std::size_t resident_bytes() {
    std::FILE* statm = std::fopen("/proc/self/statm", "r");
    unsigned long size = 0, resident = 0;
    if (statm == nullptr || std::fscanf(statm, "%lu %lu", &size, &resident) != 2) resident = 0;
    if (statm != nullptr) std::fclose(statm);
    return std::size_t(resident) * std::size_t(::sysconf(_SC_PAGESIZE));
}

// This process's peak (VmHWM; getrusage's would carry the parent's across exec).
std::size_t peak_bytes() {
    std::FILE* status = std::fopen("/proc/self/status", "r");
    char line[256];
    unsigned long kib = 0;
    while (status != nullptr && std::fgets(line, sizeof line, status) != nullptr) {
        if (std::sscanf(line, "VmHWM: %lu", &kib) == 1) break;
    }
    if (status != nullptr) std::fclose(status);
    return std::size_t(kib) * 1024;
}

// The largest of the children waited for (the import helper; it was started small, so its own).
std::size_t children_peak_bytes() {
    rusage usage{};
    ::getrusage(RUSAGE_CHILDREN, &usage);
    return std::size_t(usage.ru_maxrss) * 1024;  // KiB on Linux
}

template <class T>
std::size_t bytes_of(const std::vector<T>& v) {
    return v.size() * sizeof(T);
}

Scene load(const std::string& path) {
    if (is_mitsuba_scene_path(path)) return load_mitsuba_scene(path, {});
    return load_scene(path);
}

}  // namespace

int main(int argc, char** argv) {
    if (argc != 2) {
        std::cerr << "usage: load_bench SCENE\n";
        return 2;
    }
    json out;
    const std::size_t resident_at_start = resident_bytes();
    auto start = Clock::now();
    Scene scene = load(argv[1]);
    out["load_s"] = seconds_since(start);
    out["resident_after_load"] = resident_bytes() - resident_at_start;

    std::size_t positions = 0, normals = 0, indices = 0, triangles = 0;
    for (const Mesh& mesh : scene.meshes) {
        positions += bytes_of(mesh.positions);
        normals += bytes_of(mesh.normals);
        indices += bytes_of(mesh.triangles);
        triangles += mesh.triangles.size();
    }
    out["meshes"] = scene.meshes.size();
    out["triangles"] = triangles;
    out["scene_bytes"] = {{"positions", positions}, {"normals", normals}, {"indices", indices}};

    start = Clock::now();
    SceneBvh bvh = build_scene_bvh(scene);
    out["bvh_s"] = seconds_since(start);
    start = Clock::now();
    TraversableBvh<float> flat = traversable_bvh<float>(bvh);
    out["layout_s"] = seconds_since(start);
    out["resident_after_bvh"] = resident_bytes() - resident_at_start;
    out["bvh_bytes"] = {{"scene_triangles", bytes_of(bvh.triangles)},
                        {"nodes", bytes_of(bvh.tree.nodes)},
                        {"leaf_order", bytes_of(bvh.tree.leaf_order)},
                        {"device_triangles", bytes_of(flat.triangles)},
                        {"device_nodes", bytes_of(flat.nodes)}};
    out["bvh_nodes"] = bvh.tree.nodes.size();

    start = Clock::now();
    const EmbreeIntersector embree(scene, flat.triangles);
    out["embree_s"] = seconds_since(start);
    out["resident_after_embree"] = resident_bytes() - resident_at_start;
    out["peak_bytes"] = peak_bytes();
    out["children_peak_bytes"] = children_peak_bytes();
    std::cout << out.dump() << std::endl;
    return 0;
}
