// The bounding volume hierarchy over the scene's mesh triangles: a binary
// tree built with Embree's SAH builder into nodes of our own, then flattened
// depth first into the layout the kernels and the reference traverse
// (kernels/shared/bvh.h). The flattened tree is a function of the triangles
// alone: the same bytes for any thread count and run.
#pragma once

#include <array>
#include <cstdint>
#include <glm/vec3.hpp>
#include <vector>

#include "scene/scene.h"

namespace wp {

using TrianglePositions = std::array<glm::dvec3, 3>;

struct BvhTree {
    struct Node {
        std::array<std::array<float, 6>, 2> bounds{};  // per child: lower xyz, upper xyz, rounded outward
        std::array<std::uint32_t, 2> child{};          // as kernels/shared/bvh.h encodes them
    };
    std::vector<Node> nodes;                // nodes[0] is the root
    std::vector<std::uint32_t> leaf_order;  // for each triangle slot of the leaves, the input triangle's index
    int depth = 0;                          // levels of nodes
};

// Builds the tree (binned SAH, leaves of up to 4 triangles) on `threads`
// threads (0: all). Throws std::runtime_error when Embree fails.
BvhTree build_bvh(const std::vector<TrianglePositions>& triangles, int threads = 0);

// A mesh triangle's vertex attributes, as every layout of the triangles
// takes them: its vertices' shading normals (all zero: the mesh has none)
// and uvs (a mesh without: (0, 0), (1, 0), (0, 1), whose interpolation is
// the barycentric coordinates).
std::array<glm::dvec3, 3> vertex_normals(const Mesh& mesh, const glm::uvec3& triangle);
std::array<glm::dvec2, 3> vertex_uvs(const Mesh& mesh, const glm::uvec3& triangle);

// Every mesh triangle's corners, mesh by mesh in file order: what build_bvh
// takes for a scene (the tree's leaf_order indexes this list).
std::vector<TrianglePositions> scene_triangle_positions(const Scene& scene);

}  // namespace wp
