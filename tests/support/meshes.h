// Closed triangle meshes built in code, for the BVH, watertightness and
// rendering tests: counter-clockwise seen from outside, so fronts face out.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <glm/geometric.hpp>
#include <glm/vec3.hpp>
#include <map>
#include <utility>
#include <vector>

#include "scene/scene.h"

namespace wp::test {

// The unit cube [0, 1]^3: 8 vertices, 12 triangles.
inline Mesh unit_cube(int material) {
    Mesh mesh;
    mesh.file = "cube (test)";
    mesh.material = material;
    for (int i = 0; i < 8; ++i) mesh.positions.push_back(glm::dvec3(i & 1, (i >> 1) & 1, (i >> 2) & 1));
    // Each face as (a, b, c, d) counter-clockwise from outside.
    const int faces[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    for (const auto& f : faces) {
        mesh.triangles.push_back(glm::uvec3(f[0], f[1], f[2]));
        mesh.triangles.push_back(glm::uvec3(f[0], f[2], f[3]));
    }
    return mesh;
}

// An icosphere of radius 1 about the origin: the icosahedron, each triangle
// split into 4 `subdivisions` times, vertices pushed onto the sphere (shared
// between neighbouring triangles, so edges are shared exactly).
inline Mesh icosphere(int subdivisions, int material) {
    Mesh mesh;
    mesh.file = "icosphere (test)";
    mesh.material = material;
    const double t = (1.0 + std::sqrt(5.0)) / 2.0;
    for (glm::dvec3 v : {glm::dvec3(-1, t, 0), glm::dvec3(1, t, 0), glm::dvec3(-1, -t, 0), glm::dvec3(1, -t, 0),
                         glm::dvec3(0, -1, t), glm::dvec3(0, 1, t), glm::dvec3(0, -1, -t), glm::dvec3(0, 1, -t),
                         glm::dvec3(t, 0, -1), glm::dvec3(t, 0, 1), glm::dvec3(-t, 0, -1), glm::dvec3(-t, 0, 1)})
        mesh.positions.push_back(glm::normalize(v));
    std::vector<glm::uvec3> faces{{0, 11, 5},  {0, 5, 1},  {0, 1, 7},  {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                                  {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
                                  {3, 8, 9},   {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
    for (int level = 0; level < subdivisions; ++level) {
        std::map<std::pair<unsigned, unsigned>, unsigned> midpoints;
        auto midpoint = [&](unsigned a, unsigned b) {
            auto key = std::minmax(a, b);
            auto [it, added] = midpoints.try_emplace(key, unsigned(mesh.positions.size()));
            if (added) mesh.positions.push_back(glm::normalize(mesh.positions[a] + mesh.positions[b]));
            return it->second;
        };
        std::vector<glm::uvec3> finer;
        for (const glm::uvec3& f : faces) {
            unsigned ab = midpoint(f.x, f.y), bc = midpoint(f.y, f.z), ca = midpoint(f.z, f.x);
            finer.insert(finer.end(), {{f.x, ab, ca}, {f.y, bc, ab}, {f.z, ca, bc}, {ab, bc, ca}});
        }
        faces = std::move(finer);
    }
    mesh.triangles = faces;
    return mesh;
}

// The mesh scaled by `scale` about the origin, then moved by `offset`.
inline Mesh transformed(Mesh mesh, double scale, const glm::dvec3& offset) {
    for (glm::dvec3& p : mesh.positions) p = p * scale + offset;
    return mesh;
}

}  // namespace wp::test
