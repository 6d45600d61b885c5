// The meshes' BVH and triangles in the layout kernels/shared/bvh.h traverses,
// for one precision: the device upload takes SharedMath<float>'s, the
// reference its own Real's. The one conversion from the builder's double data.
#pragma once

#include <algorithm>
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

// The triangles' vertex normals in the tree's leaf order, for scenes that
// shade with them (FeatureSet::shading_normals).
template <class Real>
std::vector<typename SharedMath<Real>::TriangleNormals> triangle_normals(const SceneBvh& bvh) {
    std::vector<typename SharedMath<Real>::TriangleNormals> normals;
    normals.reserve(bvh.triangles.size());
    for (const SceneTriangle& t : bvh.triangles) normals.push_back(triangle_normals<Real>(t.normals));
    return normals;
}

// The triangles' uvs in the tree's leaf order, for scenes with textures
// (FeatureSet::textures).
template <class Real>
std::vector<typename SharedMath<Real>::TriangleUVs> triangle_uvs(const SceneBvh& bvh) {
    std::vector<typename SharedMath<Real>::TriangleUVs> uvs;
    uvs.reserve(bvh.triangles.size());
    for (const SceneTriangle& t : bvh.triangles) uvs.push_back(triangle_uvs<Real>(t.uvs));
    return uvs;
}

template <class Real>
struct TraversableBvh {
    std::vector<typename SharedMath<Real>::MeshTriangle> triangles;  // in the tree's leaf order
    std::vector<typename SharedMath<Real>::BvhNode> nodes;
};

template <class Real>
TraversableBvh<Real> traversable_bvh(const SceneBvh& bvh) {
    TraversableBvh<Real> flat;
    flat.triangles.reserve(bvh.triangles.size());
    flat.nodes.reserve(bvh.tree.nodes.size());
    for (const SceneTriangle& t : bvh.triangles)
        flat.triangles.push_back(mesh_triangle<Real>(t.positions, t.material, t.mesh));
    for (const BvhTree::Node& n : bvh.tree.nodes) {
        typename SharedMath<Real>::BvhNode node{};
        for (int i = 0; i < 2; ++i) {
            std::copy(n.bounds[i].begin(), n.bounds[i].end(), node.bounds[i]);
            node.child[i] = n.child[i];
        }
        flat.nodes.push_back(node);
    }
    return flat;
}

// The meshes as a renderer reads them: the triangles and, as asked, their
// vertex normals and uvs in parallel. With the BVH (the kernels and the
// reference trace it): in its leaf order, beside its nodes. Without (where
// Embree traces the rays, which finds a triangle by its index in any order:
// no tree built, `nodes` empty): in the scene's order, mesh by mesh in file
// order, straight from the meshes, so that no SceneTriangle is made.
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
    if (request.bvh) {
        SceneBvh bvh = build_scene_bvh(scene);
        TraversableBvh<Real> flat = traversable_bvh<Real>(bvh);
        if (request.normals) layout.normals = triangle_normals<Real>(bvh);
        if (request.uvs) layout.uvs = triangle_uvs<Real>(bvh);
        layout.triangles = std::move(flat.triangles);
        layout.nodes = std::move(flat.nodes);
        layout.depth = bvh.tree.depth;
        return layout;
    }
    std::size_t count = 0;
    for (const Mesh& mesh : scene.meshes) count += mesh.triangles.size();
    layout.triangles.reserve(count);
    if (request.normals) layout.normals.reserve(count);
    if (request.uvs) layout.uvs.reserve(count);
    for (std::size_t m = 0; m < scene.meshes.size(); ++m) {
        const Mesh& mesh = scene.meshes[m];
        for (const glm::uvec3& t : mesh.triangles) {
            layout.triangles.push_back(mesh_triangle<Real>(
                {mesh.positions[t.x], mesh.positions[t.y], mesh.positions[t.z]}, mesh.material, int(m)));
            if (request.normals) layout.normals.push_back(triangle_normals<Real>(vertex_normals(mesh, t)));
            if (request.uvs) layout.uvs.push_back(triangle_uvs<Real>(vertex_uvs(mesh, t)));
        }
    }
    return layout;
}

}  // namespace wp
