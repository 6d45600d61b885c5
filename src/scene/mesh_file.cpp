#include "scene/mesh_file.h"

#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <algorithm>
#include <assimp/DefaultLogger.hpp>
#include <assimp/Importer.hpp>
#include <assimp/LogStream.hpp>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>
#include <limits>
#include <memory>

#include "scene/assimp_prechecks.h"
#include "scene/json_field.h"

namespace wp {
namespace {

// ---- assimp's log ----

// assimp reports some problems only in its log and then carries on with a
// guess: an OFF index out of range is clamped, a polygon without an ear is
// fanned. This collects the error lines logged while it lives (DefaultLogger
// is global: imports must not run on several threads at once).
class AssimpErrorCapture : private Assimp::LogStream {
 public:
    AssimpErrorCapture() : created_logger_(Assimp::DefaultLogger::isNullLogger()) {
        if (created_logger_) Assimp::DefaultLogger::create(nullptr, Assimp::Logger::NORMAL, 0);
        Assimp::DefaultLogger::get()->attachStream(this, Assimp::Logger::Err);
    }
    ~AssimpErrorCapture() override {
        Assimp::DefaultLogger::get()->detachStream(this, Assimp::Logger::Err);  // ownership comes back
        if (created_logger_) Assimp::DefaultLogger::kill();
    }
    AssimpErrorCapture(const AssimpErrorCapture&) = delete;
    AssimpErrorCapture& operator=(const AssimpErrorCapture&) = delete;

    // The first logged error containing `text`, without assimp's prefix; empty if none.
    std::string find(std::string_view text) const {
        for (const std::string& line : errors_) {
            if (line.find(text) != std::string::npos) return line;
        }
        return {};
    }

 private:
    void write(const char* message) override {
        std::string line(message);
        static constexpr std::string_view kPrefix = "Error, T0: ";
        if (line.rfind(kPrefix, 0) == 0) line.erase(0, kPrefix.size());
        while (!line.empty() && (line.back() == '\n' || line.back() == '\r')) line.pop_back();
        errors_.push_back(line);
    }

    bool created_logger_;
    std::vector<std::string> errors_;
};

// assimp's messages may span lines; ours are one line.
std::string one_line(std::string text) {
    std::replace(text.begin(), text.end(), '\n', ' ');
    std::replace(text.begin(), text.end(), '\r', ' ');
    while (!text.empty() && text.back() == ' ') text.pop_back();
    return text;
}

// ---- reading ----

std::string vector_text(const glm::dvec3& v) {
    return "(" + format_number(v.x) + ", " + format_number(v.y) + ", " + format_number(v.z) + ")";
}

glm::dvec3 to_dvec3(const aiVector3D& v) { return {v.x, v.y, v.z}; }

// assimp's own message for a missing file names neither errno nor the reason.
void check_readable(const std::filesystem::path& path) {
    std::unique_ptr<std::FILE, int (*)(std::FILE*)> file(std::fopen(path.c_str(), "rb"), &std::fclose);
    if (!file) throw MeshFileError(std::string("cannot open: ") + std::strerror(errno));
    errno = 0;
    std::fgetc(file.get());
    if (std::ferror(file.get())) throw MeshFileError(std::string("cannot read: ") + std::strerror(errno));
}

// Checked before assimp's post-processing, which reads vertices through the
// indices and sorts positions (a NaN there merges unrelated vertices).
void check_raw_mesh(const aiMesh& mesh) {
    for (unsigned v = 0; v < mesh.mNumVertices; ++v) {
        glm::dvec3 position = to_dvec3(mesh.mVertices[v]);
        if (!std::isfinite(position.x) || !std::isfinite(position.y) || !std::isfinite(position.z))
            throw MeshFileError("vertex " + vector_text(position) + " is not finite");
    }
    for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
        const aiFace& face = mesh.mFaces[f];
        if (face.mNumIndices < 3) {
            throw MeshFileError("a face of " + std::to_string(face.mNumIndices) +
                                " vertices (a point or a line) cannot be triangulated");
        }
        for (unsigned i = 0; i < face.mNumIndices; ++i) {
            if (face.mIndices[i] >= mesh.mNumVertices) {
                throw MeshFileError("vertex index " + std::to_string(face.mIndices[i]) + " out of range (" +
                                    std::to_string(mesh.mNumVertices) + " vertices)");
            }
        }
    }
}

// The file's scene, triangulated with identical vertices joined, or MeshFileError.
const aiScene* import_triangles(Assimp::Importer& importer, const std::filesystem::path& path) {
    AssimpErrorCapture log;
    const aiScene* scene = importer.ReadFile(path.string(), 0);
    if (!scene) throw MeshFileError("assimp cannot read it: " + one_line(importer.GetErrorString()));
    if (std::string error = log.find("out of range"); !error.empty())
        throw MeshFileError("index out of range: " + one_line(error));
    for (unsigned m = 0; m < scene->mNumMeshes; ++m) check_raw_mesh(*scene->mMeshes[m]);

    scene = importer.ApplyPostProcessing(aiProcess_Triangulate);
    if (std::string error = log.find("triangulate"); !error.empty())
        throw MeshFileError("a polygon cannot be triangulated: " + one_line(error));
    if (scene) scene = importer.ApplyPostProcessing(aiProcess_JoinIdenticalVertices);
    if (!scene) throw MeshFileError("assimp cannot process it: " + one_line(importer.GetErrorString()));
    return scene;
}

// ---- merging the node graph ----

glm::dmat4 to_dmat4(const aiMatrix4x4& m) {
    glm::dmat4 result;
    for (int row = 0; row < 4; ++row) {
        for (int column = 0; column < 4; ++column) result[column][row] = m[row][column];
    }
    return result;
}

bool within_scene_magnitude(const glm::dvec3& p) {
    return std::fabs(p.x) <= kMaxSceneMagnitude && std::fabs(p.y) <= kMaxSceneMagnitude &&
           std::fabs(p.z) <= kMaxSceneMagnitude;
}

class MeshMerger {
 public:
    MeshMerger(const aiScene& scene, const MeshFileOptions& options)
        : scene_(scene), options_(options), found_(options.objects.size(), false) {}

