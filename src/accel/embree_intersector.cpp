#include "accel/embree_intersector.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <glm/geometric.hpp>
#include <limits>
#include <stdexcept>
#include <thread>

namespace wp {

namespace {

using M = SharedMath<float>;
using vec3 = M::vec3;

constexpr float kInfinity = std::numeric_limits<float>::infinity();
constexpr HostHit kNoHit{M::real_max, WP_NO_HIT};

std::uint32_t shape_id(std::uint32_t kind, std::uint32_t index) { return kind << WP_SHAPE_TYPE_SHIFT | index; }

// What the tests and callbacks need of one ray, found through the Embree
// ray's id (its index among the rays of one query).
struct Lane {
    vec3 origin, direction;
    M::TriangleRay triangle_ray;  // the triangle test's shear, once per ray
    float t_max;                  // the ray's own: every test runs on it, so no hit depends on what was found before
    float search_slack;           // search_limit's absolute part, the scene's
    bool traceable;               // finite, with a positive t_max: handed to Embree
    HostHit best;                 // closest so far
    bool occluded;
    // EmbreeTriangles::Filter: where Embree's watertight test and ours
    // share a point between triangles differently, Embree may not offer the
    // triangle ours hits; such rays are traced again on our test alone.
    bool best_on_edge;  // ours puts the closest hit exactly on an edge or vertex (another triangle's too)
    float disputed_t;   // the nearest Embree hit our test misses (infinity: none)
};

Lane make_lane(const RayArrays& rays, std::uint32_t slot, float search_slack) {
    Lane lane;
    lane.search_slack = search_slack;
    lane.origin = vec3(rays.origin[0][slot], rays.origin[1][slot], rays.origin[2][slot]);
    lane.direction = vec3(rays.direction[0][slot], rays.direction[1][slot], rays.direction[2][slot]);
    lane.t_max = rays.t_max ? std::min(rays.t_max[slot], M::real_max) : M::real_max;
    lane.triangle_ray = M::triangle_ray(lane.direction);
    lane.traceable = M::vec3_is_finite(lane.origin) && M::vec3_is_finite(lane.direction) && lane.t_max > 0.0f;
    lane.best = kNoHit;
    lane.occluded = false;
    lane.best_on_edge = false;
    lane.disputed_t = kInfinity;
    return lane;
}

Lane make_lane(const vec3& origin, const vec3& direction, float t_max, float search_slack) {
    std::array<const float*, 3> o{&origin.x, &origin.y, &origin.z}, d{&direction.x, &direction.y, &direction.z};
    return make_lane(RayArrays{o, d, &t_max}, 0, search_slack);
}

// `candidate` becomes the lane's closest hit if it is a hit and precedes the closest so far.
bool offer(Lane& lane, const HostHit& candidate) {
    if (!(candidate.t < lane.t_max) || !hit_precedes(candidate, lane.best)) return false;
    lane.best = candidate;
    lane.best_on_edge = false;
    return true;
}

// Embree's t_far for a ray whose search ends at t: a little beyond t, so
// that a shape our test puts at t (a tie) or just before it is still
// tested although Embree's rounding puts its box (or its own distance to a
// triangle) farther: 2^-10 of t, far above both roundings, also for rays
// grazing a surface, plus the scene's search_slack for short rays, whose
// distances both compute with errors of the coordinates' size.
float search_limit(const Lane& lane, float t) { return t * (1.0f + 0x1p-10f) + lane.search_slack; }

// ---- the shapes, each with our test ----

// A box a little larger than the shape, so that no hit our test reports
// (rounded) lies outside it: wider than the shape by 2^-16 of its magnitude.
RTCBounds widened_box(const vec3& lower, const vec3& upper) {
    float margin = 0x1p-16f * std::max(M::max_abs(lower), M::max_abs(upper));
    auto below = [margin](float x) { return std::nextafter(x - margin, -kInfinity); };
    auto above = [margin](float x) { return std::nextafter(x + margin, kInfinity); };
    return {below(lower.x), below(lower.y), below(lower.z), 0.0f, above(upper.x), above(upper.y), above(upper.z), 0.0f};
}

struct SphereShape {
    static constexpr std::uint32_t kind = WP_SHAPE_SPHERE;
    vec3 center;
    float radius;
    float t(const Lane& ray) const { return M::intersect_sphere(center, radius, ray.origin, ray.direction, ray.t_max); }
    RTCBounds box() const { return widened_box(center - radius, center + radius); }
};

struct PlaneShape {
    static constexpr std::uint32_t kind = WP_SHAPE_PLANE;
    vec3 point, normal;
    float t(const Lane& ray) const { return M::intersect_plane(point, normal, ray.origin, ray.direction, ray.t_max); }
};

struct QuadShape {
    static constexpr std::uint32_t kind = WP_SHAPE_QUAD;
    vec3 corner, edge1, edge2;
    M::QuadPlane plane;  // quad_plane(edge1, edge2), once
    float t(const Lane& ray) const {
        return M::intersect_quad_plane(corner, edge1, edge2, plane, ray.origin, ray.direction, ray.t_max);
    }
    RTCBounds box() const {
        vec3 far = corner + edge1 + edge2, a = corner + edge1, b = corner + edge2;
        return widened_box(glm::min(glm::min(corner, far), glm::min(a, b)),
                           glm::max(glm::max(corner, far), glm::max(a, b)));
    }
};

struct TriangleShape {
    static constexpr std::uint32_t kind = WP_SHAPE_TRIANGLE;
    M::MeshTriangle triangle;
    float t(const Lane& ray) const { return M::mesh_triangle_t(&triangle, ray.triangle_ray, ray.origin, ray.t_max); }
    M::TriangleEdges edges(const Lane& ray) const {
        return M::ray_triangle_edges(ray.triangle_ray, M::triangle_vertex(triangle.p0), M::triangle_vertex(triangle.p1),
                                     M::triangle_vertex(triangle.p2), ray.origin);
    }
    RTCBounds box() const {
        vec3 p0 = M::triangle_vertex(triangle.p0), p1 = M::triangle_vertex(triangle.p1),
             p2 = M::triangle_vertex(triangle.p2);
        return widened_box(glm::min(p0, glm::min(p1, p2)), glm::max(p0, glm::max(p1, p2)));
    }
};

// The shapes as the reference and the kernels convert them to float.
struct AnalyticShapes {
    std::vector<SphereShape> spheres;
    std::vector<PlaneShape> planes;
    std::vector<QuadShape> quads;

