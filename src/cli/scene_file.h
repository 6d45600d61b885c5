// Which reader a scene file gets (wavepath JSON, Mitsuba 3 XML by its .xml
// extension, glTF 2.0 by .gltf or .glb) and the -D name=value definitions of
// Mitsuba scenes.
#pragma once

#include <iosfwd>
#include <string>
#include <vector>

#include "cli/progress.h"
#include "import/import_limits.h"
#include "scene/mitsuba_xml_tree.h"
#include "scene/scene.h"

namespace wp::cli {

// "name=value" flags as definitions; UsageError for one without '=' or
// whose name is not letters, digits and '_'.
XmlDefines parse_defines(const std::vector<std::string>& flags);

// The scene: Mitsuba XML when the name ends in .xml, glTF when it ends in
// .gltf or .glb, else JSON (-D is a UsageError but for XML). The Mitsuba
// reader's warnings ("wavepath: warning: ...") and the glTF reader's notes on
// the defaults it took ("wavepath: note: ...") are printed to `warnings`, one
// line each, when it is not null. `progress`, when
// not null, shows the shapes read ("120/500 shapes"): a scene of many mesh
// files takes seconds to load. Its lines start 5 s into the load (a bar at
// once on a terminal), so a quick load, and a quick failure's one error
// line, show nothing else.
Scene load_scene_file(const std::string& path, const std::vector<std::string>& defines,
                      const MeshImportLimits& mesh_import, std::ostream* warnings,
                      ProgressReporter* progress = nullptr);

}  // namespace wp::cli
