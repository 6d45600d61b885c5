// mesh_bench: what triangle meshes cost (issue 11, "Benchmark").
//
//  a. BVH build (build_bvh, and flatten_scene's whole mesh part: gathering,
//     build, leaf order, device structs) and bytes per triangle as uploaded
//     (64-byte nodes, 44-byte MeshTriangle), for meshes of about 1k to 1M
//     triangles made from the bunny: vertex clustering below its 69,666
//     triangles, 1->4 midpoint subdivision above.
//  b. Rays/s of closest hit and any hit on the bunny scene, side by side in
//     one run: the wavefront's intersect and intersect_shadow stages
//     (OpenCL, timed by their kernel events; and as --intersector embree
//     runs them, the host's trace timed by its clock plus the kernel's
//     rest), the scalar C++ traversal on 2 threads, Embree's rtcIntersect1 /
//     rtcOccluded1 on 2 threads (not robust, and robust), and our Embree
//     intersector (accel/embree_intersector.h) on a queue on 2 threads in
//     each mode, on the same rays and the same float triangles; repetitions
//     interleaved.
//  c. Whole-frame samples/s of the wavefront against triangle count.
//  d. Lanes with meshes: the shipped scene (spheres, quads, a mesh light and
//     the bunny) rendered with one lane and with 8 (the BVH traversed in
//     each lane, device/bvh_lanes.h), interleaved: samples/s, each stage's
//     device time, and whether the images are the same to the bit.
//  e. Short list or BVH: the shipped room, cornell and bunny scenes as they
//     are (spheres and quads tested one by one),
//     with their quads as triangles in the BVH instead, and with their
//     spheres left out (an upper bound on what moving them into the BVH
//     could save): samples/s, and the intersect stages' device time per ray.
//  f. The Embree intersector on the shipped scene (spheres, quads, the mesh
//     light, the bunny) in each mode (rays/s), and the reference renderer
//     with --intersector bvh and embree on the bunny and cornell_mesh
//     (samples/s, pixels that differ).
//  g. The wavefront with --intersector bvh and embree on the bunny,
//     cornell_mesh and the room (no meshes): samples/s, and the tracing
//     stages' rays/s (the host's trace and the kernel's rest).
//  h. Embree's own rtcIntersect1 and rtcIntersect16 on camera rays with 16
//     samples per pixel, a pixel's samples adjacent (Mitsuba's layout), and
//     their diffuse bounces: in that order, shuffled, and in packets of 16.
//
// The traced scene is scenes/bunny.json with its two spheres left out and
// each wall quad as two triangles, so that both tracers see exactly the same
// geometry (Embree has no quad of ours and no sphere of ours).
//
// Usage: mesh_bench [--quick] [--json FILE] [--scene FILE] [--device CHOICE] [--repeats N] [--sections abcdefgh]
//                   [--baseline-kernels DIR]
// --sections: which of a-h to run; --baseline-kernels: b also times the
// stages built from DIR (another commit's kernels/), interleaved, as
// opencl_baseline, and counts the rays where its hits differ from ours.
#include <embree3/rtcore.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <glm/geometric.hpp>
#include <iostream>
#include <limits>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <numeric>
#include <random>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "accel/bvh.h"
#include "accel/embree_intersector.h"
#include "bench_support.h"
#include "opencl/device.h"
#include "opencl/scene_upload.h"
#include "reference/path_tracer.h"
#include "reference/reference_renderer.h"
#include "reference/sample_rays.h"
#include "scene/scene.h"
#include "wavefront/intersector_choice.h"
#include "wavefront/pipeline.h"
#include "wavefront/wavefront_renderer.h"

namespace {

using namespace wp;
using json = nlohmann::json;
using M = SharedMath<float>;
using Ray = reference::Ray<float>;
using bench::Clock;
using bench::median;
using bench::minimum;
using bench::seconds_since;
using bench::subdivide;

constexpr unsigned kThreads = 2;  // the scalar C++ traversal's and Embree's tracing threads

// The machine's load averages over 1, 5 and 15 minutes (/proc/loadavg), "" where unknown.
std::string load_average() {
    std::ifstream in("/proc/loadavg");
    std::string one, five, fifteen;
    in >> one >> five >> fifteen;
    return in ? one + " " + five + " " + fifteen : "";
}

// Commit, date, machine and OpenCL platform: recorded with every result.
json run_metadata(const DeviceInfo& device, bool quick) {
    json meta = bench::machine_metadata();
    meta["opencl_platform"] = device.platform_version;
    meta["opencl_device"] = device.name;
    meta["embree"] = RTC_VERSION_STRING;
    meta["embree_device"] = embree_device_summary();
    meta["mode"] = quick ? "quick" : "full";
    meta["load_average_start"] = load_average();
    return meta;
}

// ---- meshes of every size, from the bunny ----

Mesh with_geometry(const Mesh& like, std::vector<glm::dvec3> positions, std::vector<glm::uvec3> triangles) {
    Mesh m;
    m.file = like.file;
    m.material = like.material;
    m.positions = std::move(positions);
    m.triangles = std::move(triangles);
    return m;  // face normals only, at every size
}

// Vertex clustering on a grid of `cells` along the longest side: each cell's
// vertices merge into their mean; collapsed and zero-area triangles are dropped.
Mesh cluster(const Mesh& mesh, int cells) {
    glm::dvec3 lower(std::numeric_limits<double>::infinity()), upper(-std::numeric_limits<double>::infinity());
    for (const glm::dvec3& p : mesh.positions) lower = glm::min(lower, p), upper = glm::max(upper, p);
    glm::dvec3 extent = upper - lower;
    double cell = std::max({extent.x, extent.y, extent.z}) / cells;
    std::map<std::array<int, 3>, std::uint32_t> cell_vertex;
    std::vector<std::uint32_t> remap(mesh.positions.size());
    std::vector<glm::dvec3> sums;
    std::vector<int> counts;
    for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
        glm::dvec3 q = (mesh.positions[i] - lower) / cell;
        std::array<int, 3> key{std::min(int(q.x), cells), std::min(int(q.y), cells), std::min(int(q.z), cells)};
        auto [it, added] = cell_vertex.try_emplace(key, std::uint32_t(sums.size()));
        if (added) sums.emplace_back(0.0), counts.push_back(0);
        remap[i] = it->second;
        sums[it->second] += mesh.positions[i];
        ++counts[it->second];
    }
    for (std::size_t v = 0; v < sums.size(); ++v) sums[v] /= double(counts[v]);
    Mesh out = with_geometry(mesh, std::move(sums), {});
    for (const glm::uvec3& t : mesh.triangles) {
        glm::uvec3 r(remap[t.x], remap[t.y], remap[t.z]);
        if (r.x == r.y || r.y == r.z || r.z == r.x) continue;
        if (triangle_area(out, r) > 0.0) out.triangles.push_back(r);
    }
    return out;
}

// The clustering whose triangle count is nearest `target` (counts grow with the grid).
Mesh decimate(const Mesh& mesh, std::size_t target) {
    int lo = 2, hi = 4096;
    while (lo < hi) {  // the first grid with at least `target` triangles
        int mid = (lo + hi) / 2;
        if (cluster(mesh, mid).triangles.size() < target)
            lo = mid + 1;
        else
            hi = mid;
    }
    Mesh above = cluster(mesh, lo), below = cluster(mesh, std::max(2, lo - 1));
    auto off = [target](const Mesh& m) { return std::abs(double(m.triangles.size()) - double(target)); };
    return off(below) < off(above) ? below : above;
}

// The bunny at each benchmark size: ~1k and ~10k clustered, itself, one and two subdivisions.
std::vector<Mesh> mesh_sizes(const Mesh& bunny, bool quick) {
    std::vector<Mesh> sizes{decimate(bunny, 1000)};
    if (!quick) sizes.push_back(decimate(bunny, 10000));
    sizes.push_back(with_geometry(bunny, bunny.positions, bunny.triangles));
    if (!quick) {
        sizes.push_back(subdivide(sizes.back()));
        sizes.push_back(subdivide(sizes.back()));
    }
    return sizes;
}

// ---- scenes ----

std::size_t largest_mesh(const Scene& scene) {
    if (scene.meshes.empty()) throw std::runtime_error(scene.source + ": the benchmark needs a mesh in the scene");
    std::size_t best = 0;
    for (std::size_t i = 1; i < scene.meshes.size(); ++i)
        if (scene.meshes[i].triangles.size() > scene.meshes[best].triangles.size()) best = i;
    return best;
}