    explicit AnalyticShapes(const Scene& scene) {
        for (const Sphere& s : scene.spheres) spheres.push_back({vec3(s.center), float(s.radius)});
        for (const Plane& p : scene.planes) planes.push_back({vec3(p.point), vec3(p.normal)});
        for (const Quad& q : scene.quads)
            quads.push_back(
                {vec3(q.corner), vec3(q.edge1), vec3(q.edge2), M::quad_plane(vec3(q.edge1), vec3(q.edge2))});
    }
};

template <class Shape>
void offer_each(const std::vector<Shape>& shapes, Lane& lane) {
    for (std::uint32_t i = 0; i < shapes.size(); ++i) offer(lane, {shapes[i].t(lane), shape_id(Shape::kind, i)});
}

template <class Shape>
bool any_of(const std::vector<Shape>& shapes, const Lane& lane) {
    return std::any_of(shapes.begin(), shapes.end(), [&](const Shape& s) { return s.t(lane) < lane.t_max; });
}

// ---- Embree's callbacks ----

// The intersect context Embree hands to the callbacks, with the query's lanes after it.
struct QueryContext {
    RTCIntersectContext embree;  // first: callbacks get a pointer to it
    Lane* lanes;

    explicit QueryContext(Lane* l) : lanes(l) { rtcInitIntersectContext(&embree); }
    static Lane& lane(const RTCIntersectContext* context, RTCRayN* ray, unsigned n, unsigned i) {
        return reinterpret_cast<const QueryContext*>(context)->lanes[RTCRayN_id(ray, n, i)];
    }
};

// User geometry: one primitive of Embree's a shape of ours.
template <class Shape>
struct ShapeList {
    const std::vector<Shape>* shapes;
    unsigned count() const { return unsigned(shapes->size()); }
    bool offer_hits(Lane& lane, unsigned primitive) const {
        return offer(lane, {(*shapes)[primitive].t(lane), shape_id(Shape::kind, primitive)});
    }
    bool hits(const Lane& lane, unsigned primitive) const { return (*shapes)[primitive].t(lane) < lane.t_max; }
    RTCBounds box(unsigned primitive) const { return (*shapes)[primitive].box(); }
};

// Our tests of one primitive for each valid ray.
template <class Primitives>
void user_intersect(const RTCIntersectFunctionNArguments* args) {
    const auto& primitives = *static_cast<const Primitives*>(args->geometryUserPtr);
    RTCRayN* ray = RTCRayHitN_RayN(args->rayhit, args->N);
    RTCHitN* hit = RTCRayHitN_HitN(args->rayhit, args->N);
    for (unsigned i = 0; i < args->N; ++i) {
        if (!args->valid[i]) continue;
        Lane& lane = QueryContext::lane(args->context, ray, args->N, i);
        if (!primitives.offer_hits(lane, args->primID)) continue;
        RTCRayN_tfar(ray, args->N, i) = search_limit(lane, lane.best.t);
        RTCHitN_geomID(hit, args->N, i) = args->geomID;
        RTCHitN_primID(hit, args->N, i) = args->primID;
    }
}

template <class Primitives>
void user_occluded(const RTCOccludedFunctionNArguments* args) {
    const auto& primitives = *static_cast<const Primitives*>(args->geometryUserPtr);
    for (unsigned i = 0; i < args->N; ++i) {
        if (!args->valid[i]) continue;
        Lane& lane = QueryContext::lane(args->context, args->ray, args->N, i);
        if (!primitives.hits(lane, args->primID)) continue;
        lane.occluded = true;
        RTCRayN_tfar(args->ray, args->N, i) = -kInfinity;  // Embree's mark of an occluded ray
    }
}

template <class Primitives>
void user_bounds(const RTCBoundsFunctionArguments* args) {
    *args->bounds_o = static_cast<const Primitives*>(args->geometryUserPtr)->box(args->primID);
}

// Embree's own triangles: each hit its test finds is our test's to accept,
// at our distance; Embree then searches on to a little beyond it. A hit ours
// misses is disputed (ours gives that point to a neighbour, which Embree may
// then not offer), and a hit ours puts exactly on an edge may have a
// neighbour ours puts first: either sends the ray to be traced again on our
// test alone (EmbreeIntersector::Impl::settle).
void triangle_filter(const RTCFilterFunctionNArguments* args) {
    const auto* triangles = static_cast<const TriangleShape*>(args->geometryUserPtr);
    for (unsigned i = 0; i < args->N; ++i) {
        if (!args->valid[i]) continue;
        Lane& lane = QueryContext::lane(args->context, args->ray, args->N, i);
        std::uint32_t index = RTCHitN_primID(args->hit, args->N, i);
        M::TriangleEdges e = triangles[index].edges(lane);
        float t = M::triangle_distance(e, lane.t_max);
        if (!(t < lane.t_max)) lane.disputed_t = std::min(lane.disputed_t, RTCRayN_tfar(args->ray, args->N, i));
        if (offer(lane, {t, shape_id(WP_SHAPE_TRIANGLE, index)})) {
            lane.best_on_edge = e.e0 == 0.0f || e.e1 == 0.0f || e.e2 == 0.0f;
            RTCRayN_tfar(args->ray, args->N, i) = search_limit(lane, lane.best.t);
        } else {
            args->valid[i] = 0;
        }
    }
}

void triangle_occlusion_filter(const RTCFilterFunctionNArguments* args) {
    const auto* triangles = static_cast<const TriangleShape*>(args->geometryUserPtr);
    for (unsigned i = 0; i < args->N; ++i) {
        if (!args->valid[i]) continue;
        Lane& lane = QueryContext::lane(args->context, args->ray, args->N, i);
        if (triangles[RTCHitN_primID(args->hit, args->N, i)].t(lane) < lane.t_max) {
            lane.occluded = true;
        } else {
            lane.disputed_t = std::min(lane.disputed_t, RTCRayN_tfar(args->ray, args->N, i));
            args->valid[i] = 0;
        }
    }
}

// EmbreeTriangles::Filter hands Embree each triangle enlarged so that every
// edge lies `margin` farther out (scaled about its incenter by 1 + margin /
// inradius, at most doubled, then rounded outward): Embree's robust test,
// which decides the points near an edge or vertex otherwise than ours and
// can miss all the triangles around a vertex, then offers every triangle
// ours hits (and some it does not, which the filter rejects and which send
// the ray to be traced again). The margin, 2^-18 of the scene's largest
// coordinate (64 of its float steps), is many times both tests' rounding;
// it shrinks only as seen by a ray grazing the surface.
constexpr double kEnlargement = 0x1p-18;

std::array<vec3, 3> enlarged(const M::MeshTriangle& t, double margin) {
    std::array<glm::dvec3, 3> p;
    for (int a = 0; a < 3; ++a) p[0][a] = t.p0[a], p[1][a] = t.p1[a], p[2][a] = t.p2[a];
    double a = glm::length(p[1] - p[2]), b = glm::length(p[2] - p[0]), c = glm::length(p[0] - p[1]);
    double perimeter = a + b + c;
    double inradius = glm::length(glm::cross(p[1] - p[0], p[2] - p[0])) / perimeter;
    if (!(inradius > 0.0)) return {vec3(p[0]), vec3(p[1]), vec3(p[2])};  // no area: our test never hits it
    glm::dvec3 incenter = (a * p[0] + b * p[1] + c * p[2]) / perimeter;
    double scale = std::min(1.0 + margin / inradius, 2.0);
    std::array<vec3, 3> out;
    for (int v = 0; v < 3; ++v) {
        glm::dvec3 q = incenter + (p[v] - incenter) * scale;
        for (int k = 0; k < 3; ++k) {
            float f = static_cast<float>(q[k]);
            bool inward = q[k] > incenter[k] ? double(f) < q[k] : double(f) > q[k];
            out[v][k] = inward ? std::nextafter(f, q[k] > incenter[k] ? kInfinity : -kInfinity) : f;
        }
    }
    return out;
}

// ---- queries ----

void set_ray(RTCRay& ray, const Lane& lane, float t_far, unsigned id) {
    ray.org_x = lane.origin.x, ray.org_y = lane.origin.y, ray.org_z = lane.origin.z;
    ray.dir_x = lane.direction.x, ray.dir_y = lane.direction.y, ray.dir_z = lane.direction.z;
    ray.tnear = 0.0f, ray.tfar = t_far, ray.time = 0.0f;
    ray.mask = ~0u, ray.id = id, ray.flags = 0;
}

template <class RayK>
void set_ray(RayK& ray, int k, const Lane& lane, float t_far) {
    ray.org_x[k] = lane.origin.x, ray.org_y[k] = lane.origin.y, ray.org_z[k] = lane.origin.z;
    ray.dir_x[k] = lane.direction.x, ray.dir_y[k] = lane.direction.y, ray.dir_z[k] = lane.direction.z;
    ray.tnear[k] = 0.0f, ray.tfar[k] = t_far, ray.time[k] = 0.0f;
    ray.mask[k] = ~0u, ray.id[k] = unsigned(k), ray.flags[k] = 0;
}

// Embree's packet types and functions for packets of K.
template <int K, class RayHitK, class RayK, void (*intersect_k)(const int*, RTCScene, RTCIntersectContext*, RayHitK*),
          void (*occluded_k)(const int*, RTCScene, RTCIntersectContext*, RayK*)>
struct Packet {
    static constexpr int size = K;
    using RayHit = RayHitK;
    using Ray = RayK;
    static constexpr auto intersect = intersect_k;
    static constexpr auto occluded = occluded_k;
};
using Packet4 = Packet<4, RTCRayHit4, RTCRay4, rtcIntersect4, rtcOccluded4>;
using Packet8 = Packet<8, RTCRayHit8, RTCRay8, rtcIntersect8, rtcOccluded8>;
using Packet16 = Packet<16, RTCRayHit16, RTCRay16, rtcIntersect16, rtcOccluded16>;

// Rays per stream call: the lanes of a stream stay in the first-level cache.
constexpr std::size_t kStreamSize = 64;

// The queue in parts, one per thread: static ranges, whole packets and
// streams each (every ray's result depends on that ray alone, so how the
// queue is cut changes nothing but the time).
template <class Work>
void for_each_part(std::size_t count, int threads, const Work& work) {
    constexpr std::size_t kGrain = kStreamSize;
    std::size_t grains = (count + kGrain - 1) / kGrain;
    std::size_t parts = std::clamp<std::size_t>(threads, 1, std::max<std::size_t>(grains, 1));
    auto range = [&](std::size_t p) { return std::min(count, grains * p / parts * kGrain); };
    std::vector<std::thread> workers;
    for (std::size_t p = 1; p < parts; ++p) workers.emplace_back([&, p] { work(range(p), range(p + 1)); });
    work(range(0), range(1));
    for (std::thread& w : workers) w.join();
}

std::string embree_error(RTCDevice device, const std::string& what) {
    return "Embree: " + what + " failed (error " + std::to_string(int(rtcGetDeviceError(device))) + ")";
}

}  // namespace

struct EmbreeIntersector::Impl {
    EmbreeOptions options;
    AnalyticShapes shapes;
    std::vector<TriangleShape> triangles;
    // What the user geometries' callbacks read (their user data).
    ShapeList<SphereShape> sphere_list{&shapes.spheres};
    ShapeList<QuadShape> quad_list{&shapes.quads};
    ShapeList<TriangleShape> triangle_list{&triangles};
    RTCDevice device = nullptr;
    RTCScene scene = nullptr;  // what the queries trace
    RTCScene exact =
        nullptr;  // triangles as user geometry: `scene` itself, or with Filter the rays settle() sends back
    bool has_geometry = false;  // anything in Embree's scenes
    float search_slack = 0.0f;  // 2^-16 of the largest coordinate: Lane::search_slack
    mutable std::atomic<std::uint64_t> retraced{0};

