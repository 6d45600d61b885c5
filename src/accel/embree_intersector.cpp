#include "accel/embree_intersector.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <condition_variable>
#include <functional>
#include <glm/geometric.hpp>
#include <limits>
#include <mutex>
#include <stdexcept>
#include <thread>
#include <type_traits>

namespace wp {

namespace {

using M = SharedMath<float>;
using vec3 = M::vec3;

constexpr float kInfinity = std::numeric_limits<float>::infinity();
constexpr HostHit kNoHit{M::real_max, WP_NO_HIT};

std::uint32_t shape_id(std::uint32_t kind, std::uint32_t index) { return kind << WP_SHAPE_TYPE_SHIFT | index; }

// One ray as the tests and the callbacks see it.
struct Lane {
    vec3 origin, direction;
    M::TriangleRay triangle_ray;  // the triangle test's shear, set before a triangle is tested (with_triangle_ray)
    float t_max;                  // the ray's own: every test runs on it, so no hit depends on what was found before
    float search_slack;           // search_limit's absolute part, the scene's
    bool traceable;               // finite, with a positive t_max: handed to Embree
    HostHit best;                 // closest so far
    bool occluded;
    bool declined;  // EmbreeMode::Verified's any hit: Embree offered a shape our test does not hit
};

Lane make_lane(const RayArrays& rays, std::uint32_t slot, float search_slack) {
    Lane lane;
    lane.search_slack = search_slack;
    lane.origin = vec3(rays.origin[0][slot], rays.origin[1][slot], rays.origin[2][slot]);
    lane.direction = vec3(rays.direction[0][slot], rays.direction[1][slot], rays.direction[2][slot]);
    lane.t_max = rays.t_max ? std::min(rays.t_max[slot], M::real_max) : M::real_max;
    lane.traceable = M::vec3_is_finite(lane.origin) && M::vec3_is_finite(lane.direction) && lane.t_max > 0.0f;
    lane.best = kNoHit;
    lane.occluded = false;
    lane.declined = false;
    return lane;
}

Lane make_lane(const vec3& origin, const vec3& direction, float t_max, float search_slack) {
    std::array<const float*, 3> o{&origin.x, &origin.y, &origin.z}, d{&direction.x, &direction.y, &direction.z};
    return make_lane(RayArrays{o, d, &t_max}, 0, search_slack);
}

void with_triangle_ray(Lane& lane) { lane.triangle_ray = M::triangle_ray(lane.direction); }

// `candidate` becomes the lane's closest hit if it is a hit and precedes the closest so far.
bool offer(Lane& lane, const HostHit& candidate) {
    if (!(candidate.t < lane.t_max) || !hit_precedes(candidate, lane.best)) return false;
    lane.best = candidate;
    return true;
}

// Embree's t_far for a ray whose search ends at t: a little beyond t, so
// that a shape our test puts at t (a tie) or just before it is still found
// although Embree's rounding puts its box (or its own distance to an
// enlarged triangle) farther: 2^-10 of t, far above both roundings, also
// for rays grazing a surface, plus the scene's search_slack for short rays,
// whose distances both compute with errors of the coordinates' size.
float search_limit(const Lane& lane, float t) { return t * (1.0f + 0x1p-10f) + lane.search_slack; }

// Embree's t_far for a lane's query: beyond its closest hit so far, or beyond its t_max.
float initial_t_far(const Lane& lane) { return search_limit(lane, std::min(lane.best.t, lane.t_max)); }

// ---- the shapes, each with our test ----

// A box a little larger than the shape, so that no hit our test reports
// (rounded) lies outside it: wider than the shape by 2^-16 of its magnitude.
RTCBounds widened_box(const vec3& lower, const vec3& upper) {
    float margin = 0x1p-16f * std::max(M::max_abs(lower), M::max_abs(upper));
    auto below = [margin](float x) { return std::nextafter(x - margin, -kInfinity); };
    auto above = [margin](float x) { return std::nextafter(x + margin, kInfinity); };
    return {below(lower.x), below(lower.y), below(lower.z), 0.0f, above(upper.x), above(upper.y), above(upper.z), 0.0f};
}

using Corners = std::array<glm::dvec3, 3>;

// Our test's verdict on a shape Embree offered a shadow ray (EmbreeMode::Verified).
enum class Verdict {
    Occludes,  // a hit before the ray's t_max
    Beyond,    // a hit at t_max or beyond only (the light at the end of a shadow ray)
    Missed,    // no hit at any distance: the ray passed through the enlarged shape's margin
};

// The verdict from a shape's distance within a given t_max, asked at most
// twice: before the ray's t_max, then at any distance.
template <class DistanceWithin>
Verdict verdict_from(const DistanceWithin& distance_within, float t_max) {
    if (distance_within(t_max) < t_max) return Verdict::Occludes;
    return distance_within(M::real_max) < M::real_max ? Verdict::Beyond : Verdict::Missed;
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
    static constexpr unsigned triangles =
        2;  // as Embree's triangles: (c, c + e1, c + e1 + e2), (c, c + e1 + e2, c + e2)
    vec3 corner, edge1, edge2;
    M::QuadPlane plane;  // quad_plane(edge1, edge2), once
    float t(const Lane& ray) const { return t_within(ray, ray.t_max); }
    Verdict verdict(const Lane& ray) const {
        return verdict_from([&](float t_max) { return t_within(ray, t_max); }, ray.t_max);
    }
    float t_within(const Lane& ray, float t_max) const {
        return M::intersect_quad_plane(corner, edge1, edge2, plane, ray.origin, ray.direction, t_max);
    }
    RTCBounds box() const {
        vec3 far = corner + edge1 + edge2, a = corner + edge1, b = corner + edge2;
        return widened_box(glm::min(glm::min(corner, far), glm::min(a, b)),
                           glm::max(glm::max(corner, far), glm::max(a, b)));
    }
    Corners corners(unsigned half) const {
        glm::dvec3 c(corner), e1(edge1), e2(edge2);
        return half == 0 ? Corners{c, c + e1, c + e1 + e2} : Corners{c, c + e1 + e2, c + e2};
    }
};

struct TriangleShape {
    static constexpr std::uint32_t kind = WP_SHAPE_TRIANGLE;
    static constexpr unsigned triangles = 1;
    M::MeshTriangle triangle;  // alone: a list of shapes has the bytes of a list of triangles (triangle_bytes)
    // These need with_triangle_ray(ray).
    float t(const Lane& ray) const { return M::mesh_triangle_t(&triangle, ray.triangle_ray, ray.origin, ray.t_max); }
    // mesh_triangle_t's two steps, the edges computed once for both distances.
    Verdict verdict(const Lane& ray) const {
        M::TriangleEdges edges = M::mesh_triangle_edges(&triangle, ray.triangle_ray, ray.origin);
        return verdict_from([&](float t_max) { return M::triangle_distance(edges, t_max); }, ray.t_max);
    }
    RTCBounds box() const {
        vec3 p0 = M::triangle_vertex(triangle.p0), p1 = M::triangle_vertex(triangle.p1),
             p2 = M::triangle_vertex(triangle.p2);
        return widened_box(glm::min(p0, glm::min(p1, p2)), glm::max(p0, glm::max(p1, p2)));
    }
    Corners corners(unsigned) const {
        Corners p;
        for (int a = 0; a < 3; ++a) p[0][a] = triangle.p0[a], p[1][a] = triangle.p1[a], p[2][a] = triangle.p2[a];
        return p;
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

// EmbreeMode::Verified hands Embree each triangle enlarged so that every
// edge lies `margin` farther out (scaled about its incenter by 1 + margin /
// inradius, at most doubled, then rounded outward): Embree's robust test,
// which decides the points near an edge or vertex otherwise than ours and
// can miss all the triangles around a vertex, then hits every shape ours
// hits. The margin, 2^-18 of the scene's largest coordinate (64 of its
// float steps), is many times both tests' rounding; it shrinks only as seen
// by a ray grazing the surface. The enlargement keeps the triangle's plane
// (but for the rounding of its corners), so Embree's distances stay ours
// within rounding.
constexpr double kEnlargement = 0x1p-18;

std::array<vec3, 3> enlarged(const Corners& p, double margin) {
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

// ---- Embree's callbacks ----

// The intersect context Embree hands to the callbacks, with the query's lane after it.
struct QueryContext {
    RTCIntersectContext embree;  // first: callbacks get a pointer to it
    Lane* lane;

    explicit QueryContext(Lane& l) : lane(&l) { rtcInitIntersectContext(&embree); }
    static Lane& of(const RTCIntersectContext* context) {
        return *reinterpret_cast<const QueryContext*>(context)->lane;
    }
};

// Embree's primitives of one kind of our shapes: each a shape (user
// geometry) or one of Shape::triangles triangles of a shape (Verified).
template <class Shape>
struct ShapeList {
    const std::vector<Shape>* shapes;
    static std::uint32_t shape_of(unsigned primitive) { return primitive / Shape::triangles; }
    unsigned count() const { return unsigned(shapes->size()); }
    HostHit hit(const Lane& lane, unsigned primitive) const {
        return {(*shapes)[primitive].t(lane), shape_id(Shape::kind, primitive)};
    }
    bool hits(const Lane& lane, unsigned primitive) const { return (*shapes)[primitive].t(lane) < lane.t_max; }
    Verdict verdict(const Lane& lane, unsigned shape) const { return (*shapes)[shape].verdict(lane); }
    RTCBounds box(unsigned primitive) const { return (*shapes)[primitive].box(); }
};

// Our test of one primitive (user geometry, EmbreeMode::Exact).
template <class Shapes>
void user_intersect(const RTCIntersectFunctionNArguments* args) {
    if (!args->valid[0]) return;  // one ray at a time (N = 1)
    const auto& shapes = *static_cast<const Shapes*>(args->geometryUserPtr);
    Lane& lane = QueryContext::of(args->context);
    if (!offer(lane, shapes.hit(lane, args->primID))) return;
    RTCRayN* ray = RTCRayHitN_RayN(args->rayhit, args->N);
    RTCHitN* hit = RTCRayHitN_HitN(args->rayhit, args->N);
    RTCRayN_tfar(ray, args->N, 0) = search_limit(lane, lane.best.t);
    RTCHitN_geomID(hit, args->N, 0) = args->geomID;
    RTCHitN_primID(hit, args->N, 0) = args->primID;
}

template <class Shapes>
void user_occluded(const RTCOccludedFunctionNArguments* args) {
    if (!args->valid[0]) return;
    const auto& shapes = *static_cast<const Shapes*>(args->geometryUserPtr);
    Lane& lane = QueryContext::of(args->context);
    if (!shapes.hits(lane, args->primID)) return;
    lane.occluded = true;
    RTCRayN_tfar(args->ray, args->N, 0) = -kInfinity;  // Embree's mark of an occluded ray
}

template <class Shapes>
void user_bounds(const RTCBoundsFunctionArguments* args) {
    *args->bounds_o = static_cast<const Shapes*>(args->geometryUserPtr)->box(args->primID);
}

// EmbreeMode::Verified's any hit: each shape Embree's enlarged triangles
// offer counts only where our test hits it before t_max. One that our test
// misses at any distance marks the lane: the ray passed through a margin,
// where the enlarged shape that our test hits can be missed too. (One beyond
// t_max, such as the light at the end of a shadow ray, is no such sign.)
template <class Shapes>
void verified_occlusion_filter(const RTCFilterFunctionNArguments* args) {
    if (!args->valid[0]) return;
    const auto& shapes = *static_cast<const Shapes*>(args->geometryUserPtr);
    Lane& lane = QueryContext::of(args->context);
    with_triangle_ray(lane);  // here, not for every ray: most shadow rays meet no shape
    switch (shapes.verdict(lane, Shapes::shape_of(RTCHitN_primID(args->hit, args->N, 0)))) {
        case Verdict::Occludes:
            lane.occluded = true;
            return;
        case Verdict::Missed:
            lane.declined = true;
            break;
        case Verdict::Beyond:
            break;
    }
    args->valid[0] = 0;
}

// ---- queries ----

void set_ray(RTCRay& ray, const Lane& lane, float t_far) {
    ray.org_x = lane.origin.x, ray.org_y = lane.origin.y, ray.org_z = lane.origin.z;
    ray.dir_x = lane.direction.x, ray.dir_y = lane.direction.y, ray.dir_z = lane.direction.z;
    ray.tnear = 0.0f, ray.tfar = t_far, ray.time = 0.0f;
    ray.mask = ~0u, ray.id = 0, ray.flags = 0;
}

// Rays per chunk of a queue: a thread takes chunks in turn, and the rays of
// one chunk, traced one after the other, have their found shapes' data
// fetched while the next ones are traced.
constexpr std::size_t kChunk = 64;

// Host threads started once, which run one job at a time over chunks taken
// in turn (the caller's thread among them). Every ray's result depends on
// that ray alone, so which thread takes which chunk changes nothing but the time.
class WorkerThreads {
 public:
    explicit WorkerThreads(int threads) {
        for (int i = 1; i < threads; ++i) workers_.emplace_back([this] { serve(); });
    }
    ~WorkerThreads() {
        {
            std::lock_guard lock(mutex_);
            stopping_ = true;
        }
        wake_.notify_all();
        for (std::thread& w : workers_) w.join();
    }

    // work(chunk) for every chunk in [0, chunks); returns when all are done.
    void run(std::size_t chunks, const std::function<void(std::size_t)>& work) {
        std::lock_guard one_job(job_);
        {
            std::lock_guard lock(mutex_);
            work_ = &work;
            chunks_ = chunks;
            next_ = 0;
            busy_ = workers_.size();
            ++generation_;
        }
        wake_.notify_all();
        take_chunks(work, chunks);
        std::unique_lock lock(mutex_);
        done_.wait(lock, [this] { return busy_ == 0; });
    }

 private:
    void take_chunks(const std::function<void(std::size_t)>& work, std::size_t chunks) {
        for (std::size_t chunk; (chunk = next_.fetch_add(1)) < chunks;) work(chunk);
    }
    void serve() {
        for (std::uint64_t seen = 0;;) {
            std::unique_lock lock(mutex_);
            wake_.wait(lock, [&] { return stopping_ || generation_ != seen; });
            if (stopping_) return;
            seen = generation_;
            const std::function<void(std::size_t)>& work = *work_;
            std::size_t chunks = chunks_;
            lock.unlock();
            take_chunks(work, chunks);
            lock.lock();
            if (--busy_ == 0) done_.notify_one();
        }
    }

    std::vector<std::thread> workers_;
    std::mutex job_;  // one run at a time
    std::mutex mutex_;
    std::condition_variable wake_, done_;
    const std::function<void(std::size_t)>* work_ = nullptr;
    std::size_t chunks_ = 0, busy_ = 0;
    std::atomic<std::size_t> next_{0};
    std::uint64_t generation_ = 0;
    bool stopping_ = false;
};

std::string embree_error(RTCDevice device, const std::string& what) {
    return "Embree: " + what + " failed (error " + std::to_string(int(rtcGetDeviceError(device))) + ")";
}

// The shape Embree found for a ray (EmbreeMode::Verified), before our test.
struct FoundShape {
    unsigned geometry = RTC_INVALID_GEOMETRY_ID;  // WP_SHAPE_TRIANGLE or WP_SHAPE_QUAD
    unsigned primitive = 0;
};

}  // namespace

struct EmbreeIntersector::Impl {
    EmbreeOptions options;
    std::vector<SphereShape> spheres;  // tested in turn, as planes are
    std::vector<PlaneShape> planes;
    std::vector<QuadShape> quads;  // Embree's, as triangles are
    std::vector<TriangleShape> triangles;
    // What Embree's geometries hand their callbacks (their user data).
    ShapeList<QuadShape> quad_list{&quads};
    ShapeList<TriangleShape> triangle_list{&triangles};
    bool has_embree_shapes = false;  // any triangle or quad
    float search_slack = 0.0f;       // 2^-16 of the largest coordinate: Lane::search_slack
    // EmbreeMode::Verified's reach: an origin with a coordinate beyond 4
    // times the scene's largest is traced exactly, for Embree's rounding
    // grows with the origin's coordinates (about 2^-24 of them) and the
    // margin does not (2^-18 of the scene's: 16 times the rounding at 4).
    float verified_reach = 0.0f;
    RTCDevice device = nullptr;
    RTCScene verified = nullptr;  // EmbreeMode::Verified: enlarged triangles
    RTCScene exact = nullptr;     // user geometry: EmbreeMode::Exact, and Verified's retraced rays
    mutable std::atomic<std::uint64_t> retraced{0};
    std::unique_ptr<WorkerThreads> workers;

    Impl(const Scene& source, std::vector<M::MeshTriangle> mesh_triangles, const EmbreeOptions& o) : options(o) {
        if (options.threads <= 0) options.threads = std::max(1, int(std::thread::hardware_concurrency()));
        for (const Sphere& s : source.spheres) spheres.push_back({vec3(s.center), float(s.radius)});
        for (const Plane& p : source.planes) planes.push_back({vec3(p.point), vec3(p.normal)});
        for (const Quad& q : source.quads)
            quads.push_back(
                {vec3(q.corner), vec3(q.edge1), vec3(q.edge2), M::quad_plane(vec3(q.edge1), vec3(q.edge2))});
        triangles.reserve(mesh_triangles.size());
        for (const M::MeshTriangle& t : mesh_triangles) triangles.push_back({t});
        std::vector<M::MeshTriangle>().swap(mesh_triangles);  // one copy through Embree's builds
        has_embree_shapes = !triangles.empty() || !quads.empty();
        search_slack = float(0x1p-16 * coordinate_magnitude());
        verified_reach = float(4.0 * coordinate_magnitude());
        device = rtcNewDevice(("threads=" + std::to_string(options.threads)).c_str());
        if (!device) throw std::runtime_error("Embree: cannot create a device");
        try {
            exact = build_scene(EmbreeMode::Exact);
            if (options.mode == EmbreeMode::Verified) verified = build_scene(EmbreeMode::Verified);
        } catch (...) {
            release();
            throw;
        }
        workers = std::make_unique<WorkerThreads>(options.threads);
    }
    ~Impl() { release(); }

    void release() {
        if (verified) rtcReleaseScene(verified);
        if (exact) rtcReleaseScene(exact);
        if (device) rtcReleaseDevice(device);
        verified = exact = nullptr, device = nullptr;
    }

    RTCScene build_scene(EmbreeMode mode) {
        RTCScene built = rtcNewScene(device);
        // Exact: robust box tests, which never lose a box to rounding, as its
        // user geometry's watertightness needs. Verified: Embree's fast
        // tests, whose rounding, like the robust ones', the enlargement's
        // margin exceeds (the same rays found in every test; 1.15x the
        // bunny's samples/s).
        if (mode == EmbreeMode::Exact) rtcSetSceneFlags(built, RTC_SCENE_FLAG_ROBUST);
        rtcSetSceneBuildQuality(built, RTC_BUILD_QUALITY_MEDIUM);
        if (mode == EmbreeMode::Verified) {
            attach_enlarged(built, quad_list);
            attach_enlarged(built, triangle_list);
        } else {
            attach_user(built, quad_list);
            attach_user(built, triangle_list);
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
        for (const SphereShape& s : spheres) add(s.box());
        for (const QuadShape& q : quads) add(q.box());
        return magnitude;
    }

    // Embree's robust triangles, Shape::triangles per shape, each enlarged
    // (primID / Shape::triangles = the shape's index; geomID its kind), our
    // test the judge of any hit.
    template <class Shape>
    void attach_enlarged(RTCScene target, const ShapeList<Shape>& list) {
        const std::vector<Shape>& shapes = *list.shapes;
        if (shapes.empty()) return;
        const std::size_t count = Shape::triangles * shapes.size();
        RTCGeometry geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
        auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0,
                                                                     RTC_FORMAT_FLOAT3, 3 * sizeof(float), 3 * count));
        auto* indices = static_cast<unsigned*>(
            rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), count));
        if (!vertices || !indices) {
            rtcReleaseGeometry(geometry);
            throw std::runtime_error(embree_error(device, "allocating the triangles"));
        }
        const double margin = kEnlargement * coordinate_magnitude();
        for (std::size_t i = 0; i < count; ++i) {
            std::array<vec3, 3> p = enlarged(shapes[i / Shape::triangles].corners(i % Shape::triangles), margin);
            for (unsigned v = 0; v < 3; ++v) {
                std::copy(&p[v].x, &p[v].x + 3, vertices + 9 * i + 3 * v);
                indices[3 * i + v] = unsigned(3 * i + v);
            }
        }
        rtcSetGeometryUserData(geometry, const_cast<ShapeList<Shape>*>(&list));
        rtcSetGeometryOccludedFilterFunction(geometry, verified_occlusion_filter<ShapeList<Shape>>);
        attach(target, geometry, Shape::kind);
    }