// The scene with each quad as two triangles (a mesh of its own), after its meshes.
Scene quads_as_triangles(const Scene& scene) {
    Scene out = scene;
    out.quads.clear();
    for (const Quad& q : scene.quads) {
        Mesh m;
        m.file = "quad";
        m.material = q.material;
        m.positions = {q.corner, q.corner + q.edge1, q.corner + q.edge1 + q.edge2, q.corner + q.edge2};
        m.triangles = {{0, 1, 2}, {0, 2, 3}};  // counter-clockwise about edge1 x edge2, like the quad's front
        out.meshes.push_back(m);
    }
    build_light_table(out);
    return out;
}

Scene without_spheres(const Scene& scene) {
    Scene out = scene;
    out.spheres.clear();
    build_light_table(out);
    return out;
}

// The scene with triangles alone: spheres left out, each quad two triangles.
Scene triangles_only(const Scene& scene) {
    if (!scene.planes.empty()) throw std::runtime_error(scene.source + ": infinite planes cannot be triangulated");
    return quads_as_triangles(without_spheres(scene));
}

// The scene with its largest mesh replaced.
Scene with_mesh(const Scene& scene, const Mesh& mesh) {
    Scene out = scene;
    out.meshes[largest_mesh(scene)] = mesh;
    build_light_table(out);
    return out;
}

// ---- a. BVH build ----

json build_figures(const Scene& base, const std::vector<Mesh>& meshes, int repeats) {
    json rows = json::array();
    std::printf("\n## a. BVH build (min / median of %d; Embree binned SAH on all cores, then our flattening)\n\n",
                repeats);
    std::printf("%10s %8s %6s %14s %16s %10s %14s\n", "triangles", "nodes", "depth", "build_bvh s", "flatten_scene s",
                "bytes/tri", "flatten/tri ns");
    for (const Mesh& mesh : meshes) {
        Scene scene = base;  // the mesh alone, in the scene's first material
        scene.spheres.clear(), scene.planes.clear(), scene.quads.clear();
        scene.meshes = {mesh};
        scene.meshes[0].material = 0;
        build_light_table(scene);
        std::vector<TrianglePositions> triangles;
        for (const glm::uvec3& t : mesh.triangles)
            triangles.push_back({mesh.positions[t.x], mesh.positions[t.y], mesh.positions[t.z]});
        std::vector<double> build_s, flatten_s;
        std::size_t nodes = 0, uploaded = 0;
        int depth = 0;
        for (int r = 0; r < repeats; ++r) {  // interleaved: build, then the whole of flatten_scene
            auto start = Clock::now();
            BvhTree tree = build_bvh(triangles);
            build_s.push_back(seconds_since(start));
            start = Clock::now();
            SceneLayout layout = flatten_scene(scene);
            flatten_s.push_back(seconds_since(start));
            nodes = layout.bvh_nodes.size();
            depth = tree.depth;
            uploaded = sizeof(layout.bvh_nodes[0]) * layout.bvh_nodes.size() +
                       sizeof(layout.triangles[0]) * layout.triangles.size();
        }
        std::size_t n = mesh.triangles.size();
        double per_triangle = double(uploaded) / double(n);
        std::printf("%10zu %8zu %6d %6.3f / %5.3f %7.3f / %6.3f %10.1f %14.0f\n", n, nodes, depth, minimum(build_s),
                    median(build_s), minimum(flatten_s), median(flatten_s), per_triangle,
                    1e9 * median(flatten_s) / double(n));
        rows.push_back({{"triangles", n},
                        {"nodes", nodes},
                        {"depth", depth},
                        {"repeats", repeats},
                        {"build_bvh_s_min", minimum(build_s)},
                        {"build_bvh_s_median", median(build_s)},
                        {"flatten_scene_s_min", minimum(flatten_s)},
                        {"flatten_scene_s_median", median(flatten_s)},
                        {"uploaded_bytes", uploaded},
                        {"bytes_per_triangle", per_triangle}});
    }
    return rows;
}

// ---- b. traversal: the wavefront's stages, the scalar C++ traversal, Embree ----

struct RaySet {
    std::string name;
    std::vector<Ray> rays;
    std::vector<float> segment;  // any hit: t_max, 0.99 of the closest hit (FLT_MAX where none)
    // The same rays as the wavefront keeps them, for the Embree intersector: one array per component.
    std::array<std::vector<float>, 3> origin, direction;
    std::vector<std::uint32_t> queue;  // every slot, in order

    RaySet(std::string set_name, std::vector<Ray> set_rays, std::vector<float> segments)
        : name(std::move(set_name)), rays(std::move(set_rays)), segment(std::move(segments)) {
        for (std::uint32_t i = 0; i < rays.size(); ++i) {
            for (int a = 0; a < 3; ++a)
                origin[a].push_back(rays[i].origin[a]), direction[a].push_back(rays[i].direction[a]);
            queue.push_back(i);
        }
    }
    RayArrays arrays(bool bounded) const {
        return {{origin[0].data(), origin[1].data(), origin[2].data()},
                {direction[0].data(), direction[1].data(), direction[2].data()},
                bounded ? segment.data() : nullptr};
    }
};

struct ClosestResult {
    std::vector<float> t;            // infinity where nothing is hit
    std::vector<std::uint32_t> tri;  // leaf-order triangle index; ~0u where nothing is hit
};

const std::uint32_t kNone = ~0u;

void split_threads(std::size_t n, const std::function<void(std::size_t, std::size_t)>& work) {
    std::vector<std::thread> threads;
    for (unsigned k = 0; k < kThreads; ++k) threads.emplace_back(work, n * k / kThreads, n * (k + 1) / kThreads);
    for (std::thread& t : threads) t.join();
}

// The wavefront's intersect and intersect_shadow stages, run alone on given rays.
class StageTracer {
 public:
    // host_traced: the stages as --intersector embree runs them (the host traces, the kernel does the rest).
    StageTracer(const Scene& scene, const DeviceInfo& device, std::size_t n, bool host_traced = false)
        : n_(n), pipeline_(scene, device, n, n, features(scene, host_traced), options()) {
        if (!scene.features().nee) throw std::runtime_error("the benchmark scene needs a light (intersect_shadow)");
        for (std::size_t i = 0; i < n; ++i) slots_.push_back(std::uint32_t(i));
    }
    unsigned lanes() const { return pipeline_.lanes(); }

    // Device seconds of the intersect kernel.
    double closest(const std::vector<Ray>& rays, ClosestResult& out) {
        std::size_t n = rays.size();
        if (n > n_) throw std::logic_error("more rays than slots");
        std::vector<glm::vec3> origins, directions;
        for (const Ray& r : rays) origins.push_back(r.origin), directions.push_back(r.direction);
        pipeline_.start_paths(origins, directions);
        double seconds = timed("intersect", [this] { pipeline_.run_alone(Stage::intersect); });
        std::vector<float> t = pipeline_.read_field<float>("hit_t");
        std::vector<std::uint32_t> shape = pipeline_.read_field<std::uint32_t>("hit_shape");
        out.t.assign(n, std::numeric_limits<float>::infinity());
        out.tri.assign(n, kNone);
        for (std::size_t i = 0; i < n; ++i) {
            if (shape[i] == WP_NO_HIT) continue;
            if (shape[i] >> WP_SHAPE_TYPE_SHIFT != WP_SHAPE_TRIANGLE)
                throw std::logic_error("a hit that is no triangle");
            out.t[i] = t[i];
            out.tri[i] = shape[i] & ((1u << WP_SHAPE_TYPE_SHIFT) - 1u);
        }
        return seconds;
    }

    // Device seconds of the intersect_shadow kernel; occluded[i] 1 where something is hit before segment[i].
    double any(const std::vector<Ray>& rays, const std::vector<float>& segment, std::vector<std::uint8_t>& occluded) {
        std::size_t n = rays.size();
        std::vector<std::uint32_t> slots(slots_.begin(), slots_.begin() + std::ptrdiff_t(n));
        std::vector<float> o[3], d[3];
        split(rays, o, d);
        for (std::size_t a = 0; a < 3; ++a) {
            pipeline_.write_field("shadow_origin", o[a], a);
            pipeline_.write_field("shadow_direction", d[a], a);
            pipeline_.write_field("radiance", std::vector<float>(n, 0.0f), a);
            pipeline_.write_field("shadow_radiance", std::vector<float>(n, 1.0f), a);
        }
        pipeline_.write_field("shadow_distance", segment);
        pipeline_.write_field("depth", std::vector<std::uint32_t>(n, 0u));
        // Written, not left as the buffer's first contents: a path that the
        // stage takes as ended keeps its radiance, which reads as occluded.
        pipeline_.write_field("shadow_ends_path", std::vector<std::uint32_t>(n, 0u));
        pipeline_.begin_pass(0, std::uint32_t(n));
        pipeline_.queues().set_queue(WP_QUEUE_FREE, {});
        pipeline_.queues().set_queue(WP_QUEUE_SHADOW, slots);
        double seconds = timed("intersect_shadow", [this] { pipeline_.run_alone(Stage::intersect_shadow); });
        std::vector<float> radiance = pipeline_.read_field<float>("radiance");
        occluded.assign(n, 0);
        for (std::size_t i = 0; i < n; ++i) occluded[i] = radiance[i] == 1.0f ? 0 : 1;
        return seconds;
    }

