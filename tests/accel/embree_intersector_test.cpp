// The Embree intersector (src/accel/embree_intersector.h): it finds exactly
// what testing every shape with our tests finds under the tie rule; it
// agrees with our BVH on the bunny's camera and bounce rays but for ties,
// which are counted and listed; its any-hit agrees everywhere; and no query
// kind, triangle mode or thread count changes a bit of its results.
#include "accel/embree_intersector.h"

#include <embree3/rtcore.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <numeric>
#include <random>

#include "reference/sample_rays.h"
#include "support/meshes.h"

namespace wp {
namespace {

using M = SharedMath<float>;
using vec3 = M::vec3;
using Ray = reference::Ray<float>;
using RefScene = reference::ReferenceScene<float>;

// Every option the intersector has, each of which must give the same bits.
std::vector<EmbreeOptions> every_option(int threads) {
    std::vector<EmbreeOptions> all;
    for (EmbreeTriangles triangles : {EmbreeTriangles::Filter, EmbreeTriangles::User})
        for (EmbreeQuery query : {EmbreeQuery::Single, EmbreeQuery::Packet4, EmbreeQuery::Packet8,
                                  EmbreeQuery::Packet16, EmbreeQuery::Stream})
            for (EmbreeAnalytic analytic : {EmbreeAnalytic::Loop, EmbreeAnalytic::User})
                all.push_back({triangles, query, analytic, threads});
    return all;
}

std::string describe(const EmbreeOptions& o) { return options_name(o) + ", " + std::to_string(o.threads) + " threads"; }

// Rays in the wavefront's layout, with a queue that visits the slots out of
// order and leaves every third slot out.
struct Queue {
    std::array<std::vector<float>, 3> origin, direction;
    std::vector<float> t_max;
    std::vector<std::uint32_t> slots;  // slots[i]: ray i's slot

