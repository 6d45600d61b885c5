// `wavepath convert SCENE.xml -o SCENE.json`: a Mitsuba 3 XML scene as the
// equivalent wavepath JSON (docs/scene-format.md, "Mitsuba XML"), its
// generated meshes as PLY files beside the JSON.
#pragma once

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "import/import_limits.h"

namespace wp::cli {

struct ConvertCommand {
    std::string scene_path;
    std::string output_path;
    std::vector<std::string> defines;  // -D name=value
    MeshImportLimits mesh_import;
    bool quiet = false;
};

void add_convert_options(CLI::App& convert, ConvertCommand& command);

// Throws SceneError (the scene), UsageError (-D, a scene that is not XML,
// an output that is not .json) or OutputError; writes nothing on failure.
void run_convert(const ConvertCommand& command);

}  // namespace wp::cli