    Impl(const Scene& source, std::vector<M::MeshTriangle> mesh_triangles, const EmbreeOptions& o)
        : options(o), shapes(source) {
        if (options.threads <= 0) options.threads = std::max(1, int(std::thread::hardware_concurrency()));
        triangles.reserve(mesh_triangles.size());
        for (const M::MeshTriangle& t : mesh_triangles) triangles.push_back({t});
        search_slack = float(0x1p-16 * coordinate_magnitude());
        device = rtcNewDevice(nullptr);
        if (!device) throw std::runtime_error("Embree: cannot create a device");
        try {
            scene = build_scene(options.triangles);
            exact = options.triangles == EmbreeTriangles::User ? scene : build_scene(EmbreeTriangles::User);
        } catch (...) {
            release();
            throw;
        }
    }
    ~Impl() { release(); }

    void release() {
        if (exact && exact != scene) rtcReleaseScene(exact);
        if (scene) rtcReleaseScene(scene);
        if (device) rtcReleaseDevice(device);
        exact = scene = nullptr, device = nullptr;
    }

    RTCScene build_scene(EmbreeTriangles mode) {
        RTCScene built = rtcNewScene(device);
        // Robust: box tests (and Embree's own triangle test) that never lose
        // a hit to rounding, which the tie rule and watertightness need.
        rtcSetSceneFlags(built, RTC_SCENE_FLAG_ROBUST);
        rtcSetSceneBuildQuality(built, RTC_BUILD_QUALITY_MEDIUM);
        if (!triangles.empty()) {
            if (mode == EmbreeTriangles::Filter)
                attach_native_triangles(built);
            else
                attach_user(built, triangle_list, WP_SHAPE_TRIANGLE);
        }
        if (options.analytic == EmbreeAnalytic::User) {
            attach_user(built, sphere_list, WP_SHAPE_SPHERE);
            attach_user(built, quad_list, WP_SHAPE_QUAD);
        }
        rtcCommitScene(built);
        if (rtcGetDeviceError(device) != RTC_ERROR_NONE) {
            rtcReleaseScene(built);
            throw std::runtime_error(embree_error(device, "building the scene"));
        }
        return built;
    }

