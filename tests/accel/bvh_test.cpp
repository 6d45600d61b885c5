// The meshes' BVH (src/accel/bvh.cpp, kernels/shared/bvh.h) and the
// watertight triangle test (kernels/shared/triangle.h): the tree finds what
// a test of every triangle finds, bit for bit; it is the same for any thread
// count; and a ray through a closed mesh crosses it where it was aimed and
// once more on the far side, at any scale, through the BVH and through the
// Embree intersector.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <random>
#include <vector>

#include "accel/bvh_layout.h"
#include "accel/embree_intersector.h"
#include "core/shared_math.h"
#include "scene/scene.h"
#include "support/meshes.h"

namespace wp {
namespace {

using M = SharedMath<float>;
using vec3 = M::vec3;

using FlatMeshes = MeshLayout<float>;

FlatMeshes flatten(const std::vector<Mesh>& meshes) {
    Scene scene;
    scene.meshes = meshes;
    return mesh_layout<float>(scene, {});
}

// Every triangle tested in turn, keeping the first of equal distances.
float brute_force(const FlatMeshes& flat, vec3 origin, vec3 direction, float t_max, std::uint32_t& index) {
    for (std::uint32_t k = 0; k < flat.triangles.size(); ++k) {
        float t = M::mesh_triangle_t(&flat.triangles[k], M::triangle_ray(direction), origin, t_max);
        if (t < t_max) t_max = t, index = k;
    }
    return t_max;
}

// A dense, overlapping soup: 8 icospheres of 1280 triangles, shuffled about.
std::vector<Mesh> soup() {
    std::vector<Mesh> meshes;
    std::mt19937 random(5);
    std::uniform_real_distribution<double> position(-3.0, 3.0), size(0.3, 1.5);
    for (int i = 0; i < 8; ++i)
        meshes.push_back(test::transformed(test::icosphere(3, 0), size(random),
                                           {position(random), position(random), position(random)}));
    return meshes;
}

TEST(Bvh, FindsWhatTestingEveryTriangleFinds) {
    FlatMeshes flat = flatten(soup());
    std::mt19937 random(9);
    std::uniform_real_distribution<float> coordinate(-5.0f, 5.0f);
    int hits = 0;
    constexpr int kRays = 20000;
    for (int r = 0; r < kRays; ++r) {
        vec3 origin(coordinate(random), coordinate(random), coordinate(random));
        vec3 direction = glm::normalize(vec3(coordinate(random), coordinate(random), coordinate(random)));
        std::uint32_t expected = ~0u, found = ~0u;
        float t_expected = brute_force(flat, origin, direction, M::real_max, expected);
        float t_found =
            M::bvh_trace(flat.nodes.data(), flat.triangles.data(), origin, direction, M::real_max, 0, &found);
        ASSERT_EQ(t_found, t_expected) << "ray " << r;  // bit-identical distance
        if (found != expected) {                        // only a tie: another triangle at the very same distance
            ASSERT_NE(found, ~0u) << "ray " << r;
            EXPECT_EQ(M::mesh_triangle_t(&flat.triangles[found], M::triangle_ray(direction), origin, M::real_max),
                      t_expected);
        }
        hits += expected != ~0u;
        // Any hit: occluded exactly when something lies closer than the distance asked about.
        float limit = t_expected < M::real_max ? t_expected * 1.0001f : 10.0f;
        std::uint32_t any = ~0u;
        EXPECT_EQ(M::bvh_trace(flat.nodes.data(), flat.triangles.data(), origin, direction, limit, 1, &any) < limit,
                  expected != ~0u)
            << "ray " << r;
    }
    std::printf("[figure] BVH against brute force: %d rays, %d hits, all with bit-identical distances\n", kRays, hits);
    EXPECT_GT(hits, kRays / 10);
    EXPECT_LT(hits, kRays);
}

// The same on the Stanford bunny (scenes/bunny.json's meshes, 69,668
// triangles): rays from around it towards it. 2000 rays, since the test of
// every triangle costs 70k triangle tests a ray.
TEST(Bvh, FindsWhatTestingEveryTriangleFindsOnTheBunny) {
    Scene scene = load_scene(WAVEPATH_SOURCE_DIR "/scenes/bunny.json");
    FlatMeshes flat = flatten(scene.meshes);
    ASSERT_GT(flat.triangles.size(), 69000u);
    glm::dvec3 centre = scene.meshes[1].positions[0];  // a point of the bunny (the light is mesh 0)
    std::mt19937 random(13);
    std::uniform_real_distribution<float> coordinate(-1.0f, 1.0f);
    int hits = 0, differing = 0;
    constexpr int kRays = 2000;
    for (int r = 0; r < kRays; ++r) {
        vec3 target = vec3(centre) + 0.8f * vec3(coordinate(random), coordinate(random), coordinate(random));
        vec3 origin = target + 3.0f * glm::normalize(vec3(coordinate(random), coordinate(random), coordinate(random)));
        vec3 direction = glm::normalize(target - origin);
        std::uint32_t expected = ~0u, found = ~0u;
        float t_expected = brute_force(flat, origin, direction, M::real_max, expected);
        float t_found =
            M::bvh_trace(flat.nodes.data(), flat.triangles.data(), origin, direction, M::real_max, 0, &found);
        ASSERT_EQ(t_found, t_expected) << "ray " << r;
        differing += found != expected;  // ties at one distance only
        hits += expected != ~0u;
    }
    std::printf("[figure] BVH against brute force on the bunny: %d rays, %d hits, %d ties resolved differently\n",
                kRays, hits, differing);
    EXPECT_GT(hits, kRays / 4);
    EXPECT_LE(differing, 2);
}

TEST(Bvh, SameTreeForAnyThreadCountAndRun) {
    Scene scene;
    scene.meshes = soup();
    const std::vector<TrianglePositions> triangles = scene_triangle_positions(scene);
    BvhTree one = build_bvh(triangles, 1), two = build_bvh(triangles, 2), again = build_bvh(triangles, 2);
    for (const BvhTree* other : {&two, &again}) {
        ASSERT_EQ(other->nodes.size(), one.nodes.size());
        EXPECT_EQ(other->leaf_order, one.leaf_order);
        for (std::size_t i = 0; i < one.nodes.size(); ++i) {
            EXPECT_EQ(other->nodes[i].bounds, one.nodes[i].bounds) << i;
            EXPECT_EQ(other->nodes[i].child, one.nodes[i].child) << i;
        }
    }
    EXPECT_LE(one.depth, 32);
}

// The layout's triangles are in leaf order: slot i holds input triangle
// leaf_order[i] (scene_triangle_positions' index), whole: its corners, its
// material, its mesh, its vertex normals and uvs. Without the BVH: the input's order.
TEST(Bvh, MeshLayoutIsInLeafOrder) {
    Scene scene;
    scene.meshes = soup();
    scene.meshes[1].material = 1;       // meshes apart: the material and the mesh index travel with the triangle
    scene.meshes[2].triangles.clear();  // an empty mesh shifts no index
    for (std::size_t v = 0; v < scene.meshes[3].positions.size(); ++v) {  // one mesh with normals and uvs
        scene.meshes[3].normals.push_back(glm::normalize(scene.meshes[3].positions[v] + 1e-3));
        scene.meshes[3].uvs.push_back({0.25 * double(v), 0.5});
    }
    struct Input {
        TrianglePositions positions;
        std::array<glm::dvec3, 3> normals;
        std::array<glm::dvec2, 3> uvs;
        int material;
        std::uint32_t mesh;
    };
    std::vector<Input> input;
    for (std::size_t m = 0; m < scene.meshes.size(); ++m)
        for (const glm::uvec3& t : scene.meshes[m].triangles) {
            const Mesh& mesh = scene.meshes[m];
            input.push_back({{mesh.positions[t.x], mesh.positions[t.y], mesh.positions[t.z]},
                             vertex_normals(mesh, t),
                             vertex_uvs(mesh, t),
                             mesh.material,
                             std::uint32_t(m)});
        }
    const BvhTree tree = build_bvh(scene_triangle_positions(scene));
    for (bool with_bvh : {true, false}) {
        SCOPED_TRACE(with_bvh ? "BVH" : "no BVH");
        const MeshLayout<double> layout = mesh_layout<double>(scene, {with_bvh, true, true});
        ASSERT_EQ(layout.triangles.size(), input.size());
        ASSERT_EQ(layout.normals.size(), input.size());
        ASSERT_EQ(layout.uvs.size(), input.size());
        EXPECT_EQ(layout.nodes.size(), with_bvh ? tree.nodes.size() : 0u);
        for (std::size_t i = 0; i < input.size(); ++i) {
            const Input& expected = input[with_bvh ? tree.leaf_order[i] : i];
            const auto& triangle = layout.triangles[i];
            for (int a = 0; a < 3; ++a) {
                EXPECT_EQ(triangle.p0[a], expected.positions[0][a]) << i;
                EXPECT_EQ(triangle.p1[a], expected.positions[1][a]) << i;
                EXPECT_EQ(triangle.p2[a], expected.positions[2][a]) << i;
                EXPECT_EQ(layout.normals[i].n0[a], expected.normals[0][a]) << i;
                EXPECT_EQ(layout.normals[i].n2[a], expected.normals[2][a]) << i;
            }
            EXPECT_EQ(layout.uvs[i].uv1[0], expected.uvs[1][0]) << i;
            EXPECT_EQ(layout.uvs[i].uv2[1], expected.uvs[2][1]) << i;
            EXPECT_EQ(triangle.material, std::uint32_t(expected.material)) << i;
            EXPECT_EQ(triangle.mesh, expected.mesh) << i;
        }
    }
}

// Every float box holds its subtree's triangles in double: rounding outward
// leaves no sliver of a triangle outside its box.
TEST(Bvh, BoxesHoldTheirTrianglesExactly) {
    std::vector<Mesh> meshes = soup();
    Scene scene;
    scene.meshes = meshes;
    const MeshLayout<double> bvh = mesh_layout<double>(scene, {});
    std::function<void(std::uint32_t, const float*)> check = [&](std::uint32_t word, const float* box) {
        if (word & WP_BVH_LEAF) {
            std::uint32_t first = (word & ~WP_BVH_LEAF) >> WP_BVH_LEAF_COUNT_BITS, count = (word & 7u) + 1;
            for (std::uint32_t k = first; k < first + count; ++k)
                for (const double* p : {bvh.triangles[k].p0, bvh.triangles[k].p1, bvh.triangles[k].p2})
                    for (int a = 0; a < 3; ++a) {
                        EXPECT_LE(double(box[a]), p[a]);
                        EXPECT_GE(double(box[3 + a]), p[a]);
                    }
            return;
        }
        for (int i = 0; i < 2; ++i)
            if (bvh.nodes[word].child[i] != WP_BVH_NO_CHILD) check(bvh.nodes[word].child[i], bvh.nodes[word].bounds[i]);
    };
    check(0, nullptr);
    EXPECT_EQ(bvh.triangles.size(), 8u * 1280u);
}

// One intersector's closest hit: its distance along the ray, real_max where none.
template <class Real>
using ClosestDistance = std::function<Real(const typename SharedMath<Real>::vec3& origin,
                                           const typename SharedMath<Real>::vec3& direction)>;

// The distances along the ray at which it crosses the meshes: the closest
// hit, then the closest hit again from `step` past it, until none is left. A
// ray through an edge or vertex hits every triangle there at one distance;
// the step past them counts that crossing once.
template <class Real>
std::vector<double> crossings(const ClosestDistance<Real>& closest, const glm::dvec3& from, const glm::dvec3& to,
                              double step) {
    using R = SharedMath<Real>;
    using rvec3 = typename R::vec3;
    const rvec3 origin(from), direction = glm::normalize(rvec3(to) - origin);
    std::vector<double> found;
    Real travelled = 0;
    for (int i = 0; i < 8; ++i) {  // a convex mesh has 2
        const Real t = closest(origin + travelled * direction, direction);
        if (!(t < R::real_max)) break;
        travelled += t;
        found.push_back(double(travelled));
        travelled += Real(step);
    }
    return found;
}

// Rays aimed exactly at the vertices and edge midpoints of closed convex
// meshes, along the line from the centre through the target: from the centre
// out, the ray crosses the surface once, at the target; from outside in (3
// times as far out), twice, the first time at the target. A ray that leaked
// where it was aimed would find only the far side. Returns the rays that did
// not cross as expected. The step past a crossing and the tolerance on its
// distance, 5% and 2% of the mesh's size, lie far above float's spacing
// (2^-7 at 1e5, for meshes of size 1 and up there) and far below the 1x-2x
// its size between entry and exit.
template <class Real>
int rays_not_crossing_as_expected(const Mesh& mesh, double size, const ClosestDistance<Real>& closest) {
    glm::dvec3 centre(0.0);
    for (const glm::dvec3& p : mesh.positions) centre += p / double(mesh.positions.size());
    std::vector<glm::dvec3> targets = mesh.positions;
    for (const glm::uvec3& t : mesh.triangles)
        for (int e = 0; e < 3; ++e) targets.push_back((mesh.positions[t[e]] + mesh.positions[t[(e + 1) % 3]]) / 2.0);
    const double step = 0.05 * size, tolerance = 0.02 * size;
    int wrong = 0;
    for (const glm::dvec3& target : targets) {
        const double to_target = glm::length(target - centre);
        const std::vector<double> outward = crossings(closest, centre, target, step);
        const std::vector<double> inward = crossings(closest, centre + 3.0 * (target - centre), target, step);
        const bool outward_right = outward.size() == 1 && std::fabs(outward[0] - to_target) <= tolerance;
        const bool inward_right = inward.size() == 2 && std::fabs(inward[0] - 2.0 * to_target) <= tolerance;
        wrong += !outward_right + !inward_right;
    }
    return wrong;
}

// Through the BVH, in float or double.
template <class Real>
int bvh_rays_not_crossing(const Mesh& mesh, double size) {
    using R = SharedMath<Real>;
    Scene scene;
    scene.meshes = {mesh};
    MeshLayout<Real> flat = mesh_layout<Real>(scene, {});
    return rays_not_crossing_as_expected<Real>(
        mesh, size, [&](const typename R::vec3& origin, const typename R::vec3& direction) {
            std::uint32_t index = 0;
            return R::bvh_trace(flat.nodes.data(), flat.triangles.data(), origin, direction, R::real_max, 0, &index);
        });
}

// Through the Embree intersector, in float.
int embree_rays_not_crossing(const Mesh& mesh, double size, EmbreeMode mode) {
    Scene scene;
    scene.meshes = {mesh};
    EmbreeIntersector embree(scene, mesh_layout<float>(scene, {}).triangles, {mode});
    return rays_not_crossing_as_expected<float>(mesh, size, [&](const vec3& origin, const vec3& direction) {
        return embree.closest(origin, direction, M::real_max).t;
    });
}

TEST(Watertight, RaysCrossAClosedMeshWhereAimedAtAnyScale) {
    for (double scale : {1e-4, 1e-2, 1.0, 1e2, 1e4}) {
        for (glm::dvec3 offset : {glm::dvec3(0.0), glm::dvec3(1e5, -1e5, 1e5)}) {
            SCOPED_TRACE("scale " + std::to_string(scale) + ", offset " + std::to_string(offset.x));
            // Float spaces its values 2^-7 apart near 1e5: a mesh smaller than 1 there is a few
            // float steps across, its centre no longer inside it.
            bool float_can_hold_it = offset.x == 0.0 || scale >= 1.0;
            for (const Mesh& mesh : {test::icosphere(2, 0), test::unit_cube(0)}) {
                Mesh placed = test::transformed(mesh, scale, offset);
                if (float_can_hold_it) {
                    EXPECT_EQ(bvh_rays_not_crossing<float>(placed, scale), 0) << mesh.file;
                    EXPECT_EQ(embree_rays_not_crossing(placed, scale, EmbreeMode::Verified), 0)
                        << mesh.file << ", Embree, verified";
                    EXPECT_EQ(embree_rays_not_crossing(placed, scale, EmbreeMode::Exact), 0)
                        << mesh.file << ", Embree, exact";
                }
                EXPECT_EQ(bvh_rays_not_crossing<double>(placed, scale), 0) << mesh.file;
            }
        }
    }
}

TEST(Watertight, TestMeshesFaceOutward) {
    for (const Mesh& mesh : {test::icosphere(2, 0), test::unit_cube(0)}) {
        glm::dvec3 centre(0.0);
        for (const glm::dvec3& p : mesh.positions) centre += p / double(mesh.positions.size());
        for (const glm::uvec3& t : mesh.triangles) {
            glm::dvec3 p0 = mesh.positions[t.x], p1 = mesh.positions[t.y], p2 = mesh.positions[t.z];
            EXPECT_GT(glm::dot(glm::cross(p1 - p0, p2 - p0), (p0 + p1 + p2) / 3.0 - centre), 0.0) << mesh.file;
        }
    }
}

}  // namespace
}  // namespace wp
