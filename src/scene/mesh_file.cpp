#include "scene/mesh_file.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>
#include <limits>

#include "import/import_process.h"
#include "import/mesh_invariants.h"
#include "scene/json_field.h"

namespace wp {
namespace {

glm::dvec3 to_dvec3(const glm::vec3& v) { return {v.x, v.y, v.z}; }

// Checked again on what the import process sent (import/mesh_invariants.h).
void check_imported_mesh(const ImportedMesh& mesh) {
    for (const glm::vec3& position : mesh.positions) check_finite_vertex(to_dvec3(position));
    for (const glm::vec2& uv : mesh.uvs) {
        if (!std::isfinite(uv.x) || !std::isfinite(uv.y))
            throw MeshFileError("texture coordinate (" + format_number(uv.x) + ", " + format_number(uv.y) +
                                ") is not finite");
    }
    for (const glm::uvec3& triangle : mesh.triangles) {
        const std::uint32_t corners[] = {triangle.x, triangle.y, triangle.z};
        check_face(corners, mesh.positions.size());
    }
}

// ---- merging the node graph ----

glm::dmat4 to_dmat4(const std::array<float, 16>& row_major) {
    glm::dmat4 result;
    for (int row = 0; row < 4; ++row) {
        for (int column = 0; column < 4; ++column) result[column][row] = row_major[4 * row + column];
    }
    return result;
}

bool within_scene_magnitude(const glm::dvec3& p) {
    return std::fabs(p.x) <= kMaxSceneMagnitude && std::fabs(p.y) <= kMaxSceneMagnitude &&
           std::fabs(p.z) <= kMaxSceneMagnitude;
}

class MeshMerger {
 public:
    MeshMerger(const ImportedScene& scene, const MeshFileOptions& options)
        : scene_(scene), options_(options), found_(options.objects.size(), false) {}

    Mesh merge() {
        // Nodes come each before its children, so a parent's transform and selection are known first.
        std::vector<glm::dmat4> node_to_file(scene_.nodes.size());
        std::vector<bool> selected(scene_.nodes.size());
        for (std::size_t n = 0; n < scene_.nodes.size(); ++n) {
            const ImportedNode& node = scene_.nodes[n];
            const bool root = node.parent == ImportedNode::kNoParent;
            const glm::dmat4 parent_to_file = root ? glm::dmat4(1.0) : node_to_file[node.parent];
            node_to_file[n] = parent_to_file * to_dmat4(node.transform);
            // select() runs for every node: it records the names found and the names offered.
            const bool named = select(node.name, !node.meshes.empty());
            selected[n] = named || (root ? options_.objects.empty() : selected[node.parent]);
            if (selected[n]) add_node_meshes(node, node_to_file[n]);
        }
        check_objects_found();
        finish_normals();
        if (!all_have_uvs_) mesh_.uvs.clear();  // uvs only where every vertex has one
        if (mesh_.triangles.empty()) throw MeshFileError(empty_message());
        return std::move(mesh_);
    }

 private:
    void add_node_meshes(const ImportedNode& node, const glm::dmat4& node_to_file) {
        for (std::uint32_t mesh : node.meshes) add_instance(scene_.meshes[mesh], options_.to_world * node_to_file);
    }

    // Whether the node is one of options.objects; remembers the names of nodes with meshes for messages.
    bool select(const std::string& name, bool has_meshes) {
        bool selected = false;
        for (std::size_t i = 0; i < options_.objects.size(); ++i) {
            if (options_.objects[i] == name) selected = found_[i] = true;
        }
        if (has_meshes && !name.empty()) object_names_.push_back(name);
        return selected;
    }

    void add_instance(const ImportedMesh& source, const glm::dmat4& to_world) {
        const glm::dmat3 linear(to_world);
        const double determinant = glm::determinant(linear);
        if (determinant == 0.0) {  // flattened: every triangle has zero area
            mesh_.degenerate_dropped += source.triangles.size();
            return;
        }
        const std::size_t base = mesh_.positions.size();
        if (base + source.positions.size() > std::numeric_limits<std::uint32_t>::max())
            throw MeshFileError("more than 2^32 - 1 vertices");
        add_vertices(source, to_world, glm::transpose(glm::inverse(linear)));
        // A mirroring transform reverses the winding; swapping two corners keeps
        // the file's front side the front.
        const bool mirrored = determinant < 0.0;
        for (const glm::uvec3& corners : source.triangles) {
            glm::uvec3 triangle(base + corners[0], base + corners[mirrored ? 2 : 1], base + corners[mirrored ? 1 : 2]);
            add_triangle(triangle);
        }
    }

