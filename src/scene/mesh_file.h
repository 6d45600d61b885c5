// Triangle meshes from files (OBJ, PLY, OFF, STL, glTF 2.0), read by assimp
// in a child process (import/import_process.h), checked and transformed to
// world space in double here.
#pragma once

#include <filesystem>
#include <glm/mat4x4.hpp>
#include <string>
#include <vector>

#include "import/import_process.h"
#include "import/imported_scene.h"
#include "import/mesh_file_error.h"
#include "scene/scene.h"

namespace wp {

struct MeshFileOptions {
    glm::dmat4 to_world{1.0};          // applied after the file's own node transforms; invertible
    bool face_normals = false;         // leave Mesh::normals empty even if the file has normals
    std::vector<std::string> objects;  // names of the file's objects (nodes) to load; empty: all
};

// Reads every mesh of the file's node graph, merged into one, with node
// transforms and then `to_world` applied. Fills positions, normals and uvs
// (each only if every vertex has one in the file; v turned as
// orient_file_uvs says), triangles and degenerate_dropped of the result; file
// and material are the caller's. Throws MeshFileError
// (ImportProcessError if the import process failed).
Mesh read_mesh_file(const std::filesystem::path& path, const MeshFileOptions& options, MeshImporter& importer);

// Texture coordinates as textures read them, v = 0 at an image's top row.
// Mitsuba's OBJ reader turns v upside down (an OBJ's v grows upwards, an
// image's rows downwards); its PLY and serialized readers, like assimp, do
// not. glTF's v already grows downwards, and assimp's glTF reader turns it
// into 1 - v. For a file at `path` of those extensions (.obj; .gltf, .glb),
// v becomes 1 - v in `scene`.
void orient_file_uvs(const std::filesystem::path& path, ImportedScene& scene);

// What read_mesh_file makes of an imported file: its meshes checked
// (finite vertices, indices in range), then merged as above.
Mesh mesh_from_import(const ImportedScene& imported, const MeshFileOptions& options);

}  // namespace wp