    // The largest coordinate of a triangle, sphere or quad: scenes are
    // rebased to the camera, so rays travel no farther than a few times this.
    double coordinate_magnitude() const {
        double magnitude = 0.0;
        auto add = [&magnitude](const RTCBounds& b) {
            for (float x : {b.lower_x, b.lower_y, b.lower_z, b.upper_x, b.upper_y, b.upper_z})
                magnitude = std::max(magnitude, std::fabs(double(x)));
        };
        for (const TriangleShape& t : triangles) add(t.box());
        for (const SphereShape& s : shapes.spheres) add(s.box());
        for (const QuadShape& q : shapes.quads) add(q.box());
        return magnitude;
    }

    // Embree's triangles (primID = leaf-order index) a little larger than
    // ours, under our filter.
    void attach_native_triangles(RTCScene target) {
        RTCGeometry geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
        auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(
            geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), 3 * triangles.size()));
        auto* indices = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
            geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), triangles.size()));
        if (!vertices || !indices) {
            rtcReleaseGeometry(geometry);
            throw std::runtime_error(embree_error(device, "allocating the triangles"));
        }
        const double margin = kEnlargement * coordinate_magnitude();
        for (std::size_t i = 0; i < triangles.size(); ++i) {
            std::array<vec3, 3> p = enlarged(triangles[i].triangle, margin);
            for (unsigned v = 0; v < 3; ++v) {
                std::copy(&p[v].x, &p[v].x + 3, vertices + 9 * i + 3 * v);
                indices[3 * i + v] = unsigned(3 * i + v);
            }
        }
        rtcSetGeometryUserData(geometry, triangles.data());
        rtcSetGeometryIntersectFilterFunction(geometry, triangle_filter);
        rtcSetGeometryOccludedFilterFunction(geometry, triangle_occlusion_filter);
        attach(target, geometry, WP_SHAPE_TRIANGLE);
    }

    // One user geometry of every shape of a kind, its geomID the kind.
    template <class Primitives>
    void attach_user(RTCScene target, const Primitives& primitives, std::uint32_t kind) {
        if (primitives.count() == 0) return;
        RTCGeometry geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_USER);
        rtcSetGeometryUserPrimitiveCount(geometry, primitives.count());
        rtcSetGeometryUserData(geometry, const_cast<Primitives*>(&primitives));
        rtcSetGeometryBoundsFunction(geometry, user_bounds<Primitives>, nullptr);
        rtcSetGeometryIntersectFunction(geometry, user_intersect<Primitives>);
        rtcSetGeometryOccludedFunction(geometry, user_occluded<Primitives>);
        attach(target, geometry, kind);
    }

    void attach(RTCScene target, RTCGeometry geometry, std::uint32_t kind) {
        rtcCommitGeometry(geometry);
        rtcAttachGeometryByID(target, geometry, kind);
        rtcReleaseGeometry(geometry);
        has_geometry = true;
    }

    // What is tested in turn, before Embree: planes, and with
    // EmbreeAnalytic::Loop spheres and quads.
    void offer_listed(Lane& lane) const {
        if (options.analytic == EmbreeAnalytic::Loop) offer_each(shapes.spheres, lane);
        offer_each(shapes.planes, lane);
        if (options.analytic == EmbreeAnalytic::Loop) offer_each(shapes.quads, lane);
    }
    bool any_listed(const Lane& lane) const {
        return (options.analytic == EmbreeAnalytic::Loop &&
                (any_of(shapes.spheres, lane) || any_of(shapes.quads, lane))) ||
               any_of(shapes.planes, lane);
    }

    // Lanes the listed shapes leave to Embree.
    bool needs_embree(const Lane& lane) const { return has_geometry && lane.traceable && !lane.occluded; }

    // A lane Embree's triangles may have answered otherwise than our test
    // alone (triangle_filter) is traced again on the exact scene.
    void settle_closest(Lane& lane) const {
        bool disputed = lane.disputed_t < kInfinity && lane.disputed_t <= initial_t_far(lane);
        if (!lane.best_on_edge && !disputed) return;
        ++retraced;
        lane = fresh(lane);
        closest_one(exact, lane);
    }
    void settle_occluded(Lane& lane) const {
        if (lane.occluded || lane.disputed_t == kInfinity) return;
        ++retraced;
        lane = fresh(lane);
        occluded_one(exact, lane);
    }
    static Lane fresh(const Lane& lane) {
        Lane again = lane;
        again.best = kNoHit;
        again.occluded = again.best_on_edge = false;
        again.disputed_t = kInfinity;
        return again;
    }

    // ---- one query of lanes, each kind ----

    // The listed shapes' part of a query: the closest of them, or whether any lies before t_max.
    void trace_listed(Lane& lane, bool closest) const {
        if (closest)
            offer_listed(lane);
        else
            lane.occluded = any_listed(lane);
    }
    // Embree's t_far for a lane's query: beyond its closest hit so far, or beyond its t_max.
    static float initial_t_far(const Lane& lane) { return search_limit(lane, std::min(lane.best.t, lane.t_max)); }

    void closest_one(RTCScene target, Lane& lane) const {
        trace_listed(lane, true);
        if (!needs_embree(lane)) return;
        QueryContext context(&lane);
        RTCRayHit rayhit;
        set_ray(rayhit.ray, lane, initial_t_far(lane), 0);
        rayhit.hit.geomID = RTC_INVALID_GEOMETRY_ID;
        rtcIntersect1(target, &context.embree, &rayhit);
        if (target != exact) settle_closest(lane);
    }
    void occluded_one(RTCScene target, Lane& lane) const {
        trace_listed(lane, false);
        if (!needs_embree(lane)) return;
        QueryContext context(&lane);
        RTCRay ray;
        set_ray(ray, lane, initial_t_far(lane), 0);
        rtcOccluded1(target, &context.embree, &ray);
        if (target != exact) settle_occluded(lane);
    }

    // A packet's valid mask and rays from up to P::size lanes; false: Embree need trace none.
    template <class P, class RayK>
    bool fill_packet(Lane* lanes, std::size_t n, bool closest, int* valid, RayK& ray) const {
        bool any = false;
        for (int k = 0; k < P::size; ++k) {
            valid[k] = 0;
            if (std::size_t(k) >= n) continue;
            trace_listed(lanes[k], closest);
            if (!needs_embree(lanes[k])) continue;
            valid[k] = -1, any = true;
            set_ray(ray, k, lanes[k], initial_t_far(lanes[k]));
        }
        return any;
    }
    template <class P>
    void closest_packet(Lane* lanes, std::size_t n) const {
        alignas(64) int valid[P::size];
        typename P::RayHit rayhit;
        if (!fill_packet<P>(lanes, n, true, valid, rayhit.ray)) return;
        std::fill(rayhit.hit.geomID, rayhit.hit.geomID + P::size, RTC_INVALID_GEOMETRY_ID);
        QueryContext context(lanes);
        P::intersect(valid, scene, &context.embree, &rayhit);
        settle_closest(lanes, n);
    }
    template <class P>
    void occluded_packet(Lane* lanes, std::size_t n) const {
        alignas(64) int valid[P::size];
        typename P::Ray ray;
        if (!fill_packet<P>(lanes, n, false, valid, ray)) return;
        QueryContext context(lanes);
        P::occluded(valid, scene, &context.embree, &ray);
        settle_occluded(lanes, n);
    }

    // A stream's rays (`ray(i)`, the i-th) from the lanes Embree must trace, each with its lane as id; their count.
    template <class RayAt>
    unsigned fill_stream(Lane* lanes, std::size_t n, bool closest, const RayAt& ray) const {
        unsigned m = 0;
        for (std::size_t k = 0; k < n; ++k) {
            trace_listed(lanes[k], closest);
            if (needs_embree(lanes[k])) set_ray(ray(m++), lanes[k], initial_t_far(lanes[k]), unsigned(k));
        }
        return m;
    }
    void closest_stream(Lane* lanes, std::size_t n) const {
        RTCRayHit rays[kStreamSize];
        unsigned m = fill_stream(lanes, n, true, [&rays](unsigned i) -> RTCRay& {
            rays[i].hit.geomID = RTC_INVALID_GEOMETRY_ID;
            return rays[i].ray;
        });
        if (m == 0) return;
        QueryContext context(lanes);
        rtcIntersect1M(scene, &context.embree, rays, m, sizeof(RTCRayHit));
        settle_closest(lanes, n);
    }
    void occluded_stream(Lane* lanes, std::size_t n) const {
        RTCRay rays[kStreamSize];
        unsigned m = fill_stream(lanes, n, false, [&rays](unsigned i) -> RTCRay& { return rays[i]; });
        if (m == 0) return;
        QueryContext context(lanes);
        rtcOccluded1M(scene, &context.embree, rays, m, sizeof(RTCRay));
        settle_occluded(lanes, n);
    }

    void settle_closest(Lane* lanes, std::size_t n) const {
        if (scene == exact) return;
        for (std::size_t k = 0; k < n; ++k)
            if (needs_embree(lanes[k])) settle_closest(lanes[k]);
    }
    void settle_occluded(Lane* lanes, std::size_t n) const {
        if (scene == exact) return;
        for (std::size_t k = 0; k < n; ++k)
            if (lanes[k].traceable) settle_occluded(lanes[k]);
    }

    // Up to kStreamSize lanes, in queries of the options' kind.
    void trace(Lane* lanes, std::size_t n, bool closest) const {
        switch (options.query) {
            case EmbreeQuery::Single:
                for (std::size_t k = 0; k < n; ++k)
                    closest ? closest_one(scene, lanes[k]) : occluded_one(scene, lanes[k]);
                break;
            case EmbreeQuery::Packet4:
                trace_packets<Packet4>(lanes, n, closest);
                break;
            case EmbreeQuery::Packet8:
                trace_packets<Packet8>(lanes, n, closest);
                break;
            case EmbreeQuery::Packet16:
                trace_packets<Packet16>(lanes, n, closest);
                break;
            case EmbreeQuery::Stream:
                closest ? closest_stream(lanes, n) : occluded_stream(lanes, n);
                break;
        }
    }
    template <class P>
    void trace_packets(Lane* lanes, std::size_t n, bool closest) const {
        for (std::size_t k = 0; k < n; k += P::size) {
            std::size_t m = std::min<std::size_t>(P::size, n - k);
            closest ? closest_packet<P>(lanes + k, m) : occluded_packet<P>(lanes + k, m);
        }
    }

    // The queue in runs of kStreamSize lanes on the options' threads; `write` stores each lane's result.
    template <class Write>
    void trace_queue(const RayArrays& rays, std::span<const std::uint32_t> queue, bool closest,
                     const Write& write) const {
        for_each_part(queue.size(), options.threads, [&](std::size_t begin, std::size_t end) {
            Lane lanes[kStreamSize];
            for (std::size_t first = begin; first < end; first += kStreamSize) {
                std::size_t n = std::min(kStreamSize, end - first);
                for (std::size_t k = 0; k < n; ++k) lanes[k] = make_lane(rays, queue[first + k], search_slack);
                trace(lanes, n, closest);
                for (std::size_t k = 0; k < n; ++k) write(queue[first + k], lanes[k]);
            }
        });
    }
};