    void add_vertices(const ImportedMesh& source, const glm::dmat4& to_world, const glm::dmat3& normal_to_world) {
        all_have_normals_ &= source.has_normals;
        all_have_uvs_ &= source.has_uvs;
        for (std::size_t v = 0; v < source.positions.size(); ++v) {
            glm::dvec3 position(to_world * glm::dvec4(to_dvec3(source.positions[v]), 1.0));
            if (!within_scene_magnitude(position)) {
                throw MeshFileError("vertex " + vector_text(position) +
                                    " after the transform: magnitude must be <= " + format_number(kMaxSceneMagnitude));
            }
            mesh_.positions.push_back(position);
            if (source.has_normals) mesh_.normals.push_back(normal_to_world * to_dvec3(source.normals[v]));
            if (source.has_uvs) mesh_.uvs.emplace_back(source.uvs[v].x, source.uvs[v].y);
        }
    }

    void add_triangle(const glm::uvec3& triangle) {
        const glm::dvec3& p0 = mesh_.positions[triangle.x];
        const glm::dvec3 area_vector = glm::cross(mesh_.positions[triangle.y] - p0, mesh_.positions[triangle.z] - p0);
        if (area_vector == glm::dvec3(0.0)) {
            ++mesh_.degenerate_dropped;
        } else {
            mesh_.triangles.push_back(triangle);
        }
    }

    // Normals only where every vertex of the file has one, unit length.
    void finish_normals() {
        if (options_.face_normals || !all_have_normals_) {
            mesh_.normals.clear();
            return;
        }
        for (glm::dvec3& normal : mesh_.normals) {
            const double length = glm::length(normal);
            if (!(length > 0.0) || !std::isfinite(length)) {
                throw MeshFileError("vertex normal " + vector_text(normal) +
                                    " after the transform is zero or not finite (\"face_normals\": true ignores "
                                    "the file's normals)");
            }
            normal /= length;
        }
    }

    void check_objects_found() const {
        for (std::size_t i = 0; i < options_.objects.size(); ++i) {
            if (found_[i]) continue;
            std::string names;
            for (const std::string& name : object_names_) names += (names.empty() ? "" : ", ") + name;
            throw MeshFileError("no object named " + nlohmann::json(options_.objects[i]).dump() +
                                " (objects: " + (names.empty() ? "none" : names) + ")");
        }
    }

    std::string empty_message() const {
        if (mesh_.degenerate_dropped == 0) return "empty mesh: no triangles";
        return "empty mesh: all " + std::to_string(mesh_.degenerate_dropped) + " triangles have zero area";
    }

    const ImportedScene& scene_;
    const MeshFileOptions& options_;
    std::vector<bool> found_;
    std::vector<std::string> object_names_;
    bool all_have_normals_ = true;
    bool all_have_uvs_ = true;
    Mesh mesh_;
};

}  // namespace

Mesh mesh_from_import(const ImportedScene& imported, const MeshFileOptions& options) {
    for (const ImportedMesh& mesh : imported.meshes) check_imported_mesh(mesh);
    return MeshMerger(imported, options).merge();
}

void orient_file_uvs(const std::filesystem::path& path, ImportedScene& scene) {
    std::string extension = path.extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    if (extension != ".obj" && extension != ".gltf" && extension != ".glb") return;
    for (ImportedMesh& mesh : scene.meshes)
        for (glm::vec2& uv : mesh.uvs) uv.y = 1.0f - uv.y;
}

Mesh read_mesh_file(const std::filesystem::path& path, const MeshFileOptions& options, MeshImporter& importer) {
    ImportedScene imported = importer.import(path);
    orient_file_uvs(path, imported);
    return mesh_from_import(imported, options);
}

}  // namespace wp