    // One user geometry of every shape of a kind.
    template <class Shape>
    void attach_user(RTCScene target, const ShapeList<Shape>& list) {
        if (list.count() == 0) return;
        RTCGeometry geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_USER);
        rtcSetGeometryUserPrimitiveCount(geometry, list.count());
        rtcSetGeometryUserData(geometry, const_cast<ShapeList<Shape>*>(&list));
        rtcSetGeometryBoundsFunction(geometry, user_bounds<ShapeList<Shape>>, nullptr);
        rtcSetGeometryIntersectFunction(geometry, user_intersect<ShapeList<Shape>>);
        rtcSetGeometryOccludedFunction(geometry, user_occluded<ShapeList<Shape>>);
        attach(target, geometry, Shape::kind);
    }

    void attach(RTCScene target, RTCGeometry geometry, std::uint32_t kind) {
        rtcCommitGeometry(geometry);
        rtcAttachGeometryByID(target, geometry, kind);
        rtcReleaseGeometry(geometry);
    }

    // Lanes the spheres and planes leave to Embree.
    bool needs_embree(const Lane& lane) const { return has_embree_shapes && lane.traceable && !lane.occluded; }

    bool verifiable(const Lane& lane) const {
        return options.mode == EmbreeMode::Verified && M::max_abs(lane.origin) <= verified_reach;
    }