 private:
    static PipelineOptions options() {
        PipelineOptions o;
        o.profile = true;
        return o;
    }
    static FeatureSet features(const Scene& scene, bool host_traced) {
        FeatureSet f = scene.features();
        f.host_traced = host_traced;
        f.shadow_stage = true;  // intersect_shadow, run alone
        return f;
    }
    void split(const std::vector<Ray>& rays, std::vector<float> (&o)[3], std::vector<float> (&d)[3]) const {
        if (rays.size() > n_) throw std::logic_error("more rays than slots");
        for (const Ray& r : rays)
            for (int a = 0; a < 3; ++a) o[a].push_back(r.origin[a]), d[a].push_back(r.direction[a]);
    }
    double kernel_seconds(const std::string& name) {
        double s = 0.0;
        for (const KernelProfile& k : pipeline_.profile().kernels)
            if (k.name == name) s += k.device_s;
        return s;
    }
    // The stage's kernel time, and where the host traces, the host's time too (its profile row).
    double timed(const std::string& kernel, const std::function<void()>& run) {
        pipeline_.read_counts();  // earlier kernels' times in
        const std::string host_row =
            host_trace_row(declaration(kernel == "intersect" ? Stage::intersect : Stage::intersect_shadow));
        double before = kernel_seconds(kernel) + kernel_seconds(host_row);
        run();
        pipeline_.read_counts();
        return kernel_seconds(kernel) + kernel_seconds(host_row) - before;
    }

    std::size_t n_;
    Pipeline pipeline_;
    std::vector<std::uint32_t> slots_;
};

// Embree's own scene of the same float triangles (primID = our leaf-order index).
class EmbreeTracer {
 public:
    EmbreeTracer(const std::vector<M::MeshTriangle>& triangles, bool robust) {
        device_ = rtcNewDevice("threads=2");
        if (!device_) throw std::runtime_error("Embree: cannot create a device");
        scene_ = rtcNewScene(device_);
        rtcSetSceneBuildQuality(scene_, RTC_BUILD_QUALITY_MEDIUM);
        rtcSetSceneFlags(scene_, robust ? RTC_SCENE_FLAG_ROBUST : RTC_SCENE_FLAG_NONE);
        RTCGeometry geometry = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
        auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(
            geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), 3 * triangles.size()));
        auto* indices = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
            geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), triangles.size()));
        for (std::size_t i = 0; i < triangles.size(); ++i) {
            const M::MeshTriangle& t = triangles[i];
            for (int a = 0; a < 3; ++a) {
                vertices[9 * i + a] = t.p0[a];
                vertices[9 * i + 3 + a] = t.p1[a];
                vertices[9 * i + 6 + a] = t.p2[a];
            }
            for (int k = 0; k < 3; ++k) indices[3 * i + k] = unsigned(3 * i + k);
        }
        rtcCommitGeometry(geometry);
        rtcAttachGeometry(scene_, geometry);
        rtcReleaseGeometry(geometry);
        rtcCommitScene(scene_);
    }
    ~EmbreeTracer() {
        rtcReleaseScene(scene_);
        rtcReleaseDevice(device_);
    }

    double closest(const std::vector<Ray>& rays, ClosestResult& out) {
        out.t.assign(rays.size(), std::numeric_limits<float>::infinity());
        out.tri.assign(rays.size(), kNone);
        auto start = Clock::now();
        split_threads(rays.size(), [&](std::size_t begin, std::size_t end) {
            RTCIntersectContext context;
            rtcInitIntersectContext(&context);
            for (std::size_t i = begin; i < end; ++i) {
                RTCRayHit rh{};
                set_ray(rh.ray, rays[i], std::numeric_limits<float>::infinity());
                rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
                rtcIntersect1(scene_, &context, &rh);
                if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) continue;
                out.t[i] = rh.ray.tfar;
                out.tri[i] = rh.hit.primID;
            }
        });
        return seconds_since(start);
    }

    // rtcIntersect16 on consecutive rays, 16 at a time (the last packet's missing lanes invalid).
    double closest_packets(const std::vector<Ray>& rays, ClosestResult& out) {
        out.t.assign(rays.size(), std::numeric_limits<float>::infinity());
        out.tri.assign(rays.size(), kNone);
        const std::size_t packets = (rays.size() + 15) / 16;
        auto start = Clock::now();
        split_threads(packets, [&](std::size_t begin, std::size_t end) {
            RTCIntersectContext context;
            rtcInitIntersectContext(&context);
            for (std::size_t p = begin; p < end; ++p) {
                RTCRayHit16 rh;
                alignas(64) int valid[16];
                for (std::size_t k = 0; k < 16; ++k) {
                    const std::size_t i = 16 * p + k;
                    valid[k] = i < rays.size() ? -1 : 0;
                    const Ray& ray = rays[std::min(i, rays.size() - 1)];
                    rh.ray.org_x[k] = ray.origin.x, rh.ray.org_y[k] = ray.origin.y, rh.ray.org_z[k] = ray.origin.z;
                    rh.ray.dir_x[k] = ray.direction.x, rh.ray.dir_y[k] = ray.direction.y;
                    rh.ray.dir_z[k] = ray.direction.z;
                    rh.ray.tnear[k] = 0.0f, rh.ray.tfar[k] = std::numeric_limits<float>::infinity();
                    rh.ray.time[k] = 0.0f, rh.ray.mask[k] = ~0u, rh.ray.id[k] = 0, rh.ray.flags[k] = 0;
                    rh.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID;
                }
                rtcIntersect16(valid, scene_, &context, &rh);
                for (std::size_t k = 0; k < 16 && 16 * p + k < rays.size(); ++k) {
                    if (rh.hit.geomID[k] == RTC_INVALID_GEOMETRY_ID) continue;
                    out.t[16 * p + k] = rh.ray.tfar[k];
                    out.tri[16 * p + k] = rh.hit.primID[k];
                }
            }
        });
        return seconds_since(start);
    }

    double any(const std::vector<Ray>& rays, const std::vector<float>& segment, std::vector<std::uint8_t>& occluded) {
        occluded.assign(rays.size(), 0);
        auto start = Clock::now();
        split_threads(rays.size(), [&](std::size_t begin, std::size_t end) {
            RTCIntersectContext context;
            rtcInitIntersectContext(&context);
            for (std::size_t i = begin; i < end; ++i) {
                RTCRay ray{};
                set_ray(ray, rays[i], segment[i]);
                rtcOccluded1(scene_, &context, &ray);
                occluded[i] = ray.tfar < 0.0f;
            }
        });
        return seconds_since(start);
    }

 private:
    static void set_ray(RTCRay& r, const Ray& ray, float t_max) {
        r.org_x = ray.origin.x, r.org_y = ray.origin.y, r.org_z = ray.origin.z;
        r.dir_x = ray.direction.x, r.dir_y = ray.direction.y, r.dir_z = ray.direction.z;
        r.tnear = 0.0f;
        r.tfar = t_max;
        r.mask = ~0u;
    }
    RTCDevice device_;
    RTCScene scene_;
};

// The Embree intersector (src/accel/embree_intersector.h) on a queue of
// every ray, read from and written to arrays by slot as the wavefront's
// intersect stages will hand them over, on kThreads threads.
class IntersectorTracer {
 public:
    IntersectorTracer(const Scene& scene, const std::vector<M::MeshTriangle>& triangles, EmbreeOptions options)
        : embree_(scene, triangles, with_threads(options)) {}