    Mesh merge() {
        if (scene_.mRootNode) add_node(*scene_.mRootNode, glm::dmat4(1.0), options_.objects.empty());
        check_objects_found();
        finish_normals();
        if (mesh_.triangles.empty()) throw MeshFileError(empty_message());
        return std::move(mesh_);
    }

 private:
    void add_node(const aiNode& node, const glm::dmat4& parent_to_file, bool selected) {
        const glm::dmat4 node_to_file = parent_to_file * to_dmat4(node.mTransformation);
        selected |= select(node.mName.C_Str(), node.mNumMeshes > 0);
        if (selected) {
            for (unsigned i = 0; i < node.mNumMeshes; ++i)
                add_instance(*scene_.mMeshes[node.mMeshes[i]], options_.to_world * node_to_file);
        }
        for (unsigned i = 0; i < node.mNumChildren; ++i) add_node(*node.mChildren[i], node_to_file, selected);
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

    void add_instance(const aiMesh& source, const glm::dmat4& to_world) {
        const glm::dmat3 linear(to_world);
        const double determinant = glm::determinant(linear);
        if (determinant == 0.0) {  // flattened: every triangle has zero area
            mesh_.degenerate_dropped += source.mNumFaces;
            return;
        }
        const std::size_t base = mesh_.positions.size();
        if (base + source.mNumVertices > std::numeric_limits<std::uint32_t>::max())
            throw MeshFileError("more than 2^32 - 1 vertices");
        add_vertices(source, to_world, glm::transpose(glm::inverse(linear)));
        // A mirroring transform reverses the winding; swapping two corners keeps
        // the file's front side the front.
        const bool mirrored = determinant < 0.0;
        for (unsigned f = 0; f < source.mNumFaces; ++f) {
            const unsigned* index = source.mFaces[f].mIndices;
            glm::uvec3 triangle(base + index[0], base + index[mirrored ? 2 : 1], base + index[mirrored ? 1 : 2]);
            add_triangle(triangle);
        }
    }

    void add_vertices(const aiMesh& source, const glm::dmat4& to_world, const glm::dmat3& normal_to_world) {
        all_have_normals_ &= source.mNormals != nullptr;
        for (unsigned v = 0; v < source.mNumVertices; ++v) {
            glm::dvec3 position(to_world * glm::dvec4(to_dvec3(source.mVertices[v]), 1.0));
            if (!within_scene_magnitude(position)) {
                throw MeshFileError("vertex " + vector_text(position) +
                                    " after the transform: magnitude must be <= " + format_number(kMaxSceneMagnitude));
            }
            mesh_.positions.push_back(position);
            if (source.mNormals) mesh_.normals.push_back(normal_to_world * to_dvec3(source.mNormals[v]));
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

    const aiScene& scene_;
    const MeshFileOptions& options_;
    std::vector<bool> found_;
    std::vector<std::string> object_names_;
    bool all_have_normals_ = true;
    Mesh mesh_;
};

}  // namespace

Mesh read_mesh_file(const std::filesystem::path& path, const MeshFileOptions& options) {
    check_readable(path);
    check_before_assimp(path);
    Assimp::Importer importer;
    const aiScene* scene = import_triangles(importer, path);
    return MeshMerger(*scene, options).merge();
}

}  // namespace wp