    // ---- closest hit ----

    void closest_exact(Lane& lane) const {
        offer_each(spheres, lane);
        offer_each(planes, lane);
        if (!needs_embree(lane)) return;
        with_triangle_ray(lane);
        QueryContext context(lane);
        RTCRayHit rayhit;
        set_ray(rayhit.ray, lane, initial_t_far(lane));
        rayhit.hit.geomID = RTC_INVALID_GEOMETRY_ID;
        rtcIntersect1(exact, &context.embree, &rayhit);
    }

    // EmbreeMode::Verified, in two steps, so that a queue's rays are all
    // traced before their found shapes are tested (whose data is then in
    // cache): the spheres and planes and Embree's nearest enlarged shape.
    FoundShape find(Lane& lane, RTCIntersectContext& context) const {
        offer_each(spheres, lane);
        offer_each(planes, lane);
        if (!needs_embree(lane)) return {};
        RTCRayHit rayhit;
        set_ray(rayhit.ray, lane, initial_t_far(lane));
        rayhit.hit.geomID = RTC_INVALID_GEOMETRY_ID;
        rtcIntersect1(verified, &context, &rayhit);
        FoundShape found{rayhit.hit.geomID, rayhit.hit.primID};
        if (found.geometry == WP_SHAPE_TRIANGLE) {
            const char* data = reinterpret_cast<const char*>(&triangles[found.primitive]);
            __builtin_prefetch(data);
            __builtin_prefetch(data + sizeof(TriangleShape) - 1);
        }
        return found;
    }
    // Then our test of the found shape gives its distance; where it misses,
    // the ray is traced again Exact.
    void settle(Lane& lane, const FoundShape& found) const {
        if (found.geometry == RTC_INVALID_GEOMETRY_ID) return;
        HostHit hit;
        if (found.geometry == WP_SHAPE_TRIANGLE) {
            with_triangle_ray(lane);
            hit = triangle_list.hit(lane, found.primitive);
        } else {
            hit = quad_list.hit(lane, ShapeList<QuadShape>::shape_of(found.primitive));
        }
        if (hit.t < lane.t_max) {
            offer(lane, hit);
            return;
        }
        retraced.fetch_add(1, std::memory_order_relaxed);
        lane.best = kNoHit;
        closest_exact(lane);
    }