    double closest(const RaySet& set, ClosestResult& out) {
        std::vector<float> t(set.rays.size());
        std::vector<std::uint32_t> shape(set.rays.size());
        std::uint64_t retraced_before = embree_.retraced_rays();
        auto start = Clock::now();
        embree_.closest(set.arrays(false), set.queue, {t.data(), shape.data()});
        double seconds = seconds_since(start);
        last_retraced_ = embree_.retraced_rays() - retraced_before;
        out.t.assign(set.rays.size(), std::numeric_limits<float>::infinity());
        out.tri.assign(set.rays.size(), kNone);
        for (std::size_t i = 0; i < t.size(); ++i) {
            if (shape[i] == WP_NO_HIT) continue;
            if (shape[i] >> WP_SHAPE_TYPE_SHIFT == WP_SHAPE_TRIANGLE) out.tri[i] = shape[i] & WP_SHAPE_INDEX_MASK;
            out.t[i] = t[i];
        }
        return seconds;
    }

    double any(const RaySet& set, std::vector<std::uint8_t>& occluded) {
        std::vector<std::uint32_t> flags(set.rays.size());
        auto start = Clock::now();
        embree_.occluded(set.arrays(true), set.queue, flags.data());
        double seconds = seconds_since(start);
        occluded.assign(flags.begin(), flags.end());
        return seconds;
    }

    // Rays the last closest() traced again exactly (EmbreeMode::Verified).
    std::uint64_t last_retraced() const { return last_retraced_; }

 private:
    static EmbreeOptions with_threads(EmbreeOptions options) {
        options.threads = kThreads;
        return options;
    }
    EmbreeIntersector embree_;
    std::uint64_t last_retraced_ = 0;
};

// "ours_verified": the tracer's name in the tables.
std::string intersector_name(const EmbreeOptions& options) { return "ours_" + mode_name(options.mode); }

// The scalar C++ traversal (the reference's, kernels/shared/bvh.h) on kThreads threads.
double scalar_closest(const reference::ReferenceScene<float>& scene, const std::vector<Ray>& rays, ClosestResult& out) {
    out.t.assign(rays.size(), std::numeric_limits<float>::infinity());
    out.tri.assign(rays.size(), kNone);
    auto start = Clock::now();
    split_threads(rays.size(), [&](std::size_t begin, std::size_t end) {
        for (std::size_t i = begin; i < end; ++i) {
            reference::ShapeHit<float> hit = reference::closest_hit(scene, rays[i]);
            if (!hit.found()) continue;
            out.t[i] = hit.t;
            out.tri[i] = std::uint32_t(hit.index);
        }
    });
    return seconds_since(start);
}

double scalar_any(const reference::ReferenceScene<float>& scene, const std::vector<Ray>& rays,
                  const std::vector<float>& segment, std::vector<std::uint8_t>& occluded) {
    occluded.assign(rays.size(), 0);
    auto start = Clock::now();
    split_threads(rays.size(), [&](std::size_t begin, std::size_t end) {
        for (std::size_t i = begin; i < end; ++i) occluded[i] = reference::occluded(scene, rays[i], segment[i]);
    });
    return seconds_since(start);
}

// Primary rays (one per pixel, jittered as the renderer's first sample) and
// incoherent rays: a cosine-distributed bounce from each primary hit, its
// origin offset along the normal as the renderer offsets it
// (reference/sample_rays.h); segments for any hit end at 0.99 of the closest hit.
std::vector<RaySet> make_rays(const reference::ReferenceScene<float>& scene) {
    reference::SampleRays rays = reference::sample_rays(scene);
    auto segments = [&](const std::vector<Ray>& set) {
        std::vector<float> segment;
        for (const Ray& ray : set) {
            reference::ShapeHit<float> hit = reference::closest_hit(scene, ray);
            segment.push_back(hit.found() ? 0.99f * hit.t : M::real_max);  // as far as a float reaches
        }
        return segment;
    };
    std::vector<float> primary = segments(rays.camera), bounce = segments(rays.bounce);
    return {RaySet("primary", std::move(rays.camera), std::move(primary)),
            RaySet("incoherent", std::move(rays.bounce), std::move(bounce))};
}

// Rays whose hit differs beyond float tolerance: one hits and the other not,
// or the distances differ by more than 1e-4 relative. Hits of another
// triangle at the same distance (a shared edge or vertex) are counted apart.
struct Agreement {
    std::size_t hits_a = 0, hits_b = 0, differ = 0, other_triangle_same_t = 0, bit_identical = 0;
};
Agreement compare(const ClosestResult& a, const ClosestResult& b) {
    Agreement g;
    for (std::size_t i = 0; i < a.t.size(); ++i) {
        bool ha = a.tri[i] != kNone, hb = b.tri[i] != kNone;
        g.hits_a += ha, g.hits_b += hb;
        if (a.tri[i] == b.tri[i] && (a.t[i] == b.t[i] || (!ha && !hb))) ++g.bit_identical;
        if (ha != hb) {
            ++g.differ;
        } else if (ha) {
            if (std::abs(a.t[i] - b.t[i]) > 1e-4f * std::max(1.0f, std::abs(b.t[i])))
                ++g.differ;
            else if (a.tri[i] != b.tri[i])
                ++g.other_triangle_same_t;
        }
    }
    return g;
}

// A StageTracer whose kernels are read from `kernel_dir` (another commit's
// kernels/): WAVEPATH_KERNEL_DIR while its program is built.
std::unique_ptr<StageTracer> tracer_from(const std::string& kernel_dir, const Scene& scene, const DeviceInfo& device,
                                         std::size_t n) {
    const char* before = std::getenv("WAVEPATH_KERNEL_DIR");
    std::string saved = before ? before : "";
    ::setenv("WAVEPATH_KERNEL_DIR", kernel_dir.c_str(), 1);
    auto tracer = std::make_unique<StageTracer>(scene, device, n);
    if (before)
        ::setenv("WAVEPATH_KERNEL_DIR", saved.c_str(), 1);
    else
        ::unsetenv("WAVEPATH_KERNEL_DIR");
    return tracer;
}

