// The scene's rays traced with Embree on host threads: the CPU devices'
// alternative to our OpenCL BVH (kernels/shared/bvh.h), for the reference
// now and for the wavefront's intersect stages over mapped buffers later.
//
// What makes it ours and not Embree's: every hit it reports is one of our
// tests (the watertight triangle test of kernels/shared/triangle.h, the
// sphere, plane and quad tests of kernels/shared/geometry.h) run on the
// ray's own t_max, so its distance is bit for bit the one the BVH reports
// and the offsets computed from it stay conservative; Embree only decides
// which primitives are tested. The closest hit is the first in the order of
// hit_precedes among all that our tests report, a function of the ray alone:
// the same for one ray or a queue, any query kind, any thread count.
//
// Where it may differ from bvh_trace: at a tie (two shapes at the very same
// distance: a ray through an edge or vertex shared by triangles), which the
// BVH gives to the first it visits and this gives to the smaller shape id.
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
// (kernels/interface/scene_layout.h), triangles by their index in the BVH's
// leaf order; no hit: t = WP_INFINITY (FLT_MAX), shape = WP_NO_HIT.
struct HostHit {
    float t;
    std::uint32_t shape;
};

// The tie rule, the one order of hits along a ray: the nearer first and, at
// the same distance, the smaller shape id (spheres, then planes, quads and
// triangles, each kind by index). The reference's test order (spheres,
// planes, quads, each replacing the hit only when strictly closer, then the
// meshes) gives the same result for every tie but one between triangles.
constexpr bool hit_precedes(const HostHit& a, const HostHit& b) {
    return a.t < b.t || (a.t == b.t && a.shape < b.shape);
}

// What traces a renderer's rays: our BVH (kernels/shared/bvh.h, the OpenCL
// kernels' and the reference's) or this Embree intersector (float only).
// They differ only in which of two shapes at the very same distance a ray hits.
enum class Intersector { Bvh, Embree };

// How Embree meets our triangles (bench/mesh_bench.cpp measures both; both
// find exactly the same hits, tests/accel/embree_intersector_test.cpp).
enum class EmbreeTriangles {
    // User geometry: Embree's BVH over the triangles' boxes, our test in its
    // callback: every triangle whose box the ray enters is tested.
    User,
    // Embree's robust triangles, each enlarged a little (2^-18 of the
    // scene's largest coordinate beyond every edge), find the candidates; a
    // filter tests each with ours and keeps our verdict and distance. Embree's
    // test alone is not watertight at vertices (it can miss all the
    // triangles around one); enlarged, it offers every triangle ours hits. A
    // ray where the two tests disagree within its closest hit (a candidate
    // ours misses, or our hit exactly on an edge) is traced again as with
    // User, so that the answer is ours whatever Embree offered.
    Filter,
};

// How a queue is handed to Embree: one ray at a time (rtcIntersect1),
// packets of 4, 8 or 16 with a valid mask, or streams (rtcIntersect1M).
enum class EmbreeQuery { Single, Packet4, Packet8, Packet16, Stream };

// Spheres and quads: tested in turn before Embree runs (Loop), or as Embree
// user geometry beside the triangles (User). Planes, unbounded, are always
// tested in turn.
enum class EmbreeAnalytic { Loop, User };

struct EmbreeOptions {
    EmbreeTriangles triangles = EmbreeTriangles::User;
    EmbreeQuery query = EmbreeQuery::Single;
    EmbreeAnalytic analytic = EmbreeAnalytic::User;
    int threads = 0;  // host threads tracing a queue; 0: all hardware threads
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
    // `triangles` are the scene's mesh triangles in the BVH's leaf order
    // (accel/bvh_layout.h), so that a triangle's shape id is the same for
    // both intersectors. Throws std::runtime_error when Embree fails.
    EmbreeIntersector(const Scene& scene, std::vector<SharedMath<float>::MeshTriangle> triangles,
                      const EmbreeOptions& options = {});
    ~EmbreeIntersector();
    EmbreeIntersector(const EmbreeIntersector&) = delete;
    EmbreeIntersector& operator=(const EmbreeIntersector&) = delete;

    // One ray (the reference): the closest hit in (0, t_max), and whether any
    // shape lies in (0, t_max).
    HostHit closest(const SharedMath<float>::vec3& origin, const SharedMath<float>::vec3& direction, float t_max) const;
    bool occluded(const SharedMath<float>::vec3& origin, const SharedMath<float>::vec3& direction, float t_max) const;

    // A queue (the slots in `queue`) on the options' threads: each slot's
    // closest hit into `hits`, or into `occluded` 1 where any shape lies in
    // (0, t_max) and 0 elsewhere. Slots outside the queue are left alone.
    void closest(const RayArrays& rays, std::span<const std::uint32_t> queue, const HitArrays& hits) const;
    void occluded(const RayArrays& rays, std::span<const std::uint32_t> queue, std::uint32_t* occluded) const;

    const EmbreeOptions& options() const;

    // Rays EmbreeTriangles::Filter traced a second time on our test alone
    // (where Embree's test and ours split an edge differently), so far.
    std::uint64_t retraced_rays() const;

    struct Impl;

 private:
    std::unique_ptr<Impl> impl_;
};

// The options' short name, e.g. "user_packet16" or "filter_single_analytic_user"
// (their threads aside): the bench's and the tests' tracer names.
std::string options_name(const EmbreeOptions& options);

// What Embree's device reports of itself: version, the ISA its kernels were
// built for and are chosen among, and whether packets of 4, 8 and 16 and
// streams run natively, e.g. "Embree 3.13.5; ISA AVX512; native packets 4 8 16; streams".
std::string embree_device_summary();

}  // namespace wp
