// Triangle meshes from files (OBJ, PLY, OFF, STL, glTF 2.0, and whatever
// else assimp reads), checked and transformed to world space in double.
#pragma once

#include <filesystem>
#include <glm/mat4x4.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "scene/scene.h"

namespace wp {

// A problem with a mesh file, one line without the file's name (the scene
// loader prefixes the scene file, the JSON path and the mesh file).
class MeshFileError : public std::runtime_error {
 public:
    using std::runtime_error::runtime_error;
};

struct MeshFileOptions {
    glm::dmat4 to_world{1.0};          // applied after the file's own node transforms; invertible
    bool face_normals = false;         // leave Mesh::normals empty even if the file has normals
    std::vector<std::string> objects;  // names of the file's objects (nodes) to load; empty: all
};

// Reads every mesh of the file's node graph, merged into one, with node
// transforms and then `to_world` applied. Fills positions, normals (only if
// every vertex has one in the file), triangles and degenerate_dropped of the
// result; file and material are the caller's. Throws MeshFileError.
Mesh read_mesh_file(const std::filesystem::path& path, const MeshFileOptions& options);

}  // namespace wp
