// The first stage of reading a Mitsuba 3 XML scene (docs/scene-format.md,
// "Mitsuba XML"): the file and what it includes as one tree of elements, as
// Mitsuba's parser sees it before it instantiates plugins. pugixml parses
// each file; this stage inlines <include>s, applies <default>s and the
// command line's -D definitions to every `$name` in attribute values (in
// document order, as Mitsuba does), collects <path> search folders, and
// renames the properties of files older than version 2.0.0 as Mitsuba's
// upgrade does (camelCase to snake_case). Every element keeps its file and
// line for messages.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace wp {

struct XmlElement {
    std::string tag;
    std::vector<std::pair<std::string, std::string>> attributes;  // in document order, after substitution
    std::vector<XmlElement> children;                             // elements only, includes inlined
    std::string file;                                             // the file it is in, as named for messages
    int line = 0;                                                 // 1-based

    // The attribute's value, or nullptr.
    const std::string* attribute(std::string_view name) const;
    // "<file>:<line>"
    std::string where() const;
};

// -D name=value definitions, in command-line order.
using XmlDefines = std::vector<std::pair<std::string, std::string>>;

struct XmlScene {
    XmlElement root;  // <scene>
    // Where file names (meshes) are looked up, first to last: the <path>
    // folders (the last one given first, as Mitsuba prepends them), then the
    // scene file's folder.
    std::vector<std::filesystem::path> search_paths;
};

// Nesting deeper than this (elements in elements, includes counted) is refused.
inline constexpr int kMaxXmlDepth = 64;
// Includes nested deeper than this are refused (Mitsuba's limit).
inline constexpr int kMaxIncludeDepth = 15;

// Throws SceneError "<file>:<line>: <problem>" (or "<file>: <problem>" where
// no line applies) for any problem: malformed XML, a missing file, an
// include cycle, an undefined $name, a -D definition the scene never uses.
XmlScene read_xml_scene(const std::string& path, const XmlDefines& defines);
// The same of the scene file's text, as if it were the file `path` (includes resolve beside it).
XmlScene parse_xml_scene(const std::string& text, const std::string& path, const XmlDefines& defines);

// Throws SceneError "<element's file>:<line>: <problem>".
[[noreturn]] void fail_at(const XmlElement& element, std::string_view problem);

// `name` resolved against the search paths: the first that names an existing
// file, else the first candidate (absolute names as they are).
std::filesystem::path resolve_scene_file(const XmlScene& scene, const std::string& name);

}  // namespace wp
