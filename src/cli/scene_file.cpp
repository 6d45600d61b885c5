#include "cli/scene_file.h"

#include <algorithm>
#include <cctype>
#include <ostream>

#include "cli/errors.h"
#include "scene/gltf_scene.h"
#include "scene/mitsuba_xml.h"

namespace wp::cli {

XmlDefines parse_defines(const std::vector<std::string>& flags) {
    XmlDefines defines;
    for (const std::string& flag : flags) {
        const std::size_t equals = flag.find('=');
        const std::string name = flag.substr(0, equals);
        const bool name_ok = !name.empty() && std::all_of(name.begin(), name.end(), [](char c) {
            return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
        });
        if (equals == std::string::npos || !name_ok)
            throw UsageError("-D: expected name=value (name of letters, digits and '_'), got '" + flag + "'");
        defines.push_back({name, flag.substr(equals + 1)});
    }
    return defines;
}

namespace {

ShapeProgress shapes_read(ProgressReporter* progress) {
    if (!progress) return {};
    return [progress, planned = false](std::size_t read, std::size_t count) mutable {
        if (!planned) progress->set_plan({0.0, double(count), 0.0, "shapes", 0});
        planned = true;
        progress->update(double(read) / double(count));
    };
}

}  // namespace

Scene load_scene_file(const std::string& path, const std::vector<std::string>& defines,
                      const MeshImportLimits& mesh_import, std::ostream* warnings, ProgressReporter* progress) {
    const XmlDefines parsed = parse_defines(defines);
    if (is_gltf_scene_path(path)) {
        if (!parsed.empty())
            throw UsageError("-D: applies to Mitsuba XML scenes (.xml) only, and " + path + " is glTF");
        std::vector<std::string> notes;
        Scene scene = load_gltf_scene(path, mesh_import, &notes);
        if (warnings)
            for (const std::string& line : notes) *warnings << "wavepath: note: " << line << std::endl;
        return scene;
    }
    if (!is_mitsuba_scene_path(path)) {
        if (!parsed.empty())
            throw UsageError("-D: applies to Mitsuba XML scenes (.xml) only, and " + path + " is read as JSON");
        Scene scene = load_scene(path, mesh_import, shapes_read(progress));
        if (progress) progress->finish_shown();
        return scene;
    }
    std::vector<std::string> lines;
    Scene scene = load_mitsuba_scene(path, parsed, mesh_import, &lines, shapes_read(progress));
    if (progress) progress->finish_shown();
    if (warnings)
        for (const std::string& line : lines) *warnings << "wavepath: warning: " << line << std::endl;
    return scene;
}

}  // namespace wp::cli