    Queue(const std::vector<Ray>& rays, const std::vector<float>& limits) {
        std::size_t capacity = rays.size() + rays.size() / 2 + 1;
        for (int a = 0; a < 3; ++a) origin[a].assign(capacity, 0.0f), direction[a].assign(capacity, 0.0f);
        t_max.assign(capacity, 0.0f);
        std::vector<std::uint32_t> free(capacity);
        std::iota(free.begin(), free.end(), 0u);
        free.erase(std::remove_if(free.begin(), free.end(), [](std::uint32_t s) { return s % 3 == 1; }), free.end());
        std::shuffle(free.begin(), free.end(), std::mt19937(3));
        for (std::size_t i = 0; i < rays.size(); ++i) {
            std::uint32_t slot = free[i];
            slots.push_back(slot);
            for (int a = 0; a < 3; ++a) origin[a][slot] = rays[i].origin[a], direction[a][slot] = rays[i].direction[a];
            t_max[slot] = limits[i];
        }
    }
    RayArrays arrays() const {
        return {{origin[0].data(), origin[1].data(), origin[2].data()},
                {direction[0].data(), direction[1].data(), direction[2].data()},
                t_max.data()};
    }
};

struct QueueResults {
    std::vector<HostHit> closest;
    std::vector<std::uint32_t> occluded;
};

// The queue's closest hits on `limits` and its any-hits on `segments`, per ray;
// slots outside the queue must keep the values they had.
QueueResults trace_queue(const EmbreeIntersector& embree, const std::vector<Ray>& rays,
                         const std::vector<float>& limits, const std::vector<float>& segments) {
    Queue closest(rays, limits), any(rays, segments);
    const float kUntouched = -7.0f;
    std::vector<float> t(closest.t_max.size(), kUntouched);
    std::vector<std::uint32_t> shape(t.size(), 77u), occluded(t.size(), 5u);
    embree.closest(closest.arrays(), closest.slots, {t.data(), shape.data()});
    embree.occluded(any.arrays(), any.slots, occluded.data());
    QueueResults r;
    for (std::size_t i = 0; i < rays.size(); ++i) {
        r.closest.push_back({t[closest.slots[i]], shape[closest.slots[i]]});
        r.occluded.push_back(occluded[any.slots[i]]);
    }
    for (std::size_t s = 1; s < t.size(); s += 3) {
        EXPECT_EQ(t[s], kUntouched) << "slot " << s;
        EXPECT_EQ(occluded[s], 5u) << "slot " << s;
    }
    return r;
}

bool same(const HostHit& a, const HostHit& b) { return a.t == b.t && a.shape == b.shape; }

// Our test of one shape (by shape id) on the ray's own t_max.
float shape_t(const RefScene& scene, std::uint32_t shape, const Ray& ray, float t_max) {
    std::uint32_t i = shape & WP_SHAPE_INDEX_MASK;
    switch (shape >> WP_SHAPE_TYPE_SHIFT) {
        case WP_SHAPE_SPHERE:
            return M::intersect_sphere(scene.spheres[i].center, scene.spheres[i].radius, ray.origin, ray.direction,
                                       t_max);
        case WP_SHAPE_PLANE:
            return M::intersect_plane(scene.planes[i].point, scene.planes[i].normal, ray.origin, ray.direction, t_max);
        case WP_SHAPE_QUAD:
            return M::intersect_quad(scene.quads[i].corner, scene.quads[i].edge1, scene.quads[i].edge2, ray.origin,
                                     ray.direction, t_max);
        default:
            return M::mesh_triangle_t(&scene.triangles[i], M::triangle_ray(ray.direction), ray.origin, t_max);
    }
}

// Every shape tested on the ray's own t_max, the first in hit_precedes' order kept.
HostHit every_shape(const RefScene& scene, const Ray& ray, float t_max) {
    HostHit best{M::real_max, WP_NO_HIT};
    auto offer = [&](std::uint32_t kind, std::size_t count) {
        for (std::uint32_t i = 0; i < count; ++i) {
            std::uint32_t shape = kind << WP_SHAPE_TYPE_SHIFT | i;
            HostHit candidate{shape_t(scene, shape, ray, t_max), shape};
            if (candidate.t < t_max && hit_precedes(candidate, best)) best = candidate;
        }
    };
    offer(WP_SHAPE_SPHERE, scene.spheres.size());
    offer(WP_SHAPE_PLANE, scene.planes.size());
    offer(WP_SHAPE_QUAD, scene.quads.size());
    offer(WP_SHAPE_TRIANGLE, scene.triangles.size());
    return best;
}

HostHit as_host_hit(const reference::ShapeHit<float>& hit) {
    if (!hit.found()) return {M::real_max, WP_NO_HIT};
    return {hit.t, std::uint32_t(hit.shape) << WP_SHAPE_TYPE_SHIFT | std::uint32_t(hit.index)};
}

// A scene of every shape kind with ties built in: overlapping icospheres,
// one of them twice (every hit on it is a tie of two triangles), a sphere, a
// plane and quads.
Scene tie_scene() {
    Scene scene;
    std::mt19937 random(5);
    std::uniform_real_distribution<double> position(-3.0, 3.0), size(0.3, 1.5);
    for (int i = 0; i < 6; ++i)
        scene.meshes.push_back(test::transformed(test::icosphere(2, 0), size(random),
                                                 {position(random), position(random), position(random)}));
    scene.meshes.push_back(scene.meshes[2]);
    scene.meshes.push_back(test::transformed(test::unit_cube(0), 1.5, {-1.0, -4.0, 0.5}));
    scene.spheres.push_back({{1.0, 1.0, -1.0}, 1.2, 0});
    scene.planes.push_back({{0.0, -4.5, 0.0}, {0.0, 1.0, 0.0}, 0});
    scene.quads.push_back({{-2.0, 3.5, -2.0}, {4.0, 0.0, 0.0}, {0.0, 0.0, 4.0}, 0});
    scene.quads.push_back({{2.5, -2.0, -2.0}, {0.0, 4.0, 0.0}, {0.0, 0.0, 4.0}, 0});
    return scene;
}

// Random rays, and rays aimed exactly at vertices (the even ones: ties
// among the triangles around them); half of them bounded by a random t_max.
void tie_rays(const Scene& scene, int count, std::vector<Ray>& rays, std::vector<float>& limits) {
    std::mt19937 random(9);
    std::uniform_real_distribution<float> coordinate(-6.0f, 6.0f), limit(0.5f, 12.0f);
    for (int r = 0; r < count; ++r) {
        const Mesh& mesh = scene.meshes[r % scene.meshes.size()];
        vec3 origin(coordinate(random), coordinate(random), coordinate(random));
        vec3 target = r % 2 ? vec3(coordinate(random), coordinate(random), coordinate(random))
                            : vec3(mesh.positions[r % mesh.positions.size()]);
        rays.push_back({origin, glm::normalize(target - origin)});
        limits.push_back(r % 4 < 2 ? M::real_max : limit(random));
    }
}
bool aimed_at_vertex(std::size_t ray) { return ray % 2 == 0; }

// tie_scene(), its triangles in leaf order, and `count` tie_rays.
struct TieRays {
    Scene scene = tie_scene();
    RefScene reference{scene};
    std::vector<Ray> rays;
    std::vector<float> limits;
    explicit TieRays(int count) { tie_rays(scene, count, rays, limits); }
};

TEST(EmbreeIntersector, FindsWhatTestingEveryShapeFindsUnderTheTieRule) {
    TieRays tie(3000);
    const Scene& scene = tie.scene;
    const RefScene& reference = tie.reference;
    const std::vector<Ray>& rays = tie.rays;
    const std::vector<float>& limits = tie.limits;
    std::vector<HostHit> expected;
    std::size_t hits = 0, ties = 0;
    for (std::size_t i = 0; i < rays.size(); ++i) {
        expected.push_back(every_shape(reference, rays[i], limits[i]));
        hits += expected.back().shape != WP_NO_HIT;
        // a tie: another shape our tests put at the same distance
        for (std::uint32_t k = 0; k < reference.triangles.size() && expected.back().shape != WP_NO_HIT; ++k) {
            std::uint32_t shape = WP_SHAPE_TRIANGLE << WP_SHAPE_TYPE_SHIFT | k;
            if (shape != expected.back().shape && shape_t(reference, shape, rays[i], limits[i]) == expected.back().t) {
                ++ties;
                break;
            }
        }
    }
    for (const EmbreeOptions& options : every_option(2)) {
        SCOPED_TRACE(describe(options));
        EmbreeIntersector embree(scene, reference.triangles, options);
        QueueResults batch = trace_queue(embree, rays, limits, limits);
        for (std::size_t i = 0; i < rays.size(); ++i) {
            HostHit one = embree.closest(rays[i].origin, rays[i].direction, limits[i]);
            ASSERT_TRUE(same(one, expected[i])) << "ray " << i << ": " << one.t << " " << one.shape << ", expected "
                                                << expected[i].t << " " << expected[i].shape;
            ASSERT_TRUE(same(batch.closest[i], expected[i])) << "ray " << i;
            bool occluded = expected[i].shape != WP_NO_HIT;  // a hit lies in (0, t_max)
            ASSERT_EQ(embree.occluded(rays[i].origin, rays[i].direction, limits[i]), occluded) << "ray " << i;
            ASSERT_EQ(batch.occluded[i], occluded ? 1u : 0u) << "ray " << i;
        }
    }
    std::printf(
        "[figure] Embree intersector against every shape: %zu rays (half aimed at vertices), %zu hits, %zu ties, "
        "20 options, all identical\n",
        rays.size(), hits, ties);
    EXPECT_GT(ties, rays.size() / 10);  // the duplicated mesh and the vertices make ties to decide
    EXPECT_GT(hits, rays.size() / 3);
}

// Why EmbreeTriangles::Filter enlarges the triangles it hands Embree:
// Embree's robust triangle test is watertight along edges but not at
// vertices, where it can report none of the triangles around one (the ray
// passes through a closed mesh there), so no filter of its hits could find
// ours. On the triangles as they are, some rays aimed at vertices pass
// through; the Filter mode (enlarged) finds every hit ours finds. If the
// first count falls to 0, Embree has become watertight at vertices.
int embree_robust_misses(const TieRays& tie, std::size_t& vertex_hits) {
    RTCDevice device = rtcNewDevice(nullptr);
    RTCScene scene = rtcNewScene(device);
    rtcSetSceneFlags(scene, RTC_SCENE_FLAG_ROBUST);
    RTCGeometry geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    const std::vector<M::MeshTriangle>& triangles = tie.reference.triangles;
    auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                                 3 * sizeof(float), 3 * triangles.size()));
    auto* indices = static_cast<unsigned*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                                   3 * sizeof(unsigned), triangles.size()));
    for (std::size_t i = 0; i < triangles.size(); ++i) {
        std::copy(triangles[i].p0, triangles[i].p0 + 3, vertices + 9 * i);
        std::copy(triangles[i].p1, triangles[i].p1 + 3, vertices + 9 * i + 3);
        std::copy(triangles[i].p2, triangles[i].p2 + 3, vertices + 9 * i + 6);
        for (unsigned k = 0; k < 3; ++k) indices[3 * i + k] = unsigned(3 * i + k);
    }
    rtcCommitGeometry(geometry);
    rtcAttachGeometry(scene, geometry);
    rtcReleaseGeometry(geometry);
    rtcCommitScene(scene);
    Scene meshes_only = tie.scene;
    meshes_only.spheres.clear(), meshes_only.planes.clear(), meshes_only.quads.clear();
    EmbreeIntersector ours(meshes_only, triangles);
    int misses = 0;
    for (std::size_t i = 0; i < tie.rays.size(); i += 2) {  // the rays aimed at vertices
        const Ray& ray = tie.rays[i];
        HostHit hit = ours.closest(ray.origin, ray.direction, M::real_max);
        if (hit.shape == WP_NO_HIT) continue;
        ++vertex_hits;
        RTCIntersectContext context;
        rtcInitIntersectContext(&context);
        RTCRayHit rayhit{};
        rayhit.ray.org_x = ray.origin.x, rayhit.ray.org_y = ray.origin.y, rayhit.ray.org_z = ray.origin.z;
        rayhit.ray.dir_x = ray.direction.x, rayhit.ray.dir_y = ray.direction.y, rayhit.ray.dir_z = ray.direction.z;
        rayhit.ray.tfar = std::numeric_limits<float>::infinity(), rayhit.ray.mask = ~0u;
        rayhit.hit.geomID = RTC_INVALID_GEOMETRY_ID;
        rtcIntersect1(scene, &context, &rayhit);
        misses += rayhit.hit.geomID == RTC_INVALID_GEOMETRY_ID || rayhit.ray.tfar > hit.t * 1.001f;
    }
    rtcReleaseScene(scene);
    rtcReleaseDevice(device);
    return misses;
}

