#include "scene/mitsuba_xml_tree.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cstdio>
#include <cstring>
#include <memory>
#include <pugixml.hpp>
#include <system_error>

#include "scene/scene.h"

namespace wp {
namespace {

namespace fs = std::filesystem;

// One file's text and where its lines start, for line numbers of byte offsets.
struct SourceFile {
    std::string name;  // for messages
    fs::path path;
    std::string text;
    std::vector<std::size_t> line_starts{0};
    bool legacy = false;  // version < 2.0.0: properties renamed as Mitsuba's upgrade does

    int line_of(std::ptrdiff_t offset) const {
        if (offset < 0) return 0;
        auto next = std::upper_bound(line_starts.begin(), line_starts.end(), std::size_t(offset));
        return int(next - line_starts.begin());
    }
};

[[noreturn]] void fail_in(const std::string& file, int line, std::string_view problem) {
    std::string where = file;
    if (line > 0) where += ":" + std::to_string(line);
    throw SceneError(where + ": " + std::string(problem));
}

std::string read_file(const fs::path& path, const std::string& name, const std::string& context) {
    // Not a FIFO or a device, which could be read without end.
    std::error_code error;
    if (fs::exists(path, error) && !fs::is_regular_file(path, error))
        throw SceneError(context + "cannot read scene file " + name + ": not a regular file");
    std::unique_ptr<std::FILE, int (*)(std::FILE*)> file(std::fopen(path.c_str(), "rb"), &std::fclose);
    const auto fail = [&](const char* what) {
        throw SceneError(context + what + " " + name + ": " + std::strerror(errno));
    };
    if (!file) fail("cannot open scene file");
    std::string text;
    char buffer[1 << 16];
    std::size_t count;
    while ((count = std::fread(buffer, 1, sizeof buffer, file.get())) > 0) text.append(buffer, count);
    if (std::ferror(file.get())) fail("cannot read scene file");
    return text;
}

// Mitsuba's camel_to_underscore_case (src/core/parser.cpp): "maxDepth" -> "max_depth", "intIOR" -> "int_ior".
std::string camel_to_underscore(std::string_view input) {
    std::string result;
    for (std::size_t i = 0; i < input.size(); ++i) {
        const char c = input[i];
        if (i > 0 && std::islower(static_cast<unsigned char>(input[i - 1])) &&
            std::isupper(static_cast<unsigned char>(c))) {
            result += '_';
            result += char(std::tolower(static_cast<unsigned char>(c)));
            while (i + 1 < input.size() && std::isupper(static_cast<unsigned char>(input[i + 1])))
                result += char(std::tolower(static_cast<unsigned char>(input[++i])));
        } else {
            result += c;
        }
    }
    return result;
}

// "3.0.0", "0.6", "2": the major version, or -1 when it is not such a number.
int major_version(std::string_view version) {
    int parts = 0, major = -1;
    while (true) {
        int value = 0;
        const auto [end, error] = std::from_chars(version.data(), version.data() + version.size(), value);
        if (error != std::errc{} || value < 0) return -1;
        if (parts++ == 0) major = value;
        version.remove_prefix(std::size_t(end - version.data()));
        if (version.empty()) return parts <= 3 ? major : -1;
        if (version.front() != '.') return -1;
        version.remove_prefix(1);
    }
}

struct Parameter {
    std::string key;  // "$name"
    std::string value;
    bool used = false;
    bool from_command_line = false;
};

bool is_name_character(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }

class TreeBuilder {
 public:
    TreeBuilder(XmlScene& scene, const XmlDefines& defines) : scene_(scene) {
        for (const auto& define : defines) {
            const std::string key = "$" + define.first;
            const auto same = [&](const Parameter& p) { return p.key == key; };
            auto found = std::find_if(parameters_.begin(), parameters_.end(), same);
            if (found != parameters_.end())
                found->value = define.second;  // the last -D of a name wins
            else
                add_parameter({key, define.second, false, true});
        }
    }