json traversal_figures(const Scene& traced, const DeviceInfo& device, int repeats, const std::string& baseline_kernels,
                       json& agreement_rows) {
    reference::ReferenceScene<float> reference_scene(traced);
    std::vector<RaySet> sets = make_rays(reference_scene);
    std::size_t capacity = 0;
    for (const RaySet& s : sets) capacity = std::max(capacity, s.rays.size());
    StageTracer stages(traced, device, capacity), host_traced_stages(traced, device, capacity, true);
    EmbreeTracer embree(reference_scene.triangles, false), embree_robust(reference_scene.triangles, true);
    std::unique_ptr<StageTracer> baseline;
    if (!baseline_kernels.empty()) baseline = tracer_from(baseline_kernels, traced, device, capacity);
    std::printf(
        "\n## b. Traversal: %zu triangles, %zu primary and %zu incoherent rays, %d interleaved repetitions, %u threads "
        "for the scalar C++ and Embree, OpenCL stage lanes %u; %s\n",
        reference_scene.triangles.size(), sets[0].rays.size(), sets[1].rays.size(), repeats, kThreads, stages.lanes(),
        embree_device_summary().c_str());

    // Every tracer: its name, closest hit and any hit, each returning seconds.
    struct Tracer {
        std::string name;
        std::function<double(const RaySet&, ClosestResult&)> closest;
        std::function<double(const RaySet&, std::vector<std::uint8_t>&)> any;
    };
    std::vector<Tracer> impls = {
        {"opencl_stage", [&](const RaySet& set, ClosestResult& out) { return stages.closest(set.rays, out); },
         [&](const RaySet& set, std::vector<std::uint8_t>& out) { return stages.any(set.rays, set.segment, out); }},
        {"embree_stage",
         [&](const RaySet& set, ClosestResult& out) { return host_traced_stages.closest(set.rays, out); },
         [&](const RaySet& set, std::vector<std::uint8_t>& out) {
             return host_traced_stages.any(set.rays, set.segment, out);
         }},
        {"scalar_cpp",
         [&](const RaySet& set, ClosestResult& out) { return scalar_closest(reference_scene, set.rays, out); },
         [&](const RaySet& set, std::vector<std::uint8_t>& out) {
             return scalar_any(reference_scene, set.rays, set.segment, out);
         }},
        {"embree", [&](const RaySet& set, ClosestResult& out) { return embree.closest(set.rays, out); },
         [&](const RaySet& set, std::vector<std::uint8_t>& out) { return embree.any(set.rays, set.segment, out); }},
        {"embree_robust", [&](const RaySet& set, ClosestResult& out) { return embree_robust.closest(set.rays, out); },
         [&](const RaySet& set, std::vector<std::uint8_t>& out) {
             return embree_robust.any(set.rays, set.segment, out);
         }},
    };
    const std::size_t kEmbreeStage = 1, kScalar = 2, kEmbree = 3, kFirstOurs = impls.size();
    std::vector<std::unique_ptr<IntersectorTracer>> ours;
    for (EmbreeMode mode : {EmbreeMode::Verified, EmbreeMode::Exact}) {
        EmbreeOptions options{mode, int(kThreads)};
        IntersectorTracer* tracer =
            ours.emplace_back(std::make_unique<IntersectorTracer>(traced, reference_scene.triangles, options)).get();
        impls.push_back(
            {intersector_name(options),
             [tracer](const RaySet& set, ClosestResult& out) { return tracer->closest(set, out); },
             [tracer](const RaySet& set, std::vector<std::uint8_t>& out) { return tracer->any(set, out); }});
    }
    std::size_t baseline_index = impls.size();
    if (baseline)
        impls.push_back({"opencl_baseline",
                         [&](const RaySet& set, ClosestResult& out) { return baseline->closest(set.rays, out); },
                         [&](const RaySet& set, std::vector<std::uint8_t>& out) {
                             return baseline->any(set.rays, set.segment, out);
                         }});
    const std::size_t n_impls = impls.size();
    const char* queries[] = {"closest", "any"};
    // times[set][query][impl]
    std::vector<std::vector<std::vector<std::vector<double>>>> times(
        sets.size(), std::vector<std::vector<std::vector<double>>>(2, std::vector<std::vector<double>>(n_impls)));
    std::vector<std::vector<ClosestResult>> closest(sets.size(), std::vector<ClosestResult>(n_impls));
    std::vector<std::vector<std::uint64_t>> retraced(sets.size(), std::vector<std::uint64_t>(ours.size()));
    std::vector<std::vector<std::vector<std::uint8_t>>> any(sets.size(),
                                                            std::vector<std::vector<std::uint8_t>>(n_impls));
    for (int r = -1; r < repeats; ++r) {  // r = -1: warm-up, not recorded (PoCL compiles at the first launch)
        for (std::size_t s = 0; s < sets.size(); ++s) {
            const RaySet& set = sets[s];
            std::vector<double> t[2];
            for (std::size_t i = 0; i < n_impls; ++i) {
                t[0].push_back(impls[i].closest(set, closest[s][i]));
                t[1].push_back(impls[i].any(set, any[s][i]));
            }
            for (std::size_t k = 0; k < ours.size(); ++k) retraced[s][k] = ours[k]->last_retraced();
            if (r < 0) continue;
            for (int q = 0; q < 2; ++q)
                for (std::size_t i = 0; i < n_impls; ++i) times[s][q][i].push_back(t[q][i]);
        }
    }

    json rows = json::array();
    std::printf("\n%-11s %-8s %-28s %12s %14s %16s %8s\n", "rays", "query", "tracer", "Mrays/s best", "Mrays/s median",
                "of Embree (med)", "hits");
    for (std::size_t s = 0; s < sets.size(); ++s) {
        const std::size_t count = sets[s].rays.size();
        for (int q = 0; q < 2; ++q) {
            double embree_median = double(count) / median(times[s][q][kEmbree]);
            for (std::size_t i = 0; i < n_impls; ++i) {
                double best = double(count) / minimum(times[s][q][i]) / 1e6;
                double med = double(count) / median(times[s][q][i]) / 1e6;
                std::size_t hits = 0;
                if (q == 0)
                    for (std::uint32_t tri : closest[s][i].tri) hits += tri != kNone;
                else
                    for (std::uint8_t o : any[s][i]) hits += o;
                double ratio = med * 1e6 / embree_median;
                std::printf("%-11s %-8s %-28s %12.2f %14.2f %15.2fx %8zu\n", sets[s].name.c_str(), queries[q],
                            impls[i].name.c_str(), best, med, ratio, hits);
                if (q == 0 && i >= kFirstOurs && i < kFirstOurs + ours.size())
                    std::printf("%-11s %-8s %-28s traced again exactly: %llu rays\n", "", "", "",
                                static_cast<unsigned long long>(retraced[s][i - kFirstOurs]));
                rows.push_back({{"rays", sets[s].name},
                                {"query", queries[q]},
                                {"tracer", impls[i].name},
                                {"ray_count", count},
                                {"repeats", repeats},
                                {"mrays_s_best", best},
                                {"mrays_s_median", med},
                                {"of_embree_median", ratio},
                                {"hits", hits}});
                if (q == 0 && i >= kFirstOurs && i < kFirstOurs + ours.size())
                    rows.back()["retraced"] = retraced[s][i - kFirstOurs];
            }
        }
    }

    std::printf(
        "\nAgreement (last repetition): closest hit, a ray differs where one tracer hits and the other does "
        "not or the distances differ by more than 1e-4 relative; any hit, where the verdicts differ. Any-hit "
        "rays are segments ending at 0.99 of their closest hit.\n\n");
    std::printf("%-11s %-8s %-44s %10s %10s %12s %18s %14s\n", "rays", "query", "pair", "hits a", "hits b", "differ",
                "other tri same t", "bit-identical");
    for (std::size_t s = 0; s < sets.size(); ++s) {
        const std::size_t count = sets[s].rays.size();
        std::vector<std::pair<std::size_t, std::size_t>> pairs{{0, kEmbree}, {0, kScalar}, {kScalar, kEmbreeStage}};
        if (baseline) pairs.emplace_back(0, baseline_index);
        for (std::size_t k = kFirstOurs; k < kFirstOurs + ours.size(); ++k) pairs.emplace_back(kScalar, k);
        for (auto [a, b] : pairs) {
            std::string pair = impls[a].name + " vs " + impls[b].name;
            Agreement g = compare(closest[s][a], closest[s][b]);
            std::printf("%-11s %-8s %-44s %10zu %10zu %11.5f%% %18zu %13.2f%%\n", sets[s].name.c_str(), "closest",
                        pair.c_str(), g.hits_a, g.hits_b, 100.0 * double(g.differ) / double(count),
                        g.other_triangle_same_t, 100.0 * double(g.bit_identical) / double(count));
            agreement_rows.push_back({{"rays", sets[s].name},
                                      {"query", "closest"},
                                      {"pair", pair},
                                      {"ray_count", count},
                                      {"hits_a", g.hits_a},
                                      {"hits_b", g.hits_b},
                                      {"differ_fraction", double(g.differ) / double(count)},
                                      {"other_triangle_same_t", g.other_triangle_same_t},
                                      {"bit_identical_fraction", double(g.bit_identical) / double(count)}});
            std::size_t occluded_a = 0, occluded_b = 0, differ = 0;
            for (std::size_t i = 0; i < count; ++i) {
                occluded_a += any[s][a][i], occluded_b += any[s][b][i];
                differ += any[s][a][i] != any[s][b][i];
            }
            std::printf("%-11s %-8s %-44s %10zu %10zu %11.5f%%\n", sets[s].name.c_str(), "any", pair.c_str(),
                        occluded_a, occluded_b, 100.0 * double(differ) / double(count));
            agreement_rows.push_back({{"rays", sets[s].name},
                                      {"query", "any"},
                                      {"pair", pair},
                                      {"ray_count", count},
                                      {"hits_a", occluded_a},
                                      {"hits_b", occluded_b},
                                      {"differ_fraction", double(differ) / double(count)}});
        }
    }
    return rows;
}

// ---- c. whole frames ----

// Sections c, d and e measure our BVH in the kernels (the wavefront's default for meshes on a CPU is Embree).
WavefrontOptions traced_by_bvh() {
    WavefrontOptions options;
    options.intersector = Intersector::Bvh;
    return options;
}

// A profiled render's options: intersect and shade apart, so that the
// tracing stage's time is its own (the default on a CPU launches them as
// one kernel, intersect_and_shade).
WavefrontOptions profiled_apart(WavefrontOptions options) {
    options.profile = true;
    options.intersect_and_shade = false;
    return options;
}

// The fields of every whole-frame row: image size, samples, repetitions and samples/s.
json frame_fields(int size, int spp, int repeats, const std::vector<double>& samples_per_s) {
    return {{"width", size},
            {"height", size},
            {"spp", spp},
            {"repeats", repeats},
            {"msamples_s_min", minimum(samples_per_s) / 1e6},
            {"msamples_s_median", median(samples_per_s) / 1e6}};
}

