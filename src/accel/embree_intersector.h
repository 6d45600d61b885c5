// The scene's rays traced with Embree on host threads: the CPU devices'
// alternative to our OpenCL BVH (kernels/shared/bvh.h), for the reference
// and behind the wavefront's intersect stages (wavefront/host_trace.h).
//
// What makes it ours and not Embree's: every distance it reports is one of
// our tests (the watertight triangle test of kernels/shared/triangle.h, the
// sphere, plane and quad tests of kernels/shared/geometry.h) run on the
// ray's own t_max, bit for bit what bvh_trace reports for that shape, so
// the offsets computed from it stay conservative. Embree decides which shape
// a ray meets (EmbreeMode). Every result is a function of the ray alone: the
// same for one ray or a queue, any thread count, any run (Embree's build is
// deterministic, tests/accel/embree_intersector_test.cpp).
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "core/shared_math.h"
#include "scene/scene.h"

namespace wp {

namespace device_layout {  // as opencl/scene_upload.h: the shape ids' WP_SHAPE_* and WP_NO_HIT
using uint = std::uint32_t;
#include "interface/scene_layout.h"
}  // namespace device_layout

// A hit: its distance and WP_SHAPE_* << WP_SHAPE_TYPE_SHIFT | index
// (kernels/interface/scene_layout.h), triangles by their index in the
// intersector's list; no hit: t = WP_INFINITY (FLT_MAX), shape = WP_NO_HIT.
struct HostHit {
    float t;
    std::uint32_t shape;
};

// The exact order of hits along a ray: the nearer first and, at the same
// distance, the smaller shape id (spheres, then planes, quads and
// triangles, each kind by index). EmbreeMode::Exact returns the first hit
// in this order; the reference's BVH, testing spheres, planes and quads in
// turn (each replacing the hit only when strictly closer) before the
// meshes, returns the same for every tie but one between two triangles.
constexpr bool hit_precedes(const HostHit& a, const HostHit& b) {
    return a.t < b.t || (a.t == b.t && a.shape < b.shape);
}

// What traces a renderer's rays: our BVH (kernels/shared/bvh.h, the OpenCL
// kernels' and the reference's) or this Embree intersector (float only).
enum class Intersector { Bvh, Embree };

// Who decides which shape a ray meets.
enum class EmbreeMode {
    // Embree, the default: its robust triangles hold the mesh triangles and
    // the quads (two triangles each), each enlarged beyond every edge by
    // 2^-18 of the scene's largest coordinate, so that wherever our test
    // hits a shape, Embree's test hits the enlarged one. Closest hit: one
    // rtcIntersect1, no callback, finds the nearest enlarged shape and our
    // test recomputes its distance; where ours misses it (the ray passed
    // through the margin alone, about 1 ray in 1000 on the bunny) the ray is
    // traced again Exact. Spheres and planes are tested in turn first.
    // Any hit: rtcOccluded1, our test run on each shape Embree offers (a
    // filter: a shadow ray that reaches its light meets none).
    //
    // The tie rule: the closest hit is the first in hit_precedes' order
    // among the spheres and planes and the one shape Embree found. Embree
    // finds the shape nearest by its own distance, so where two triangles
    // or quads lie within Embree's rounding of each other along the ray (a
    // shared edge or vertex, touching or coincident surfaces: a near tie),
    // Embree's choice stands, although our test may put the other one a few
    // float steps nearer. Its choice is a function of the ray (its
    // traversal visits one deterministic tree in an order set by the ray).
    Verified,
    // Our test as Embree user geometry for every triangle whose box the ray
    // enters (quads, spheres and planes tested in turn): exactly the first
    // hit in hit_precedes' order. Verified's fallback and the tests'
    // yardstick; about half as fast (bench/results/embree_intersector.md).
    Exact,
};

struct EmbreeOptions {
    EmbreeMode mode = EmbreeMode::Verified;
    int threads = 0;  // host threads building the scene and tracing a queue; 0: all hardware threads
};

// A queue's rays as the wavefront keeps its path state: one float array per
// component, each indexed by slot.
struct RayArrays {
    std::array<const float*, 3> origin{}, direction{};  // directions of unit length
    const float* t_max = nullptr;                       // nullptr: WP_INFINITY for every ray
};

// Where a queue's closest hits go, indexed by slot as the rays.
struct HitArrays {
    float* t = nullptr;
    std::uint32_t* shape = nullptr;
};

class EmbreeIntersector {
 public:
    // `triangles` are the scene's mesh triangles in the order the renderer
    // keeps them (accel/bvh_layout.h, mesh_layout: without a BVH the
    // scene's), a triangle's shape id its index there. Embree's tree, and so
    // its choice at a near tie, depends on that order. Throws
    // std::runtime_error when Embree fails.
    EmbreeIntersector(const Scene& scene, std::vector<SharedMath<float>::MeshTriangle> triangles,
                      const EmbreeOptions& options = {});
    ~EmbreeIntersector();
    EmbreeIntersector(const EmbreeIntersector&) = delete;
    EmbreeIntersector& operator=(const EmbreeIntersector&) = delete;

    // One ray, on the calling thread (the reference's): the closest hit in
    // (0, t_max), and whether any shape lies in (0, t_max).
    HostHit closest(const SharedMath<float>::vec3& origin, const SharedMath<float>::vec3& direction, float t_max) const;
    bool occluded(const SharedMath<float>::vec3& origin, const SharedMath<float>::vec3& direction, float t_max) const;

    // A queue (the slots in `queue`) on the options' threads, one ray at a
    // time: each slot's closest hit into `hits`, or into `occluded` 1 where
    // any shape lies in (0, t_max) and 0 elsewhere. Slots outside the queue
    // are left alone. One queue at a time: concurrent calls wait their turn.
    void closest(const RayArrays& rays, std::span<const std::uint32_t> queue, const HitArrays& hits) const;
    void occluded(const RayArrays& rays, std::span<const std::uint32_t> queue, std::uint32_t* occluded) const;

    const EmbreeOptions& options() const;

    // The triangles it was given, as their bytes: the layout of
    // SharedMath<float>::MeshTriangle, in their order. They stay where they
    // are for its life, so a device buffer on a CPU can use them in place
    // (wavefront/pipeline.cpp).
    std::span<const std::byte> triangle_bytes() const;

    // Closest-hit rays EmbreeMode::Verified traced again Exact (our test
    // missed the shape Embree found), so far.
    std::uint64_t retraced_rays() const;

    struct Impl;

 private:
    std::unique_ptr<Impl> impl_;
};

// "verified" or "exact": the bench's and the tests' names of the modes.
std::string mode_name(EmbreeMode mode);

// What Embree's device reports of itself: version, the ISA its kernels were
// built for and are chosen among, and whether packets of 4, 8 and 16 and
// streams run natively, e.g. "Embree 3.13.5; ISA AVX512; native packets 4 8 16; streams".
std::string embree_device_summary();

}  // namespace wp