TEST(EmbreeIntersector, EmbreeRobustTrianglesMissSomeVerticesTheFilterModeDoesNot) {
    TieRays tie(40000);
    std::size_t vertex_hits = 0;
    int misses = embree_robust_misses(tie, vertex_hits);
    EmbreeIntersector filter(tie.scene, tie.reference.triangles, {EmbreeTriangles::Filter, EmbreeQuery::Single});
    EmbreeIntersector user(tie.scene, tie.reference.triangles, {EmbreeTriangles::User, EmbreeQuery::Single});
    for (std::size_t i = 0; i < tie.rays.size(); ++i) {
        const Ray& ray = tie.rays[i];
        ASSERT_TRUE(same(filter.closest(ray.origin, ray.direction, tie.limits[i]),
                         user.closest(ray.origin, ray.direction, tie.limits[i])))
            << "ray " << i;
    }
    std::printf(
        "[figure] Embree's robust triangles pass through %d of %zu vertices hit; the filter mode, on "
        "enlarged triangles, finds all (%llu of %zu rays traced again)\n",
        misses, vertex_hits, static_cast<unsigned long long>(filter.retraced_rays()), tie.rays.size());
    EXPECT_GT(misses, 0);
}

// ---- the bunny ----

// scenes/bunny.json with the camera on the bunny, 316 x 316 (about 1e5 camera
// rays, and as many bounces).
Scene bunny_close_up() {
    Scene scene = load_scene(WAVEPATH_SOURCE_DIR "/scenes/bunny.json");
    const Mesh& bunny = scene.meshes[1];  // the light is mesh 0
    glm::dvec3 lower(1e30), upper(-1e30);
    for (const glm::dvec3& p : bunny.positions) lower = glm::min(lower, p), upper = glm::max(upper, p);
    scene.camera.look_at = (lower + upper) / 2.0;
    scene.camera.fov_y_degrees = 24.0;
    scene.camera.width = scene.camera.height = 316;
    return scene;
}

