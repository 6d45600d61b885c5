#include "scene/mitsuba_shapes.h"

#include <cmath>
#include <glm/geometric.hpp>
#include <glm/mat4x4.hpp>
#include <numbers>

namespace wp {

ImportedMesh cube_mesh() {
    // Each face as its corners (bit 0 of a corner's index: x = +1, bit 1: y, bit 2: z), two counter-clockwise
    // triangles seen from outside, and the uv Mitsuba's cube gives its points: u = (1 + u_sign p[u_axis]) / 2,
    // v = (1 + v_sign p[v_axis]) / 2 (a unit uv square per face, which fixes each face's dp/du).
    struct Face {
        unsigned corners[4];
        int u_axis, u_sign, v_axis, v_sign;
    };
    const Face faces[6] = {{{0, 4, 6, 2}, 1, 1, 2, 1},   {{1, 3, 7, 5}, 1, 1, 2, -1}, {{0, 1, 5, 4}, 2, 1, 0, 1},
                           {{2, 6, 7, 3}, 0, -1, 2, -1}, {{0, 2, 3, 1}, 1, -1, 0, 1}, {{4, 5, 7, 6}, 1, 1, 0, 1}};
    ImportedMesh mesh;
    mesh.has_uvs = true;
    for (const Face& f : faces) {
        const unsigned first = unsigned(mesh.positions.size());
        for (unsigned corner : f.corners) {
            const glm::vec3 p(corner & 1 ? 1.0f : -1.0f, corner & 2 ? 1.0f : -1.0f, corner & 4 ? 1.0f : -1.0f);
            mesh.positions.push_back(p);
            mesh.uvs.push_back(
                {0.5f * (1.0f + float(f.u_sign) * p[f.u_axis]), 0.5f * (1.0f + float(f.v_sign) * p[f.v_axis])});
        }
        mesh.triangles.push_back({first, first + 1, first + 2});
        mesh.triangles.push_back({first, first + 2, first + 3});
    }
    return mesh;
}

ImportedMesh disk_mesh() {
    ImportedMesh mesh;
    mesh.positions.push_back({0.0f, 0.0f, 0.0f});
    for (int i = 0; i < kDiskSegments; ++i) {
        const double angle = 2.0 * std::numbers::pi * i / kDiskSegments;
        mesh.positions.push_back({float(std::cos(angle)), float(std::sin(angle)), 0.0f});
    }
    for (unsigned i = 0; i < unsigned(kDiskSegments); ++i)
        mesh.triangles.push_back({0u, 1u + i, 1u + (i + 1) % unsigned(kDiskSegments)});
    return mesh;
}

ImportedMesh merge_imported(const ImportedScene& scene, bool& exact) {
    ImportedMesh merged;
    exact = true;
    merged.has_normals = true;
    merged.has_uvs = true;
    std::vector<glm::dmat4> node_to_file(scene.nodes.size());
    for (std::size_t n = 0; n < scene.nodes.size(); ++n) {
        const ImportedNode& node = scene.nodes[n];
        glm::dmat4 local;
        for (int row = 0; row < 4; ++row)
            for (int column = 0; column < 4; ++column) local[column][row] = node.transform[4 * row + column];
        node_to_file[n] = node.parent == ImportedNode::kNoParent ? local : node_to_file[node.parent] * local;
        const bool identity = node_to_file[n] == glm::dmat4(1.0);
        exact &= identity || node.meshes.empty();
        const glm::dmat3 normal_matrix = glm::transpose(glm::inverse(glm::dmat3(node_to_file[n])));
        for (std::uint32_t m : node.meshes) {
            const ImportedMesh& mesh = scene.meshes[m];
            const std::uint32_t base = std::uint32_t(merged.positions.size());
            merged.has_normals &= mesh.has_normals;
            merged.has_uvs &= mesh.has_uvs;
            if (mesh.has_uvs) merged.uvs.insert(merged.uvs.end(), mesh.uvs.begin(), mesh.uvs.end());
            for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
                if (identity) {
                    merged.positions.push_back(mesh.positions[v]);
                    if (mesh.has_normals) merged.normals.push_back(mesh.normals[v]);
                    continue;
                }
                merged.positions.push_back(glm::vec3(node_to_file[n] * glm::dvec4(glm::dvec3(mesh.positions[v]), 1.0)));
                if (mesh.has_normals) merged.normals.push_back(glm::vec3(normal_matrix * glm::dvec3(mesh.normals[v])));
            }
            for (const glm::uvec3& t : mesh.triangles) merged.triangles.push_back(t + glm::uvec3(base));
        }
    }
    if (!merged.has_normals || merged.positions.empty()) {
        merged.has_normals = false;
        merged.normals.clear();
    }
    if (!merged.has_uvs || merged.positions.empty()) {
        merged.has_uvs = false;
        merged.uvs.clear();
    }
    return merged;
}

void compute_vertex_normals(Mesh& mesh) {
    std::vector<glm::dvec3> normals(mesh.positions.size(), glm::dvec3(0.0));
    for (const glm::uvec3& t : mesh.triangles) {
        const glm::dvec3 p[3] = {mesh.positions[t.x], mesh.positions[t.y], mesh.positions[t.z]};
        const glm::dvec3 n = glm::cross(p[1] - p[0], p[2] - p[0]);
        const double length = glm::length(n);
        if (!(length > 0.0)) continue;
        for (int j = 0; j < 3; ++j) {
            const glm::dvec3 a = glm::normalize(p[(j + 1) % 3] - p[j]), b = glm::normalize(p[(j + 2) % 3] - p[j]);
            // The angle between a and b, accurately for small and large angles.
            const double angle = 2.0 * std::atan2(glm::length(a - b), glm::length(a + b));
            normals[t[j]] += n / length * angle;
        }
    }
    for (glm::dvec3& n : normals) {
        const double length = glm::length(n);
        n = length > 0.0 && std::isfinite(length) ? n / length : glm::dvec3(0.0, 0.0, 1.0);
    }
    mesh.normals = std::move(normals);
}

}  // namespace wp