    void closest(Lane& lane) const { closest(&lane, 1); }

    void closest(Lane* lanes, std::size_t n) const {
        RTCIntersectContext context;
        rtcInitIntersectContext(&context);
        FoundShape found[kChunk];
        for (std::size_t k = 0; k < n; ++k)
            if (verifiable(lanes[k])) found[k] = find(lanes[k], context);
        for (std::size_t k = 0; k < n; ++k) {
            if (verifiable(lanes[k]))
                settle(lanes[k], found[k]);
            else
                closest_exact(lanes[k]);
        }
    }

    // ---- any hit ----

    void occluded(Lane& lane) const {
        lane.occluded = any_of(spheres, lane) || any_of(planes, lane);
        if (!needs_embree(lane)) return;
        if (!verifiable(lane)) {
            with_triangle_ray(lane);  // every callback needs it
            return occluded_in(exact, lane);
        }
        occluded_in(verified, lane);
        if (lane.occluded || !lane.declined) return;
        // As a closest hit whose shape our test rejects: traced again exactly
        // (the filter that declined set the triangle ray).
        retraced.fetch_add(1, std::memory_order_relaxed);
        occluded_in(exact, lane);
    }

    void occluded_in(RTCScene scene, Lane& lane) const {
        QueryContext context(lane);
        RTCRay ray;
        set_ray(ray, lane, initial_t_far(lane));
        rtcOccluded1(scene, &context.embree, &ray);
    }