    // `text`: the scene file's, or nullptr to read it.
    void read_main(const std::string& path, const std::string* text) {
        const fs::path file(path);
        scene_.search_paths.push_back(file.parent_path().empty() ? fs::path(".") : file.parent_path());
        main_text_ = text;
        std::vector<XmlElement> top;
        read_included(file, path, nullptr, 0, 0, top);
        scene_.root = std::move(top.front());
        for (const Parameter& parameter : parameters_) {
            if (parameter.from_command_line && !parameter.used)
                throw SceneError(path + ": -D " + parameter.key.substr(1) + ": the scene has no $" +
                                 parameter.key.substr(1) + " (an unused definition is an error, as in Mitsuba)");
        }
    }

 private:
    // Reads `path` and appends its root element to `out`, or, for an
    // included <scene>, the root's children. `include` is the <include>
    // element that names it (nullptr for the scene file itself).
    void read_included(const fs::path& path, const std::string& name, const XmlElement* include, int depth,
                       int include_depth, std::vector<XmlElement>& out) {
        const std::string context = include ? include->where() + ": " : "";
        auto source = std::make_unique<SourceFile>();
        source->name = name;
        source->path = path;
        source->text = !include && main_text_ ? *main_text_ : read_file(path, name, context);
        for (std::size_t i = 0; i < source->text.size(); ++i)
            if (source->text[i] == '\n') source->line_starts.push_back(i + 1);

        std::error_code error;
        fs::path canonical = fs::weakly_canonical(path, error);
        if (error) canonical = path;
        if (std::find(include_stack_.begin(), include_stack_.end(), canonical) != include_stack_.end()) {
            std::string cycle;
            for (const std::string& file : include_names_) cycle += file + " includes ";
            fail_at(*include, "include cycle: " + cycle + name);
        }

        pugi::xml_document document;
        const pugi::xml_parse_result parsed =
            document.load_buffer(source->text.data(), source->text.size(), pugi::parse_default, pugi::encoding_utf8);
        if (!parsed) {
            fail_in(name, source->line_of(parsed.offset), std::string("malformed XML: ") + parsed.description());
        }
        const pugi::xml_node root = document.document_element();
        if (!root) fail_in(name, 0, "malformed XML: no root element");
        const int line = source->line_of(root.offset_debug());
        const pugi::xml_attribute version = root.attribute("version");
        if (!version) fail_in(name, line, "<" + std::string(root.name()) + ">: missing attribute 'version'");
        const int major = major_version(version.value());
        if (major < 0)
            fail_in(name, line,
                    "<" + std::string(root.name()) + ">: version " + in_quotes(version.value()) +
                        " is not a version number (e.g. 3.0.0)");
        source->legacy = major < 2;
        if (!include && std::string_view(root.name()) != "scene")
            fail_in(name, line, "the root element is <" + std::string(root.name()) + ">, not <scene>");

        include_stack_.push_back(canonical);
        include_names_.push_back(name);
        sources_.push_back(std::move(source));
        const SourceFile& file = *sources_.back();
        std::vector<XmlElement> elements;
        convert(root, file, depth, include_depth, nullptr, true, elements);
        include_stack_.pop_back();
        include_names_.pop_back();

        XmlElement& element = elements.front();
        std::erase_if(element.attributes, [](const auto& a) { return a.first == "version"; });
        if (include && element.tag == "scene") {
            for (XmlElement& child : element.children) out.push_back(std::move(child));
            return;
        }
        if (include) {
            if (const std::string* property = include->attribute("name"))
                element.attributes.push_back({"name", *property});
        }
        out.push_back(std::move(element));
    }