EmbreeIntersector::EmbreeIntersector(const Scene& scene, std::vector<SharedMath<float>::MeshTriangle> triangles,
                                     const EmbreeOptions& options)
    : impl_(std::make_unique<Impl>(scene, std::move(triangles), options)) {}

EmbreeIntersector::~EmbreeIntersector() = default;

const EmbreeOptions& EmbreeIntersector::options() const { return impl_->options; }

std::uint64_t EmbreeIntersector::retraced_rays() const { return impl_->retraced; }

HostHit EmbreeIntersector::closest(const vec3& origin, const vec3& direction, float t_max) const {
    Lane lane = make_lane(origin, direction, t_max, impl_->search_slack);
    impl_->closest_one(impl_->scene, lane);
    return lane.best;
}

bool EmbreeIntersector::occluded(const vec3& origin, const vec3& direction, float t_max) const {
    Lane lane = make_lane(origin, direction, t_max, impl_->search_slack);
    impl_->occluded_one(impl_->scene, lane);
    return lane.occluded;
}

void EmbreeIntersector::closest(const RayArrays& rays, std::span<const std::uint32_t> queue,
                                const HitArrays& hits) const {
    impl_->trace_queue(rays, queue, true, [&](std::uint32_t slot, const Lane& lane) {
        hits.t[slot] = lane.best.t;
        hits.shape[slot] = lane.best.shape;
    });
}

