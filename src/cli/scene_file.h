// Which reader a scene file gets (wavepath JSON, or Mitsuba 3 XML by its
// .xml extension) and the -D name=value definitions of Mitsuba scenes.
#pragma once

#include <iosfwd>
#include <string>
#include <vector>

#include "import/import_limits.h"
#include "scene/mitsuba_xml_tree.h"
#include "scene/scene.h"

namespace wp::cli {

// "name=value" flags as definitions; UsageError for one without '=' or
// whose name is not letters, digits and '_'.
XmlDefines parse_defines(const std::vector<std::string>& flags);

// The scene: Mitsuba XML when the name ends in .xml, else JSON (where -D is a
// UsageError). The Mitsuba reader's warnings are printed to `warnings`, one
// line each ("wavepath: warning: ..."), when it is not null.
Scene load_scene_file(const std::string& path, const std::vector<std::string>& defines,
                      const MeshImportLimits& mesh_import, std::ostream* warnings);

}  // namespace wp::cli