    // ---- queues ----

    // The queue in chunks on the worker threads; `write` stores each lane's result.
    template <class Trace, class Write>
    void trace_queue(const RayArrays& rays, std::span<const std::uint32_t> queue, const Trace& trace,
                     const Write& write) const {
        workers->run((queue.size() + kChunk - 1) / kChunk, [&](std::size_t chunk) {
            const std::size_t first = chunk * kChunk, n = std::min(kChunk, queue.size() - first);
            Lane lanes[kChunk];
            for (std::size_t k = 0; k < n; ++k) lanes[k] = make_lane(rays, queue[first + k], search_slack);
            trace(lanes, n);
            for (std::size_t k = 0; k < n; ++k) write(queue[first + k], lanes[k]);
        });
    }
};

EmbreeIntersector::EmbreeIntersector(const Scene& scene, std::vector<SharedMath<float>::MeshTriangle> triangles,
                                     const EmbreeOptions& options)
    : impl_(std::make_unique<Impl>(scene, std::move(triangles), options)) {}

EmbreeIntersector::~EmbreeIntersector() = default;

const EmbreeOptions& EmbreeIntersector::options() const { return impl_->options; }

std::uint64_t EmbreeIntersector::retraced_rays() const { return impl_->retraced; }

static_assert(sizeof(TriangleShape) == sizeof(M::MeshTriangle) && std::is_standard_layout_v<TriangleShape>);