void EmbreeIntersector::occluded(const RayArrays& rays, std::span<const std::uint32_t> queue,
                                 std::uint32_t* occluded) const {
    impl_->trace_queue(rays, queue, false,
                       [&](std::uint32_t slot, const Lane& lane) { occluded[slot] = lane.occluded ? 1u : 0u; });
}

std::string options_name(const EmbreeOptions& options) {
    const char* queries[] = {"single", "packet4", "packet8", "packet16", "stream"};
    return std::string(options.triangles == EmbreeTriangles::User ? "user_" : "filter_") +
           queries[static_cast<int>(options.query)] +
           (options.analytic == EmbreeAnalytic::User ? "_analytic_user" : "");
}

std::string embree_device_summary() {
    RTCDevice device = rtcNewDevice(nullptr);
    if (!device) return "Embree: no device";
    auto has = [device](RTCDeviceProperty p) { return rtcGetDeviceProperty(device, p) != 0; };
    // Packets of 16 run natively only on Embree's AVX-512 kernels, of 8 on its AVX/AVX2 ones.
    std::string isa = has(RTC_DEVICE_PROPERTY_NATIVE_RAY16_SUPPORTED)  ? "AVX-512"
                      : has(RTC_DEVICE_PROPERTY_NATIVE_RAY8_SUPPORTED) ? "AVX2"
                                                                       : "SSE";
    std::string summary = std::string("Embree ") + RTC_VERSION_STRING + "; kernels " + isa + "; native packets";
    for (auto [size, property] : {std::pair{4, RTC_DEVICE_PROPERTY_NATIVE_RAY4_SUPPORTED},
                                  std::pair{8, RTC_DEVICE_PROPERTY_NATIVE_RAY8_SUPPORTED},
                                  std::pair{16, RTC_DEVICE_PROPERTY_NATIVE_RAY16_SUPPORTED}})
        if (has(property)) summary += " " + std::to_string(size);
    summary += has(RTC_DEVICE_PROPERTY_RAY_STREAM_SUPPORTED) ? "; streams" : "; no streams";
    rtcReleaseDevice(device);
    return summary;
}

}  // namespace wp
