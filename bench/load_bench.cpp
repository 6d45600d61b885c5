// load_bench: where a scene's load goes, phase by phase, in one process, as
// wavepath's render takes the steps (bench/big_scenes.py runs it once per
// measurement, so that each figure of memory is one load's). First a CPU
// device's path (its default for meshes: Embree traces, no BVH is built):
//  - load: the scene file and every mesh file (load_scene or, for .xml,
//    load_mitsuba_scene: the contained import included);
//  - layout: the device's triangles (mesh_layout without the BVH: the
//    scene's order), which the render uploads;
//  - embree: the Embree intersector over those triangles (which it takes,
//    and the device's buffer then uses in place, and Embree's BVH);
// its peak (VmHWM) read there. Then, the intersector and the layout gone
// and the peak reset (/proc/self/clear_refs), the path of the devices that
// trace with our BVH (GPUs, the megakernel):
//  - bvh: mesh_layout with the BVH: build_bvh (Embree's SAH builder,
//    flattened) over the triangles' corners, and the device's triangles in
//    its leaf order and its nodes;
// its peak. After each phase: the process's resident memory
// (/proc/self/statm); at the end the children's peak (getrusage: the import
// helper and its importers); and the bytes of each structure that holds
// triangles.
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

// Sets the peak back to the resident memory now (Linux 4.0 on); false if it cannot.
bool reset_peak() {
    std::FILE* clear_refs = std::fopen("/proc/self/clear_refs", "w");
    if (clear_refs == nullptr) return false;
    const bool written = std::fputs("5", clear_refs) >= 0;
    return std::fclose(clear_refs) == 0 && written;
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

    const FeatureSet features = scene.features();
    start = Clock::now();
    {
        MeshLayout<float> layout = mesh_layout<float>(scene, {false, features.shading_normals, features.textures});
        out["layout_s"] = seconds_since(start);
        out["resident_after_layout"] = resident_bytes() - resident_at_start;
        out["layout_bytes"] = {{"device_triangles", bytes_of(layout.triangles)},
                               {"device_normals", bytes_of(layout.normals)},
                               {"device_uvs", bytes_of(layout.uvs)}};

        start = Clock::now();
        // The render's device buffer uses the intersector's triangles in place: one copy.
        const EmbreeIntersector embree(scene, std::move(layout.triangles));
        out["embree_s"] = seconds_since(start);
        out["resident_after_embree"] = resident_bytes() - resident_at_start;
        out["peak_bytes"] = peak_bytes();
    }

    if (!reset_peak()) {
        std::cerr << "load_bench: cannot reset the peak (/proc/self/clear_refs)\n";
        return 1;
    }
    const std::size_t resident_before_bvh = resident_bytes();
    start = Clock::now();
    const MeshLayout<float> bvh = mesh_layout<float>(scene, {true, features.shading_normals, features.textures});
    out["bvh_s"] = seconds_since(start);
    out["resident_added_by_bvh"] = resident_bytes() - resident_before_bvh;
    out["bvh_bytes"] = {{"bvh_device_triangles", bytes_of(bvh.triangles)}, {"device_nodes", bytes_of(bvh.nodes)}};
    out["bvh_nodes"] = bvh.nodes.size();
    out["bvh_peak_bytes"] = peak_bytes();
    out["children_peak_bytes"] = children_peak_bytes();
    std::cout << out.dump() << std::endl;
    return 0;
}
