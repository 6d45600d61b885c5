// parse_scene / load_scene: JSON text -> validated, camera-relative Scene.
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>
#include <vector>

#include "scene/json_field.h"
#include "scene/json_syntax.h"
#include "scene/scene.h"
#include "scene/scene_sections.h"
#include "scene/texture_section.h"

namespace wp {
namespace {

// Moves the camera to the origin; kernels in float then keep full precision
// near the viewer wherever the scene sits in the file's coordinates.
void rebase_to_camera(Scene& scene) {
    const glm::dvec3 origin = scene.camera.position;
    scene.world_offset = origin;
    scene.camera.position = glm::dvec3(0.0);
    scene.camera.look_at -= origin;
    for (Sphere& sphere : scene.spheres) sphere.center -= origin;
    for (Plane& plane : scene.planes) plane.point -= origin;
    for (Quad& quad : scene.quads) quad.corner -= origin;
    for (Mesh& mesh : scene.meshes) {
        for (glm::dvec3& position : mesh.positions) position -= origin;
    }
    for (PointLight& light : scene.point_lights) light.position -= origin;
}

// The mesh files the shapes name, in order, for the importer to start on
// ahead; read_shapes checks every shape as it comes (a malformed one is
// left out here).
std::vector<std::filesystem::path> named_mesh_files(const nlohmann::json& shapes, const std::string& source) {
    std::vector<std::filesystem::path> files;
    if (!shapes.is_array()) return files;
    for (const nlohmann::json& shape : shapes) {
        if (!shape.is_object() || shape.value("type", nlohmann::json()) != "mesh") continue;
        const nlohmann::json file = shape.value("file", nlohmann::json());
        if (file.is_string()) files.push_back(std::filesystem::path(source).parent_path() / file.get<std::string>());
    }
    return files;
}

std::string read_text_file(const std::string& path) {
    std::unique_ptr<std::FILE, int (*)(std::FILE*)> file(std::fopen(path.c_str(), "rb"), &std::fclose);
    if (!file) throw SceneError(path + ": cannot open scene file: " + std::strerror(errno));
    std::string text;
    char buffer[1 << 16];
    std::size_t count;
    while ((count = std::fread(buffer, 1, sizeof buffer, file.get())) > 0) text.append(buffer, count);
    if (std::ferror(file.get())) throw SceneError(path + ": cannot read scene file: " + std::strerror(errno));
    return text;
}

}  // namespace

void finish_scene(Scene& scene) {
    rebase_to_camera(scene);
    build_light_table(scene);
}

Scene parse_scene(const std::string& json_text, const std::string& source_name, const MeshImportLimits& mesh_import,
                  const ShapeProgress& progress) {
    const nlohmann::json document = parse_json_strictly(json_text, source_name);
    const JsonField root = root_field(document, source_name);
    root.allow_only_keys({"camera", "render", "background", "lights", "textures", "materials", "shapes"});

    Scene scene;
    scene.source = source_name;
    scene.camera = read_camera(root.member("camera"));
    if (auto render = root.optional_member("render")) scene.render = read_render(*render);
    if (auto background = root.optional_member("background")) {
        scene.background = background->vec3_in(0.0, kMaxSceneMagnitude);
    }
    if (auto textures = root.optional_member("textures")) scene.textures = read_textures(*textures, source_name);
    if (auto materials = root.optional_member("materials"))
        scene.materials = read_materials(*materials, scene.textures);
    if (auto shapes = root.optional_member("shapes")) {
        MeshImporter importer(mesh_import);
        importer.expect(named_mesh_files(document.at("shapes"), source_name));
        read_shapes(*shapes, scene, importer, progress);
    }
    if (auto lights = root.optional_member("lights")) read_lights(*lights, scene);

    finish_scene(scene);
    if (const std::string problem = sppm_problem(scene); !problem.empty())
        root.member("render").member("integrator").fail(problem);
    return scene;
}

Scene load_scene(const std::string& path, const MeshImportLimits& mesh_import, const ShapeProgress& progress) {
    return parse_scene(read_text_file(path), path, mesh_import, progress);
}

}  // namespace wp