json render_figures(const Scene& traced, const std::vector<Mesh>& meshes, int size, int spp, int repeats) {
    std::printf(
        "\n## c. Whole frames: wavefront, %dx%d, %d spp, %d interleaved repetitions (after one warm-up "
        "render), the traced scene with the bunny at each size\n\n",
        size, size, spp, repeats);
    std::vector<Scene> scenes;
    for (const Mesh& mesh : meshes) {
        Scene scene = with_mesh(traced, mesh);
        scene.camera.width = scene.camera.height = size;
        scene.render.spp = spp;
        scenes.push_back(scene);
    }
    std::vector<std::vector<double>> sps(scenes.size()), rps(scenes.size());
    render_wavefront(scenes[0], traced_by_bvh(), Progress{});  // warm-up: kernel compilation
    for (int r = 0; r < repeats; ++r) {
        for (std::size_t k = 0; k < scenes.size(); ++k) {
            RenderStats stats = render_wavefront(scenes[k], traced_by_bvh(), Progress{}).stats;
            sps[k].push_back(double(stats.samples) / stats.time_s);
            rps[k].push_back(double(stats.extension_rays + stats.shadow_rays) / stats.time_s);
        }
    }
    json rows = json::array();
    std::printf("%12s %16s %18s %18s\n", "triangles", "scene triangles", "Msamples/s min", "median   Mrays/s");
    for (std::size_t k = 0; k < scenes.size(); ++k) {
        std::size_t total = 0;
        for (const Mesh& m : scenes[k].meshes) total += m.triangles.size();
        std::printf("%12zu %16zu %11.4f %11.4f %9.3f\n", meshes[k].triangles.size(), total, minimum(sps[k]) / 1e6,
                    median(sps[k]) / 1e6, median(rps[k]) / 1e6);
        json row = frame_fields(size, spp, repeats, sps[k]);
        row.update({{"triangles", meshes[k].triangles.size()},
                    {"scene_triangles", total},
                    {"mrays_s_median", median(rps[k]) / 1e6}});
        rows.push_back(row);
    }
    return rows;
}

// ---- d. lanes with meshes ----

json lanes_figures(const Scene& shipped, int size, int spp, int repeats) {
    Scene scene = shipped;
    scene.camera.width = scene.camera.height = size;
    scene.render.spp = spp;
    const unsigned lanes[] = {1u, 8u};
    constexpr int kConfigs = 2;
    const std::vector<std::string> kernels{"generate",      "intersect",     "shade",     "intersect_shadow",
                                           "compact_count", "compact_write", "accumulate"};
    std::printf(
        "\n## d. Lanes with meshes: %s, %dx%d, %d spp, %d interleaved repetitions (after one warm-up render each), "
        "one lane against 8\n\n",
        shipped.source.c_str(), size, size, spp, repeats);
    std::vector<double> sps[kConfigs];
    std::map<std::string, std::vector<double>> stage_s[kConfigs];
    std::vector<float> image[kConfigs];
    for (int r = -1; r < repeats; ++r) {  // r = -1: warm-up (kernel compilation)
        for (int k = 0; k < kConfigs; ++k) {
            WavefrontOptions options = traced_by_bvh();
            options.lanes = lanes[k];
            RenderResult plain = render_wavefront(scene, options, Progress{});
            // a render of its own: profiling adds count_depths and waits on events
            WavefrontReport report;
            render_wavefront(scene, profiled_apart(options), Progress{}, &report);
            image[k] = plain.image.rgb;
            if (report.lanes != lanes[k]) throw std::logic_error("the pipeline ran other lanes than asked");
            if (r < 0) continue;
            sps[k].push_back(double(plain.stats.samples) / plain.stats.time_s);
            for (const std::string& name : kernels)
                stage_s[k][name].push_back(report.profile.has_kernel(name) ? report.profile.kernel(name).device_s
                                                                           : 0.0);
        }
    }
    bool identical = image[0] == image[1];
    std::printf("%-7s %16s %10s", "lanes", "Msamples/s min", "median");
    for (const std::string& name : kernels) std::printf(" %16s", (name + " ms").c_str());
    std::printf("\n");
    json rows = json::array();
    for (int k = 0; k < kConfigs; ++k) {
        std::printf("%-7u %16.4f %10.4f", lanes[k], minimum(sps[k]) / 1e6, median(sps[k]) / 1e6);
        json stages = json::object();
        for (const std::string& name : kernels) {
            std::printf(" %16.1f", 1e3 * median(stage_s[k][name]));
            stages[name] = {{"device_ms_min", 1e3 * minimum(stage_s[k][name])},
                            {"device_ms_median", 1e3 * median(stage_s[k][name])}};
        }
        std::printf("\n");
        json row = frame_fields(size, spp, repeats, sps[k]);
        row.update({{"scene", shipped.source},
                    {"lanes", lanes[k]},
                    {"stages", stages},
                    {"image_identical_to_one_lane", identical}});
        rows.push_back(row);
    }
    std::printf("images identical to the bit: %s\n", identical ? "yes" : "NO");
    if (!identical) throw std::runtime_error("another number of lanes rendered another image");
    return rows;
}

// ---- e. short list or BVH ----

json short_list_figures(int size, int spp, int repeats) {
    struct Variant {
        std::string scene, shapes;
        Scene loaded;
    };
    std::vector<Variant> variants;
    for (const char* name : {"room", "cornell", "bunny"}) {
        Scene scene = load_scene(std::string(WAVEPATH_SOURCE_DIR "/scenes/") + name + ".json");
        scene.camera.width = scene.camera.height = size;
        scene.render.spp = spp;
        variants.push_back({name, "as shipped", scene});
        variants.push_back({name, "quads as triangles in the BVH", quads_as_triangles(scene)});
        if (!scene.spheres.empty()) variants.push_back({name, "spheres left out", without_spheres(scene)});
    }
    std::printf(
        "\n## e. Short list or BVH: %dx%d, %d spp, %d interleaved repetitions (after one warm-up render each); "
        "intersect stages' device time per ray from a profiled render of its own (intersect and shade apart)\n\n",
        size, size, spp, repeats);
    std::vector<std::vector<double>> sps(variants.size()), closest_ns(variants.size()), any_ns(variants.size());
    for (int r = -1; r < repeats; ++r) {
        for (std::size_t k = 0; k < variants.size(); ++k) {
            RenderStats plain = render_wavefront(variants[k].loaded, traced_by_bvh(), Progress{}).stats;
            WavefrontOptions profiled = profiled_apart(traced_by_bvh());
            WavefrontReport report;
            RenderStats stats = render_wavefront(variants[k].loaded, profiled, Progress{}, &report).stats;
            if (r < 0) continue;
            sps[k].push_back(double(plain.samples) / plain.time_s);
            closest_ns[k].push_back(1e9 * report.profile.kernel("intersect").device_s / double(stats.extension_rays));
            any_ns[k].push_back(1e9 * report.profile.kernel("intersect_shadow").device_s / double(stats.shadow_rays));
        }
    }
    std::printf("%-8s %-32s %16s %10s %22s %22s\n", "scene", "shapes", "Msamples/s min", "median",
                "intersect ns/ray (med)", "shadow ns/ray (med)");
    json rows = json::array();
    for (std::size_t k = 0; k < variants.size(); ++k) {
        std::printf("%-8s %-32s %16.4f %10.4f %22.1f %22.1f\n", variants[k].scene.c_str(), variants[k].shapes.c_str(),
                    minimum(sps[k]) / 1e6, median(sps[k]) / 1e6, median(closest_ns[k]), median(any_ns[k]));
        json row = frame_fields(size, spp, repeats, sps[k]);
        row.update({{"scene", variants[k].scene},
                    {"shapes", variants[k].shapes},
                    {"intersect_ns_per_ray_median", median(closest_ns[k])},
                    {"intersect_shadow_ns_per_ray_median", median(any_ns[k])}});
        rows.push_back(row);
    }
    return rows;
}

// ---- f. the Embree intersector: spheres and quads, and the reference ----