    void convert(const pugi::xml_node& node, const SourceFile& file, int depth, int include_depth,
                 const XmlElement* parent, bool root, std::vector<XmlElement>& out) {
        if (node.type() != pugi::node_element) return;
        XmlElement element;
        element.tag = node.name();
        element.file = file.name;
        element.line = file.line_of(node.offset_debug());
        if (depth >= kMaxXmlDepth) fail_at(element, "elements nested deeper than " + std::to_string(kMaxXmlDepth));
        for (const pugi::xml_attribute& attribute : node.attributes())
            element.attributes.push_back({attribute.name(), substitute(attribute.value(), element)});

        if (element.tag == "default") {
            define_default(element);
            return;
        }
        if (element.tag == "include") {
            include(element, file, depth, include_depth, out);
            return;
        }
        if (element.tag == "path") {
            add_search_path(element, file, parent, root);
            return;
        }
        if (file.legacy) upgrade_name(element, parent);
        for (const pugi::xml_node& child : node.children())
            convert(child, file, depth + 1, include_depth, &element, false, element.children);
        out.push_back(std::move(element));
    }

    static std::string in_quotes(std::string_view text) { return "\"" + std::string(text) + "\""; }

    static void only_attributes(const XmlElement& element, std::initializer_list<std::string_view> names) {
        for (const auto& [name, value] : element.attributes) {
            if (std::find(names.begin(), names.end(), name) == names.end())
                fail_at(element, "<" + element.tag + ">: unexpected attribute '" + name + "'");
        }
        for (std::string_view name : names) {
            if (!element.attribute(name))
                fail_at(element, "<" + element.tag + ">: missing attribute '" + std::string(name) + "'");
        }
    }

    void define_default(const XmlElement& element) {
        only_attributes(element, {"name", "value"});
        const std::string& name = *element.attribute("name");
        if (name.empty() || !std::all_of(name.begin(), name.end(), is_name_character))
            fail_at(element, "<default>: name " + in_quotes(name) + " must be letters, digits and '_'");
        const auto same = [&](const Parameter& p) { return p.key == "$" + name; };
        if (std::find_if(parameters_.begin(), parameters_.end(), same) == parameters_.end())
            add_parameter({"$" + name, *element.attribute("value"), true, false});
    }

    void include(const XmlElement& element, const SourceFile& file, int depth, int include_depth,
                 std::vector<XmlElement>& out) {
        for (const auto& [name, value] : element.attributes) {
            if (name != "filename" && name != "name")
                fail_at(element, "<include>: unexpected attribute '" + name + "'");
        }
        const std::string* filename = element.attribute("filename");
        if (!filename) fail_at(element, "<include>: missing attribute 'filename'");
        if (filename->empty()) fail_at(element, "<include>: filename must not be empty");
        if (include_depth + 1 > kMaxIncludeDepth)
            fail_at(element, "<include>: includes nested deeper than " + std::to_string(kMaxIncludeDepth));
        // Relative to the including file's folder first, then the search paths (Mitsuba's resolver).
        const fs::path name(*filename);
        fs::path path = name.is_absolute() ? name : file.path.parent_path() / name;
        std::error_code error;
        if (!name.is_absolute() && !fs::exists(path, error)) {
            for (const fs::path& folder : scene_.search_paths) {
                if (fs::exists(folder / name, error)) {
                    path = folder / name;
                    break;
                }
            }
        }
        if (fs::is_directory(path, error)) fail_at(element, "<include>: " + path.string() + " is a folder");
        read_included(path, path.lexically_normal().string(), &element, depth, include_depth + 1, out);
    }

    void add_search_path(const XmlElement& element, const SourceFile& file, const XmlElement* parent, bool root) {
        only_attributes(element, {"value"});
        if (root || parent == nullptr || parent->tag != "scene")
            fail_at(element, "<path> can only be a child of <scene>");
        // Relative to the file's folder, else to the search paths (Mitsuba's resolver).
        const fs::path value(*element.attribute("value"));
        fs::path folder = value.is_absolute() ? value : file.path.parent_path() / value;
        std::error_code error;
        for (std::size_t i = 0;
             !value.is_absolute() && !fs::is_directory(folder, error) && i < scene_.search_paths.size(); ++i)
            if (fs::is_directory(scene_.search_paths[i] / value, error)) folder = scene_.search_paths[i] / value;
        if (!fs::is_directory(folder, error)) fail_at(element, "<path>: folder " + value.string() + " not found");
        scene_.search_paths.insert(scene_.search_paths.begin(), folder);
    }