struct BunnyRays {
    Scene scene = bunny_close_up();
    RefScene bvh{scene};
    reference::SampleRays rays = reference::sample_rays(bvh);
};

const BunnyRays& bunny_rays() {
    static const BunnyRays rays;
    return rays;
}

std::vector<float> unbounded(std::size_t n) { return std::vector<float>(n, M::real_max); }

// Any-hit probes just before and just after each ray's closest hit (10 where it has none).
std::vector<float> probes(const std::vector<HostHit>& closest, float factor) {
    std::vector<float> segments;
    for (const HostHit& h : closest) segments.push_back(h.shape == WP_NO_HIT ? 10.0f : h.t * factor);
    return segments;
}

TEST(EmbreeIntersector, AgreesWithTheBvhOnTheBunnyButForTies) {
    const BunnyRays& bunny = bunny_rays();
    const RefScene& bvh = bunny.bvh;
    for (EmbreeTriangles triangles : {EmbreeTriangles::Filter, EmbreeTriangles::User}) {
        EmbreeOptions options;
        options.triangles = triangles;
        EmbreeIntersector embree(bunny.scene, bvh.triangles, options);
        for (const auto& [name, rays] : {std::pair{"camera", &bunny.rays.camera}, {"bounce", &bunny.rays.bounce}}) {
            SCOPED_TRACE(std::string(name) + " rays, " + describe(options));
            std::vector<HostHit> expected;
            for (const Ray& ray : *rays) expected.push_back(as_host_hit(reference::closest_hit(bvh, ray)));
            std::vector<float> before = probes(expected, 0.99f), after = probes(expected, 1.01f);
            QueueResults found = trace_queue(embree, *rays, unbounded(rays->size()), before);
            QueueResults found_after = trace_queue(embree, *rays, unbounded(rays->size()), after);
            std::size_t hits = 0, ties = 0, bvh_occluded = 0;
            for (std::size_t i = 0; i < rays->size(); ++i) {
                const Ray& ray = (*rays)[i];
                const HostHit &e = expected[i], &f = found.closest[i];
                hits += e.shape != WP_NO_HIT;
                if (e.shape != f.shape) {
                    // A tie: both at the same distance by our tests, Embree's the smaller id.
                    ASSERT_EQ(f.t, e.t) << "ray " << i;
                    ASSERT_EQ(shape_t(bvh, e.shape, ray, M::real_max), f.t) << "ray " << i;
                    ASSERT_TRUE(hit_precedes(f, e)) << "ray " << i;
                    if (ties++ < 10)
                        std::printf("[figure] tie: %s ray %zu at t = %.9g: Embree shape %#x, BVH shape %#x\n", name, i,
                                    double(f.t), f.shape, e.shape);
                } else {
                    ASSERT_EQ(f.t, e.t) << "ray " << i;  // bit-identical distance
                }
                bool occluded_before = reference::occluded(bvh, ray, before[i]);
                bool occluded_after = reference::occluded(bvh, ray, after[i]);
                bvh_occluded += occluded_before + occluded_after;
                ASSERT_EQ(found.occluded[i], occluded_before ? 1u : 0u) << "ray " << i;
                ASSERT_EQ(found_after.occluded[i], occluded_after ? 1u : 0u) << "ray " << i;
            }
            std::printf(
                "[figure] Embree (%s) against the BVH, bunny %s rays: %zu rays, %zu hits, %zu ties, "
                "%zu any-hit probes occluded, all agreeing\n",
                describe(options).c_str(), name, rays->size(), hits, ties, bvh_occluded);
            EXPECT_GT(rays->size(), 90000u);
            EXPECT_GT(hits, rays->size() * 9 / 10);
            EXPECT_LT(ties, rays->size() / 1000);
            EXPECT_GT(bvh_occluded, hits / 2);  // the probes after the hit find it
        }
    }
}

