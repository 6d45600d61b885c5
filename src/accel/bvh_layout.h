// The meshes' BVH and triangles in the layout kernels/shared/bvh.h traverses,
// for one precision: the device upload takes SharedMath<float>'s, the
// reference its own Real's. The one conversion from the builder's double data.
#pragma once

#include <algorithm>
#include <stdexcept>
#include <vector>

#include "accel/bvh.h"
#include "core/shared_math.h"

namespace wp {

template <class Real>
typename SharedMath<Real>::MeshTriangle mesh_triangle(const TrianglePositions& p, int material, int mesh) {
    typename SharedMath<Real>::MeshTriangle t{};
    for (int i = 0; i < 3; ++i) {
        t.p0[i] = static_cast<Real>(p[0][i]);
        t.p1[i] = static_cast<Real>(p[1][i]);
        t.p2[i] = static_cast<Real>(p[2][i]);
    }
    t.material = static_cast<std::uint32_t>(material);
    t.mesh = static_cast<std::uint32_t>(mesh);
    return t;
}

template <class Real>
typename SharedMath<Real>::TriangleNormals triangle_normals(const std::array<glm::dvec3, 3>& normals) {
    typename SharedMath<Real>::TriangleNormals n{};
    for (int i = 0; i < 3; ++i) {
        n.n0[i] = static_cast<Real>(normals[0][i]);
        n.n1[i] = static_cast<Real>(normals[1][i]);
        n.n2[i] = static_cast<Real>(normals[2][i]);
    }
    return n;
}

template <class Real>
typename SharedMath<Real>::TriangleUVs triangle_uvs(const std::array<glm::dvec2, 3>& uvs) {
    typename SharedMath<Real>::TriangleUVs uv{};
    for (int i = 0; i < 2; ++i) {
        uv.uv0[i] = static_cast<Real>(uvs[0][i]);
        uv.uv1[i] = static_cast<Real>(uvs[1][i]);
        uv.uv2[i] = static_cast<Real>(uvs[2][i]);
    }
    return uv;
}

template <class Real>
typename SharedMath<Real>::BvhNode bvh_node(const BvhTree::Node& n) {
    typename SharedMath<Real>::BvhNode node{};
    for (int i = 0; i < 2; ++i) {
        std::copy(n.bounds[i].begin(), n.bounds[i].end(), node.bounds[i]);
        node.child[i] = n.child[i];
    }
    return node;
}

// The meshes as a renderer reads them: the triangles and, as asked, their
// vertex normals and uvs in parallel, each read straight from its mesh (no
// list of the triangles in double is made: 200 bytes a triangle with its
// normals and uvs). With the BVH (the kernels and the reference trace it):
// in its leaf order, beside its nodes. Without (where Embree traces the
// rays, which finds a triangle by its index in any order: no tree built,
// `nodes` empty): in the scene's order, mesh by mesh in file order.
template <class Real>
struct MeshLayout {
    std::vector<typename SharedMath<Real>::MeshTriangle> triangles;
    std::vector<typename SharedMath<Real>::TriangleNormals> normals;  // if asked
    std::vector<typename SharedMath<Real>::TriangleUVs> uvs;          // if asked
    std::vector<typename SharedMath<Real>::BvhNode> nodes;            // the BVH's, if asked
    int depth = 0;                                                    // the BVH's levels
};

struct MeshLayoutRequest {
    bool bvh = true;
    bool normals = false;
    bool uvs = false;
};

template <class Real>
MeshLayout<Real> mesh_layout(const Scene& scene, const MeshLayoutRequest& request) {
    MeshLayout<Real> layout;
    std::size_t count = 0;
    for (const Mesh& mesh : scene.meshes) count += mesh.triangles.size();
    layout.triangles.reserve(count);
    if (request.normals) layout.normals.reserve(count);
    if (request.uvs) layout.uvs.reserve(count);
    auto add = [&](std::size_t m, const glm::uvec3& t) {
        const Mesh& mesh = scene.meshes[m];
        layout.triangles.push_back(mesh_triangle<Real>({mesh.positions[t.x], mesh.positions[t.y], mesh.positions[t.z]},
                                                       mesh.material, static_cast<int>(m)));
        if (request.normals) layout.normals.push_back(triangle_normals<Real>(vertex_normals(mesh, t)));
        if (request.uvs) layout.uvs.push_back(triangle_uvs<Real>(vertex_uvs(mesh, t)));
    };
    if (!request.bvh) {
        for (std::size_t m = 0; m < scene.meshes.size(); ++m)
            for (const glm::uvec3& t : scene.meshes[m].triangles) add(m, t);
        return layout;
    }
    // The corners go once the tree is built; each leaf slot's triangle is
    // then read from its mesh (scene_triangle_positions' index: the first
    // triangle of each mesh, and past the last).
    BvhTree tree = build_bvh(scene_triangle_positions(scene));
    std::vector<std::size_t> first{0};
    for (const Mesh& mesh : scene.meshes) first.push_back(first.back() + mesh.triangles.size());
    if (tree.leaf_order.size() != count) throw std::runtime_error("BVH: the leaves do not hold every triangle once");
    for (std::uint32_t i : tree.leaf_order) {
        const std::size_t m = std::size_t(std::upper_bound(first.begin(), first.end(), i) - first.begin()) - 1;
        add(m, scene.meshes[m].triangles[i - first[m]]);
    }
    layout.nodes.reserve(tree.nodes.size());
    for (const BvhTree::Node& n : tree.nodes) layout.nodes.push_back(bvh_node<Real>(n));
    layout.depth = tree.depth;
    return layout;
}

}  // namespace wp