// The shipped scene (spheres, quads, the mesh light, the bunny) in each
// mode: quads among Embree's shapes, spheres tested in turn.
json shipped_scene_figures(const Scene& shipped, int size, int repeats) {
    Scene scene = shipped;
    scene.camera.width = scene.camera.height = size;
    reference::ReferenceScene<float> reference_scene(scene);
    std::vector<RaySet> sets = make_rays(reference_scene);
    std::vector<std::unique_ptr<IntersectorTracer>> tracers;
    std::vector<std::string> names;
    for (EmbreeMode mode : {EmbreeMode::Verified, EmbreeMode::Exact}) {
        EmbreeOptions options{mode};
        tracers.push_back(std::make_unique<IntersectorTracer>(scene, reference_scene.triangles, options));
        names.push_back(intersector_name(options));
    }
    std::printf(
        "\n## f. The shipped scene in each mode: %s (%zu spheres, %zu quads), %zu primary and %zu incoherent rays, %d "
        "interleaved repetitions\n\n",
        shipped.source.c_str(), scene.spheres.size(), scene.quads.size(), sets[0].rays.size(), sets[1].rays.size(),
        repeats);
    // seconds[set][query][tracer]
    std::vector<std::vector<std::vector<std::vector<double>>>> seconds(
        sets.size(),
        std::vector<std::vector<std::vector<double>>>(2, std::vector<std::vector<double>>(tracers.size())));
    for (int r = -1; r < repeats; ++r) {
        for (std::size_t s = 0; s < sets.size(); ++s) {
            for (std::size_t k = 0; k < tracers.size(); ++k) {
                ClosestResult closest;
                std::vector<std::uint8_t> occluded;
                double closest_s = tracers[k]->closest(sets[s], closest), any_s = tracers[k]->any(sets[s], occluded);
                if (r < 0) continue;
                seconds[s][0][k].push_back(closest_s);
                seconds[s][1][k].push_back(any_s);
            }
        }
    }
    const char* queries[] = {"closest", "any"};
    json rows = json::array();
    std::printf("%-11s %-8s %-40s %12s %14s\n", "rays", "query", "tracer", "Mrays/s best", "Mrays/s median");
    for (std::size_t s = 0; s < sets.size(); ++s) {
        for (int q = 0; q < 2; ++q) {
            for (std::size_t k = 0; k < tracers.size(); ++k) {
                double count = double(sets[s].rays.size());
                double best = count / minimum(seconds[s][q][k]) / 1e6, med = count / median(seconds[s][q][k]) / 1e6;
                std::printf("%-11s %-8s %-40s %12.2f %14.2f\n", sets[s].name.c_str(), queries[q], names[k].c_str(),
                            best, med);
                rows.push_back({{"scene", shipped.source},
                                {"rays", sets[s].name},
                                {"query", queries[q]},
                                {"tracer", names[k]},
                                {"ray_count", sets[s].rays.size()},
                                {"repeats", repeats},
                                {"mrays_s_best", best},
                                {"mrays_s_median", med}});
            }
        }
    }
    return rows;
}

// The reference renderer with each intersector on 2 threads: samples/s and
// the pixels whose values differ (ties resolved otherwise).
json reference_figures(int size, int spp, int repeats) {
    json rows = json::array();
    std::printf(
        "\n## f. The reference with --intersector bvh and embree: %dx%d, %d spp, %u threads, %d interleaved "
        "repetitions\n\n",
        size, size, spp, kThreads, repeats);
    std::printf("%-14s %-12s %16s %10s %18s\n", "scene", "intersector", "Msamples/s min", "median", "pixels differing");
    for (const char* name : {"bunny", "cornell_mesh"}) {
        Scene scene = load_scene(std::string(WAVEPATH_SOURCE_DIR "/scenes/") + name + ".json");
        scene.camera.width = scene.camera.height = size;
        scene.render.spp = spp;
        const Intersector kinds[] = {Intersector::Bvh, Intersector::Embree};
        std::vector<double> samples_per_s[2];
        std::vector<float> image[2];
        for (int r = 0; r < repeats; ++r) {
            for (int k = 0; k < 2; ++k) {
                ReferenceOptions options{int(kThreads), false, false, kinds[k]};
                RenderResult result = render_reference(scene, options);
                samples_per_s[k].push_back(double(result.stats.samples) / result.stats.time_s);
                image[k] = result.image.rgb;
            }
        }
        std::size_t differing = 0;
        for (std::size_t i = 0; i < image[0].size(); i += 3)
            differing += !std::equal(image[0].begin() + i, image[0].begin() + i + 3, image[1].begin() + i);
        for (int k = 0; k < 2; ++k) {
            const char* intersector = k == 0 ? "bvh" : "embree";
            std::printf("%-14s %-12s %16.4f %10.4f %18zu\n", name, intersector, minimum(samples_per_s[k]) / 1e6,
                        median(samples_per_s[k]) / 1e6, differing);
            json row = frame_fields(size, spp, repeats, samples_per_s[k]);
            row.update({{"scene", name}, {"intersector", intersector}, {"pixels_differing", differing}});
            rows.push_back(row);
        }
    }
    return rows;
}

// ---- g. the wavefront with each intersector ----

// The host's and the kernel's seconds of a tracing stage in a profile (the host's 0 with the BVH).
struct StageSeconds {
    double host = 0.0, kernel = 0.0;
    std::uint64_t rays = 0;
};
StageSeconds stage_seconds(const RenderProfile& profile, Stage stage) {
    const StageDeclaration& declared = declaration(stage);
    const std::string host_row = host_trace_row(declared);
    StageSeconds s;
    for (const KernelProfile& k : profile.kernels) {
        if (k.name == host_row) s.host = k.device_s;
        if (k.name == declared.kernel) s.kernel = k.device_s, s.rays = k.items;
    }
    return s;
}

// The shipped mesh scenes (and the room, without meshes) rendered by the
// wavefront tracing with our BVH in the kernels and with Embree on the host:
// samples/s of unprofiled renders, interleaved; the tracing stages' rays/s
// from a profiled render of its own (the host's trace and the kernel's rest).
json wavefront_intersector_figures(const DeviceInfo& device, int size, int spp, int repeats) {
    const Intersector kinds[] = {Intersector::Bvh, Intersector::Embree};
    const char* names[] = {"bunny", "cornell_mesh", "room"};
    std::vector<Scene> scenes;
    for (const char* name : names) {
        Scene scene = load_scene(std::string(WAVEPATH_SOURCE_DIR "/scenes/") + name + ".json");
        scene.camera.width = scene.camera.height = size;
        scene.render.spp = spp;
        scenes.push_back(scene);
    }
    std::printf(
        "\n## g. The wavefront with each intersector: %dx%d, %d spp, %d interleaved repetitions (after one warm-up "
        "render each), default options but --intersector; the tracing stages from a profiled render of its own "
        "(intersect and shade apart)\n\n",
        size, size, spp, repeats);
    // [scene][intersector]
    std::vector<std::array<std::vector<double>, 2>> sps(scenes.size());
    std::vector<std::array<std::vector<StageSeconds>, 2>> closest(scenes.size()), any(scenes.size());
    for (int r = -1; r < repeats; ++r) {
        for (std::size_t k = 0; k < scenes.size(); ++k) {
            for (int i = 0; i < 2; ++i) {
                WavefrontOptions options;
                options.device = std::to_string(device.index);
                options.intersector = kinds[i];
                RenderStats plain = render_wavefront(scenes[k], options, Progress{}).stats;
                WavefrontReport report;
                render_wavefront(scenes[k], profiled_apart(options), Progress{}, &report);
                if (r < 0) continue;
                sps[k][i].push_back(double(plain.samples) / plain.time_s);
                closest[k][i].push_back(stage_seconds(report.profile, Stage::intersect));
                any[k][i].push_back(stage_seconds(report.profile, Stage::intersect_shadow));
            }
        }
    }
    auto rate = [](const std::vector<StageSeconds>& runs, bool host_only) {
        std::vector<double> per_s;
        for (const StageSeconds& s : runs) per_s.push_back(double(s.rays) / (host_only ? s.host : s.host + s.kernel));
        return per_s;
    };
    // No intersect_shadow launch: shade traced the shadow rays itself (our BVH on a CPU device, docs/architecture.md,
    // "Shadow rays"), so they have no time of their own.
    auto traced_in_shade = [](const std::vector<StageSeconds>& runs) {
        return std::all_of(runs.begin(), runs.end(), [](const StageSeconds& s) { return s.rays == 0; });
    };
    std::printf("%-13s %-12s %16s %10s %12s %22s %22s\n", "scene", "intersector", "Msamples/s min", "median",
                "of bvh (med)", "intersect Mrays/s", "shadow Mrays/s");
    json rows = json::array();
    for (std::size_t k = 0; k < scenes.size(); ++k) {
        for (int i = 0; i < 2; ++i) {
            double ratio = median(sps[k][i]) / median(sps[k][0]);
            std::vector<double> stage_closest = rate(closest[k][i], false), stage_any = rate(any[k][i], false);
            const bool shadow_in_shade = traced_in_shade(any[k][i]);
            char shadow[32] = "in shade";
            if (!shadow_in_shade) std::snprintf(shadow, sizeof shadow, "%.2f", median(stage_any) / 1e6);
            std::printf("%-13s %-12s %16.4f %10.4f %11.2fx %22.2f %22s\n", names[k], intersector_name(kinds[i]).c_str(),
                        minimum(sps[k][i]) / 1e6, median(sps[k][i]) / 1e6, ratio, median(stage_closest) / 1e6, shadow);
            json row = frame_fields(size, spp, repeats, sps[k][i]);
            row.update({{"scene", names[k]},
                        {"intersector", intersector_name(kinds[i])},
                        {"of_bvh_median", ratio},
                        {"intersect_mrays_s_median", median(stage_closest) / 1e6}});
            if (!shadow_in_shade) row["intersect_shadow_mrays_s_median"] = median(stage_any) / 1e6;
            if (kinds[i] == Intersector::Embree)
                row.update({{"intersect_host_mrays_s_median", median(rate(closest[k][i], true)) / 1e6},
                            {"intersect_shadow_host_mrays_s_median", median(rate(any[k][i], true)) / 1e6}});
            rows.push_back(row);
        }
    }
    return rows;
}