// Threads, query kinds and triangle modes change no bit; one ray at a time neither.
TEST(EmbreeIntersector, SameResultsForAnyThreadCountQueryAndMode) {
    const BunnyRays& bunny = bunny_rays();
    std::vector<Ray> rays(bunny.rays.bounce.begin(), bunny.rays.bounce.begin() + 20000);
    rays.insert(rays.end(), bunny.rays.camera.begin(), bunny.rays.camera.begin() + 20000);
    std::vector<float> limits = unbounded(rays.size());
    EmbreeIntersector first(bunny.scene, bunny.bvh.triangles, EmbreeOptions{});
    std::vector<float> segments = probes(trace_queue(first, rays, limits, limits).closest, 1.01f);
    QueueResults expected = trace_queue(first, rays, limits, segments);
    for (int threads : {1, 3}) {
        for (const EmbreeOptions& options : every_option(threads)) {
            SCOPED_TRACE(describe(options));
            EmbreeIntersector embree(bunny.scene, bunny.bvh.triangles, options);
            QueueResults found = trace_queue(embree, rays, limits, segments);
            for (std::size_t i = 0; i < rays.size(); ++i) {
                ASSERT_TRUE(same(found.closest[i], expected.closest[i])) << "ray " << i;
                ASSERT_EQ(found.occluded[i], expected.occluded[i]) << "ray " << i;
            }
            if (options.query != EmbreeQuery::Single || threads != 1) continue;
            for (std::size_t i = 0; i < rays.size(); i += 7)
                ASSERT_TRUE(same(embree.closest(rays[i].origin, rays[i].direction, M::real_max), expected.closest[i]))
                    << "ray " << i;
        }
    }
}

// A ray that is not finite, or whose t_max is not positive, hits nothing;
// an empty queue does nothing.
TEST(EmbreeIntersector, UntraceableRaysAndEmptyQueues) {
    Scene scene = tie_scene();
    RefScene reference(scene);
    EmbreeIntersector embree(scene, reference.triangles);
    const float nan = std::numeric_limits<float>::quiet_NaN();
    HostHit none = embree.closest(vec3(nan, 0.0f, 0.0f), vec3(0.0f, -1.0f, 0.0f), M::real_max);
    EXPECT_EQ(none.shape, WP_NO_HIT);
    EXPECT_EQ(none.t, M::real_max);
    EXPECT_FALSE(embree.occluded(vec3(0.0f), vec3(0.0f, 1.0f, 0.0f), 0.0f));
    EXPECT_FALSE(embree.occluded(vec3(0.0f), vec3(0.0f, 1.0f, 0.0f), nan));
    embree.closest(RayArrays{}, {}, HitArrays{});
    embree.occluded(RayArrays{}, {}, nullptr);
}

}  // namespace
}  // namespace wp