std::span<const std::byte> EmbreeIntersector::triangle_bytes() const {
    return std::as_bytes(std::span(impl_->triangles));
}

HostHit EmbreeIntersector::closest(const vec3& origin, const vec3& direction, float t_max) const {
    Lane lane = make_lane(origin, direction, t_max, impl_->search_slack);
    impl_->closest(lane);
    return lane.best;
}

bool EmbreeIntersector::occluded(const vec3& origin, const vec3& direction, float t_max) const {
    Lane lane = make_lane(origin, direction, t_max, impl_->search_slack);
    impl_->occluded(lane);
    return lane.occluded;
}

void EmbreeIntersector::closest(const RayArrays& rays, std::span<const std::uint32_t> queue,
                                const HitArrays& hits) const {
    impl_->trace_queue(
        rays, queue, [&](Lane* lanes, std::size_t n) { impl_->closest(lanes, n); },
        [&](std::uint32_t slot, const Lane& lane) {
            hits.t[slot] = lane.best.t;
            hits.shape[slot] = lane.best.shape;
        });
}

void EmbreeIntersector::occluded(const RayArrays& rays, std::span<const std::uint32_t> queue,
                                 std::uint32_t* occluded) const {
    impl_->trace_queue(
        rays, queue,
        [&](Lane* lanes, std::size_t n) {
            for (std::size_t k = 0; k < n; ++k) impl_->occluded(lanes[k]);
        },
        [&](std::uint32_t slot, const Lane& lane) { occluded[slot] = lane.occluded ? 1u : 0u; });
}

std::string mode_name(EmbreeMode mode) { return mode == EmbreeMode::Verified ? "verified" : "exact"; }

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