    // Mitsuba's upgrade of scenes older than 2.0.0: property names in snake_case, and a
    // diffuse BSDF's diffuse_reflectance is its reflectance.
    static void upgrade_name(XmlElement& element, const XmlElement* parent) {
        for (auto& [name, value] : element.attributes) {
            if (name != "name") continue;
            value = camel_to_underscore(value);
            const std::string* parent_type = parent ? parent->attribute("type") : nullptr;
            if (value == "diffuse_reflectance" && parent && parent->tag == "bsdf" && parent_type &&
                *parent_type == "diffuse")
                value = "reflectance";
        }
    }

    // Mitsuba's substitute_parameters: every "$name" of a known parameter
    // (longest names first, "\$" left alone), then any "$" left is an
    // undefined parameter, then "\$" becomes "$".
    std::string substitute(std::string value, const XmlElement& element) {
        if (value.find('$') == std::string::npos) return value;
        for (Parameter& parameter : parameters_) {
            for (std::size_t at = value.find(parameter.key); at != std::string::npos;
                 at = value.find(parameter.key, at)) {
                if (at > 0 && value[at - 1] == '\\') {
                    at += parameter.key.size();
                    continue;
                }
                value.replace(at, parameter.key.size(), parameter.value);
                parameter.used = true;
                at += parameter.value.size();
            }
        }
        for (std::size_t at = value.find('$'); at != std::string::npos; at = value.find('$', at + 1)) {
            if (at > 0 && value[at - 1] == '\\') continue;
            std::size_t end = at + 1;
            while (end < value.size() && is_name_character(value[end])) ++end;
            fail_at(element, "undefined parameter $" + value.substr(at + 1, end - at - 1) +
                                 " (define it with <default> or -D " + value.substr(at + 1, end - at - 1) + "=...)");
        }
        for (std::size_t at = value.find("\\$"); at != std::string::npos; at = value.find("\\$", at + 1))
            value.erase(at, 1);
        return value;
    }

    void add_parameter(Parameter parameter) {
        auto at = std::find_if(parameters_.begin(), parameters_.end(),
                               [&](const Parameter& p) { return parameter.key.size() > p.key.size(); });
        parameters_.insert(at, std::move(parameter));
    }

    XmlScene& scene_;
    const std::string* main_text_ = nullptr;
    std::vector<Parameter> parameters_;  // longest key first
    std::vector<fs::path> include_stack_;
    std::vector<std::string> include_names_;
    std::vector<std::unique_ptr<SourceFile>> sources_;
};

}  // namespace

const std::string* XmlElement::attribute(std::string_view name) const {
    for (const auto& [key, value] : attributes)
        if (key == name) return &value;
    return nullptr;
}

std::string XmlElement::where() const { return file + ":" + std::to_string(line); }

void fail_at(const XmlElement& element, std::string_view problem) {
    throw SceneError(element.where() + ": " + std::string(problem));
}

XmlScene read_xml_scene(const std::string& path, const XmlDefines& defines) {
    XmlScene scene;
    TreeBuilder(scene, defines).read_main(path, nullptr);
    return scene;
}

XmlScene parse_xml_scene(const std::string& text, const std::string& path, const XmlDefines& defines) {
    XmlScene scene;
    TreeBuilder(scene, defines).read_main(path, &text);
    return scene;
}

std::filesystem::path resolve_scene_file(const XmlScene& scene, const std::string& name) {
    const std::filesystem::path file(name);
    if (file.is_absolute() || scene.search_paths.empty()) return file;
    std::error_code error;
    for (const std::filesystem::path& folder : scene.search_paths)
        if (std::filesystem::exists(folder / file, error)) return folder / file;
    return scene.search_paths.back() / file;
}

}  // namespace wp
