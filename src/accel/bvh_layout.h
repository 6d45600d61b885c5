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

// The triangles' vertex normals in the tree's leaf order, for scenes that
// shade with them (FeatureSet::shading_normals).
template <class Real>
std::vector<typename SharedMath<Real>::TriangleNormals> triangle_normals(const SceneBvh& bvh) {
    std::vector<typename SharedMath<Real>::TriangleNormals> normals;
    normals.reserve(bvh.triangles.size());
    for (const SceneTriangle& t : bvh.triangles) {
        typename SharedMath<Real>::TriangleNormals n{};
        for (int i = 0; i < 3; ++i) {
            n.n0[i] = static_cast<Real>(t.normals[0][i]);
            n.n1[i] = static_cast<Real>(t.normals[1][i]);
            n.n2[i] = static_cast<Real>(t.normals[2][i]);
        }
        normals.push_back(n);
    }
    return normals;
}

// The triangles' uvs in the tree's leaf order, for scenes with textures
// (FeatureSet::textures).
template <class Real>
std::vector<typename SharedMath<Real>::TriangleUVs> triangle_uvs(const SceneBvh& bvh) {
    std::vector<typename SharedMath<Real>::TriangleUVs> uvs;
    uvs.reserve(bvh.triangles.size());
    for (const SceneTriangle& t : bvh.triangles) {
        typename SharedMath<Real>::TriangleUVs uv{};
        for (int i = 0; i < 2; ++i) {
            uv.uv0[i] = static_cast<Real>(t.uvs[0][i]);
            uv.uv1[i] = static_cast<Real>(t.uvs[1][i]);
            uv.uv2[i] = static_cast<Real>(t.uvs[2][i]);
        }
        uvs.push_back(uv);
    }
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

}  // namespace wp
