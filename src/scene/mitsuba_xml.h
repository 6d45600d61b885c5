// Mitsuba 3 XML scenes (docs/scene-format.md, "Mitsuba XML"): the plugins
// wavepath can render, read into the same Scene the JSON loader makes.
// Whatever the reader does not support, and every malformed file, is one
// SceneError line naming the file, the line and the plugin or property.
#pragma once

#include <glm/mat4x4.hpp>
#include <string>
#include <vector>

#include "import/import_limits.h"
#include "import/imported_scene.h"
#include "scene/mitsuba_xml_tree.h"
#include "scene/scene.h"

namespace wp {

// Where a mesh of the scene came from, so that `wavepath convert` can write
// it: the JSON loader's mesh of `file` under `to_world` and `face_normals`
// (as_file), or `local` (in its own coordinates, winding and normals as the
// scene needs them) written as a file of its own under the same transform.
struct MeshOrigin {
    std::string file;  // the mesh file as found (obj, ply); empty for generated meshes
    bool as_file = false;
    ImportedMesh local;
    glm::dmat4 to_world{1.0};
    bool face_normals = false;
};

// An image a texture was read from that the scene file holds inside it (a
// glTF file's embedded image), so that `wavepath convert` can write it as a
// file of its own.
struct EmbeddedImage {
    std::size_t texture = 0;  // index into scene.textures
    std::string format;       // the extension its file would have ("png", "jpg")
    std::string bytes;
};

struct MitsubaScene {
    Scene scene;                     // not yet rebased to the camera (finish_scene)
    std::vector<MeshOrigin> meshes;  // one per scene.meshes
    std::vector<EmbeddedImage> embedded_images;
    std::vector<std::size_t> computed_textures;  // textures computed from an image (a glTF alpha's opacity)
    std::vector<std::string> warnings;           // one line each, e.g. a pixel filter other than box
};

// Reads the scene; `defines` are -D name=value. Mesh files are imported under `mesh_import`.
MitsubaScene read_mitsuba_scene(const std::string& path, const XmlDefines& defines,
                                const MeshImportLimits& mesh_import = {}, const ShapeProgress& progress = {});

// The same of the scene file's text, as if it were the file `path` (what it names resolves beside it).
MitsubaScene parse_mitsuba_scene(const std::string& text, const std::string& path, const XmlDefines& defines,
                                 const MeshImportLimits& mesh_import = {}, const ShapeProgress& progress = {});

// read_mitsuba_scene, then what every loader does after reading (finish_scene).
Scene load_mitsuba_scene(const std::string& path, const XmlDefines& defines, const MeshImportLimits& mesh_import = {},
                         std::vector<std::string>* warnings = nullptr, const ShapeProgress& progress = {});

// Whether a scene file is read as Mitsuba XML: its name ends in .xml (any case).
bool is_mitsuba_scene_path(const std::string& path);

}  // namespace wp