// ---- h. Packets of a pixel's samples (bench/results/analysis.md, "Where issue 21 stops") ----

// The hits of rays traced in `order` (hits[i] is ray order[i]'s) put back in the rays' own order.
ClosestResult unpermuted(const ClosestResult& hits, const std::vector<std::size_t>& order) {
    ClosestResult out = hits;
    for (std::size_t i = 0; i < order.size(); ++i) out.t[order[i]] = hits.t[i], out.tri[order[i]] = hits.tri[i];
    return out;
}

// The traced scene's camera rays, `spp` per pixel, each pixel's samples
// adjacent as Mitsuba's wavefront lays them out, and their diffuse bounces
// (reference/sample_rays.h), traced by Embree on its own triangles
// (rtcIntersect1 and rtcIntersect16, not robust, on kThreads threads): one ray
// at a time in that order, one at a time shuffled (as a queue of unrelated
// paths holds them), and in packets of 16 consecutive rays (a pixel's samples
// for camera rays; bounces only from samples that hit). Also the rays whose hit
// (triangle and t) differs from the one found one at a time in order: none
// shuffled, where a ray's hit is a function of the ray; in packets, those
// whose hit a packet's make-up would decide.
json pixel_packet_figures(Scene traced, int size, std::uint32_t spp, int repeats) {
    traced.camera.width = traced.camera.height = size;
    reference::ReferenceScene<float> scene(traced);
    reference::SampleRays rays = reference::sample_rays(scene, spp);
    EmbreeTracer embree(scene.triangles, false);
    std::printf(
        "\n## h. Packets of a pixel's samples: %dx%d, %u samples per pixel adjacent, Embree's own triangles on %u "
        "threads, %d interleaved repetitions\n\n",
        size, size, spp, kThreads, repeats);
    std::printf("%-8s %-22s %14s %14s %12s %14s\n", "rays", "traced", "Mrays/s best", "median", "of in order",
                "hits differ");
    json rows = json::array();
    for (auto [name, set] : {std::pair{"camera", &rays.camera}, std::pair{"bounce", &rays.bounce}}) {
        std::vector<std::size_t> order(set->size());
        std::iota(order.begin(), order.end(), std::size_t(0));
        std::shuffle(order.begin(), order.end(), std::mt19937(7));
        std::vector<Ray> shuffled;
        for (std::size_t i : order) shuffled.push_back((*set)[i]);
        const char* ways[] = {"one at a time, in order", "one at a time, shuffled", "packets of 16, in order"};
        std::vector<double> seconds[3];
        ClosestResult single, packets, shuffled_hits;
        for (int r = -1; r < repeats; ++r) {
            double s[3] = {embree.closest(*set, single), embree.closest(shuffled, shuffled_hits),
                           embree.closest_packets(*set, packets)};
            if (r >= 0)
                for (int w = 0; w < 3; ++w) seconds[w].push_back(s[w]);
        }
        const ClosestResult unshuffled = unpermuted(shuffled_hits, order);
        const ClosestResult* against_single[3] = {nullptr, &unshuffled, &packets};
        const double count = double(set->size());
        for (int w = 0; w < 3; ++w) {
            const double best = count / minimum(seconds[w]) / 1e6, med = count / median(seconds[w]) / 1e6;
            const double of_order = median(seconds[0]) / median(seconds[w]);
            json row = {{"rays", name},         {"traced", ways[w]},     {"count", set->size()},
                        {"mrays_s_best", best}, {"mrays_s_median", med}, {"of_in_order_median", of_order}};
            std::string differing = "-";  // the yardstick's own row
            if (against_single[w]) {
                const std::size_t n = set->size() - compare(*against_single[w], single).bit_identical;
                row["hits_differing_from_in_order"] = n;
                differing = std::to_string(n);
            }
            std::printf("%-8s %-22s %14.2f %14.2f %11.2fx %14s\n", name, ways[w], best, med, of_order,
                        differing.c_str());
            rows.push_back(row);
        }
    }
    return rows;
}

int run(int argc, char** argv) {
    bool quick = false;
    std::string json_path, scene_path = WAVEPATH_SOURCE_DIR "/scenes/bunny.json", device_choice, sections = "abcdef",
                           baseline_kernels;
    int repeats = 0;
    for (int i = 1; i < argc; ++i) {
        std::string a = argv[i];
        auto value = [&]() -> std::string {
            if (i + 1 >= argc) throw std::runtime_error(a + " needs a value");
            return argv[++i];
        };
        if (a == "--quick") {
            quick = true;
        } else if (a == "--json") {
            json_path = value();
        } else if (a == "--scene") {
            scene_path = value();
        } else if (a == "--device") {
            device_choice = value();
        } else if (a == "--repeats") {
            repeats = std::stoi(value());
        } else if (a == "--sections") {
            sections = value();
        } else if (a == "--baseline-kernels") {
            baseline_kernels = value();
        } else {
            std::cerr << "usage: mesh_bench [--quick] [--json FILE] [--scene FILE] [--device CHOICE] [--repeats N] "
                         "[--sections abcdefgh] [--baseline-kernels DIR]\n";
            return 2;
        }
    }
    if (repeats <= 0) repeats = quick ? 5 : 7;
    DeviceInfo device = choose_device(device_choice);
    json results;
    results["meta"] = run_metadata(device, quick);
    std::printf("mesh_bench (%s): commit %s, %s; %s, %u cores; OpenCL %s, device %s; Embree %s\n",
                quick ? "quick" : "full", results["meta"]["commit"].get<std::string>().c_str(),
                results["meta"]["date"].get<std::string>().c_str(), results["meta"]["cpu"].get<std::string>().c_str(),
                std::thread::hardware_concurrency(), device.platform_version.c_str(), device.name.c_str(),
                RTC_VERSION_STRING);

    Scene scene = load_scene(scene_path);
    Scene traced = triangles_only(scene);
    traced.camera.width = traced.camera.height = quick ? 128 : 512;
    std::vector<Mesh> meshes = mesh_sizes(traced.meshes[largest_mesh(traced)], quick);

    auto wanted = [&](char section) { return sections.find(section) != std::string::npos; };
    if (wanted('a')) results["build"] = build_figures(traced, meshes, 3);
    if (wanted('b')) {
        json agreement = json::array();
        results["traversal"] = traversal_figures(traced, device, repeats, baseline_kernels, agreement);
        results["agreement"] = agreement;
    }
    if (wanted('c'))
        results["render"] =
            quick ? render_figures(traced, meshes, 64, 1, 2) : render_figures(traced, meshes, 256, 4, 3);
    if (wanted('d')) results["lanes"] = quick ? lanes_figures(scene, 64, 1, 2) : lanes_figures(scene, 256, 4, 3);
    // e decides a design question and checks nothing: not in the quick run (its six builds would cost CI a minute)
    if (wanted('e') && !quick) results["short_list"] = short_list_figures(128, 4, 3);
    if (wanted('f')) {
        results["shipped_scene"] = shipped_scene_figures(scene, quick ? 128 : 512, repeats);
        results["reference"] = quick ? reference_figures(64, 1, 3) : reference_figures(128, 4, 5);
    }
    if (wanted('g'))
        results["wavefront"] = quick ? wavefront_intersector_figures(device, 64, 1, 3)
                                     : wavefront_intersector_figures(device, 256, 16, repeats);
    if (wanted('h'))
        results["pixel_packets"] =
            quick ? pixel_packet_figures(traced, 32, 16, 1) : pixel_packet_figures(traced, 128, 16, repeats);
    results["meta"]["load_average_end"] = load_average();
    if (!json_path.empty()) {
        std::ofstream out(json_path);
        out << results.dump(1) << "\n";
        if (!out) throw std::runtime_error("cannot write " + json_path);
    }
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    try {
        return run(argc, argv);
    } catch (const std::exception& e) {
        std::cerr << "mesh_bench: " << e.what() << "\n";
        return 1;
    }
}
