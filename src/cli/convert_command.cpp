#include "cli/convert_command.h"

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>

#include "cli/errors.h"
#include "cli/scene_file.h"
#include "core/atomic_file.h"
#include "image/image_io.h"
#include "scene/gltf_scene.h"
#include "scene/mitsuba_xml.h"
#include "scene/scene_writer.h"

namespace wp::cli {

namespace {

namespace fs = std::filesystem;

// The JSON, its meshes and images, each written atomically; on failure nothing of them stays behind.
void write_scene_json(const MitsubaScene& scene, const fs::path& json_path) {
    check_writable_destination(json_path);
    const SceneJson out = scene_json(scene, json_path);
    std::vector<fs::path> written;
    try {
        for (const MeshFileToWrite& mesh : out.meshes) {
            write_atomically(mesh.path, [&](const fs::path& temporary) {
                try {
                    write_ply(temporary, *mesh.mesh);
                } catch (const std::runtime_error& error) {
                    throw OutputError(error.what());
                }
            });
            written.push_back(mesh.path);
        }
        for (const ImageFileToWrite& image : out.images) {
            write_atomically(image.path, [&](const fs::path& temporary) {
                std::ofstream file(temporary, std::ios::binary);
                file.write(image.bytes->data(), std::streamsize(image.bytes->size()));
                file.close();
                if (!file) throw OutputError(image.path.string() + ": cannot write: " + std::strerror(errno));
            });
            written.push_back(image.path);
        }
        for (const TextureFileToWrite& computed : out.computed) {
            const Texture& t = *computed.texture;
            write_image(Image{t.width, t.height, t.texels}, computed.path.string());  // atomically, or OutputError
            written.push_back(computed.path);
        }
        write_atomically(json_path, [&](const fs::path& temporary) {
            std::ofstream file(temporary);
            file << out.json.dump(1) << "\n";
            file.close();
            if (!file) throw OutputError(json_path.string() + ": cannot write: " + std::strerror(errno));
        });
    } catch (...) {
        std::error_code ignored;
        for (const fs::path& path : written) fs::remove(path, ignored);
        throw;
    }
}

}  // namespace

void add_convert_options(CLI::App& convert, ConvertCommand& command) {
    convert.add_option("scene", command.scene_path, "Mitsuba 3 (.xml) or glTF 2.0 (.gltf, .glb) scene")->required();
    convert.add_option("-o,--output", command.output_path, "The wavepath scene to write (.json)")->required();
    convert
        .add_option("-D,--define", command.defines,
                    "name=value: the value of $name in the scene (overrides its <default>); repeatable")
        ->allow_extra_args(false);
    convert.add_flag("-q,--quiet", command.quiet, "No warnings and no summary on stderr (errors still appear)");
}

void run_convert(const ConvertCommand& command) {
    const bool gltf = is_gltf_scene_path(command.scene_path);
    if (!gltf && !is_mitsuba_scene_path(command.scene_path))
        throw UsageError("convert: reads Mitsuba XML (.xml) and glTF 2.0 (.gltf, .glb) scenes, got " +
                         command.scene_path);
    if (gltf && !command.defines.empty())
        throw UsageError("-D: applies to Mitsuba XML scenes (.xml) only, and " + command.scene_path + " is glTF");
    if (std::filesystem::path(command.output_path).extension() != ".json")
        throw UsageError("convert: -o must name a .json file, got " + command.output_path);
    check_writable_destination(command.output_path);
    const MitsubaScene scene =
        gltf ? read_gltf_scene(command.scene_path, command.mesh_import)
             : read_mitsuba_scene(command.scene_path, parse_defines(command.defines), command.mesh_import);
    if (!command.quiet)
        for (const std::string& line : scene.warnings)
            std::cerr << "wavepath: " << (gltf ? "note: " : "warning: ") << line << std::endl;
    write_scene_json(scene, command.output_path);
    if (!command.quiet)
        std::cerr << "wavepath: wrote " << command.output_path << " (" << scene.scene.meshes.size()
                  << (scene.scene.meshes.size() == 1 ? " mesh" : " meshes") << ", " << scene.scene.textures.size()
                  << (scene.scene.textures.size() == 1 ? " texture" : " textures") << ")" << std::endl;
}

}  // namespace wp::cli
