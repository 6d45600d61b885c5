#include "scene/mitsuba_xml.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <functional>
#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/matrix.hpp>
#include <limits>
#include <map>
#include <optional>
#include <set>

#include "core/number_text.h"
#include "core/shared_math.h"
#include "import/import_process.h"
#include "import/mesh_file_error.h"
#include "scene/json_field.h"
#include "scene/limits.h"
#include "scene/mesh_file.h"
#include "scene/mitsuba_shapes.h"
#include "scene/named_media.h"
#include "scene/serialized_mesh.h"
#include "scene/spectrum.h"
#include "scene/texture_section.h"

namespace wp {
namespace {

namespace fs = std::filesystem;

// ---- values ----

std::string joined_names(const std::vector<std::string_view>& words) {
    std::string joined;
    for (std::string_view word : words) joined += (joined.empty() ? "" : ", ") + std::string(word);
    return joined;
}

std::string in_quotes(std::string_view text) { return "\"" + std::string(text) + "\""; }

std::string lower(std::string text) {
    for (char& c : text) c = char(std::tolower(static_cast<unsigned char>(c)));
    return text;
}

// Numbers separated by commas and white space, as Mitsuba's string::tokenize splits them.
std::vector<std::string> tokens(std::string_view text) {
    std::vector<std::string> words;
    std::string word;
    for (char c : text) {
        if (c == ',' || std::isspace(static_cast<unsigned char>(c))) {
            if (!word.empty()) words.push_back(std::move(word));
            word.clear();
        } else {
            word += c;
        }
    }
    if (!word.empty()) words.push_back(std::move(word));
    return words;
}

// A finite real within the scene's magnitude limit, or why not.
std::optional<double> parse_real(std::string_view text, std::string& problem) {
    std::string_view trimmed = text;
    while (!trimmed.empty() && std::isspace(static_cast<unsigned char>(trimmed.front()))) trimmed.remove_prefix(1);
    while (!trimmed.empty() && std::isspace(static_cast<unsigned char>(trimmed.back()))) trimmed.remove_suffix(1);
    if (!trimmed.empty() && trimmed.front() == '+') trimmed.remove_prefix(1);
    double value = 0.0;
    const auto [end, error] = std::from_chars(trimmed.data(), trimmed.data() + trimmed.size(), value);
    if (error == std::errc::result_out_of_range) {
        problem = in_quotes(text) + " is out of range of a double";
        return std::nullopt;
    }
    if (error != std::errc{} || end != trimmed.data() + trimmed.size() || trimmed.empty()) {
        problem = in_quotes(text) + " is not a number";
        return std::nullopt;
    }
    if (!std::isfinite(value)) {
        problem = in_quotes(text) + " is not finite";
        return std::nullopt;
    }
    if (std::fabs(value) > kMaxSceneMagnitude) {
        problem = "magnitude must be <= " + format_number(kMaxSceneMagnitude) + ", got " + format_number(value);
        return std::nullopt;
    }
    return value;
}

bool is_property_tag(std::string_view tag) {
    for (std::string_view t :
         {"float", "integer", "boolean", "string", "rgb", "spectrum", "point", "vector", "transform"})
        if (tag == t) return true;
    return false;
}

bool is_object_tag(std::string_view tag) {
    for (std::string_view t : {"bsdf", "shape", "emitter", "sensor", "film", "rfilter", "sampler", "integrator",
                               "texture", "medium", "phase", "volume", "scene"})
        if (tag == t) return true;
    return false;
}

// ---- objects and their properties ----

using IdTable = std::map<std::string, const XmlElement*, std::less<>>;

// One plugin's element: its properties by name and its nested objects (references
// resolved), each checked against what the reader supports.
class Plugin {
 public:
    Plugin(const XmlElement& element, const IdTable& ids) : element_(element), ids_(ids) {
        const std::string* type = element.attribute("type");
        if (!type && element.tag != "scene") fail_at(element, "<" + element.tag + ">: missing attribute 'type'");
        type_ = type ? *type : element.tag;
        what_ = element.tag == "scene" ? "scene" : element.tag + " " + in_quotes(type_);
    }

    const XmlElement& element() const { return element_; }
    const std::string& type() const { return type_; }
    const std::string& what() const { return what_; }
    std::string id() const {
        const std::string* id = element_.attribute("id");
        return id ? *id : "";
    }

    [[noreturn]] void fail(const XmlElement& at, std::string_view problem) const {
        fail_at(at, what_ + ": " + std::string(problem));
    }
    [[noreturn]] void fail(std::string_view problem) const { fail(element_, problem); }

    // Every property must be one of `properties` and every nested object's tag one of
    // `objects`; the element's own attributes type, id and name only.
    void allow(std::initializer_list<std::string_view> properties,
               std::initializer_list<std::string_view> objects = {}) const {
        for (const auto& [name, value] : element_.attributes) {
            if (name != "type" && name != "id" && name != "name")
                fail("unexpected attribute " + in_quotes(name) + " (expected type, id, name)");
        }
        for (const XmlElement& child : element_.children) {
            const std::string* name = child.attribute("name");
            if (is_property_tag(child.tag)) {
                if (!name) fail_at(child, "<" + child.tag + ">: missing attribute 'name'");
                if (std::find(properties.begin(), properties.end(), *name) == properties.end())
                    fail(child, child.tag + " " + in_quotes(*name) + ": not supported (supported: " +
                                    (properties.size() ? joined_names(properties) : "none") + ")");
                continue;
            }
            for (std::string_view step : {"translate", "rotate", "scale", "matrix", "lookat"})
                if (child.tag == step) fail(child, "<" + child.tag + "> can only appear inside a <transform>");
            const XmlElement& object = resolve(child);
            if (!is_object_tag(object.tag)) fail(child, "<" + child.tag + ">: not an element of Mitsuba's format");
            if (std::find(objects.begin(), objects.end(), object.tag) == objects.end()) {
                const std::string* type = object.attribute("type");
                fail(child, object.tag + (type ? " " + in_quotes(*type) : "") +
                                (name ? " as " + in_quotes(*name) : std::string(" inside it")) + ": not supported" +
                                (objects.size() ? " (supported: " + joined_names(objects) + ")" : ""));
            }
        }
        std::set<std::string> seen;
        for (const XmlElement& child : element_.children) {
            const std::string* name = child.attribute("name");
            if (is_property_tag(child.tag) && !seen.insert(*name).second)
                fail(child, child.tag + " " + in_quotes(*name) + ": given twice");
        }
    }

    // A <ref> resolved to the element it names; any other element as it is.
    const XmlElement& resolve(const XmlElement& child) const {
        if (child.tag != "ref") return child;
        for (const auto& [name, value] : child.attributes) {
            if (name != "id" && name != "name") fail_at(child, "<ref>: unexpected attribute " + in_quotes(name));
        }
        const std::string* id = child.attribute("id");
        if (!id) fail_at(child, "<ref>: missing attribute 'id'");
        auto found = ids_.find(*id);
        if (found == ids_.end()) fail_at(child, "<ref>: no object has id " + in_quotes(*id));
        return *found->second;
    }

    // The nested objects of this tag, references resolved, in document order.
    std::vector<const XmlElement*> objects(std::string_view tag) const {
        std::vector<const XmlElement*> found;
        for (const XmlElement& child : element_.children) {
            if (is_property_tag(child.tag)) continue;
            const XmlElement& object = resolve(child);
            if (object.tag == tag) found.push_back(&object);
        }
        return found;
    }
    // Every nested <texture> (or <ref> to one) must be given as one of these properties.
    void textures_only_as(const std::vector<std::string_view>& names) const {
        for (const XmlElement& child : element_.children) {
            if (is_property_tag(child.tag) || resolve(child).tag != "texture") continue;
            const std::string* n = child.attribute("name");
            if (!n || std::find(names.begin(), names.end(), *n) == names.end())
                fail(child, "texture" + (n ? " as " + in_quotes(*n) : std::string(" inside it")) +
                                ": not supported (supported: " + joined_names(names) + ")");
        }
    }
    // The <texture> (nested or by <ref>) given as property `name`, or null.
    const XmlElement* texture(std::string_view name) const {
        for (const XmlElement& child : element_.children) {
            const std::string* n = child.attribute("name");
            if (is_property_tag(child.tag) || !n || *n != name) continue;
            const XmlElement& object = resolve(child);
            if (object.tag == "texture") return &object;
        }
        return nullptr;
    }
    const XmlElement* only_object(std::string_view tag) const {
        const std::vector<const XmlElement*> found = objects(tag);
        if (found.size() > 1) fail(*found[1], "more than one " + std::string(tag) + " (wavepath takes one)");
        return found.empty() ? nullptr : found.front();
    }

    const XmlElement* property(std::string_view name) const {
        for (const XmlElement& child : element_.children) {
            const std::string* n = child.attribute("name");
            if (is_property_tag(child.tag) && n && *n == name) return &child;
        }
        return nullptr;
    }

    // A property's value attribute, which must be there.
    const std::string& value(const XmlElement& property) const {
        const std::string* value = property.attribute("value");
        if (!value) fail(property, property_name(property) + ": missing attribute 'value'");
        return *value;
    }
    std::string property_name(const XmlElement& property) const {
        return property.tag + " " + in_quotes(*property.attribute("name"));
    }
    void expect_tags(const XmlElement& property, std::initializer_list<std::string_view> tags) const {
        if (std::find(tags.begin(), tags.end(), property.tag) == tags.end())
            fail(property,
                 property_name(property) + ": must be " +
                     (tags.size() == 1 ? "<" + std::string(*tags.begin()) + ">" : "one of " + joined_names(tags)) +
                     ", got <" + property.tag + ">");
    }
    void only_attributes(const XmlElement& property, std::initializer_list<std::string_view> names) const {
        for (const auto& [name, value] : property.attributes) {
            if (name != "name" && std::find(names.begin(), names.end(), name) == names.end())
                fail(property, property_name(property) + ": unexpected attribute " + in_quotes(name));
        }
    }

    double real(const XmlElement& at, std::string_view what, std::string_view text) const {
        std::string problem;
        std::optional<double> value = parse_real(text, problem);
        if (!value) fail(at, std::string(what) + ": " + problem);
        return *value;
    }

    std::optional<double> optional_number(std::string_view name) const {
        const XmlElement* p = property(name);
        if (!p) return std::nullopt;
        expect_tags(*p, {"float", "integer"});
        only_attributes(*p, {"value"});
        return real(*p, property_name(*p), value(*p));
    }
    double number(std::string_view name, double fallback) const { return optional_number(name).value_or(fallback); }

    std::optional<std::int64_t> optional_integer(std::string_view name, std::int64_t min, std::int64_t max) const {
        const XmlElement* p = property(name);
        if (!p) return std::nullopt;
        expect_tags(*p, {"integer"});
        only_attributes(*p, {"value"});
        std::string_view text = value(*p);
        while (!text.empty() && std::isspace(static_cast<unsigned char>(text.front()))) text.remove_prefix(1);
        while (!text.empty() && std::isspace(static_cast<unsigned char>(text.back()))) text.remove_suffix(1);
        std::int64_t v = 0;
        const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), v);
        if (error == std::errc::result_out_of_range)
            fail(*p, property_name(*p) + ": must be in [" + std::to_string(min) + ", " + std::to_string(max) +
                         "], got " + std::string(text));
        if (error != std::errc{} || end != text.data() + text.size() || text.empty())
            fail(*p, property_name(*p) + ": " + in_quotes(value(*p)) + " is not an integer");
        if (v < min || v > max)
            fail(*p, property_name(*p) + ": must be in [" + std::to_string(min) + ", " + std::to_string(max) +
                         "], got " + std::to_string(v));
        return v;
    }

    bool boolean(std::string_view name, bool fallback) const {
        const XmlElement* p = property(name);
        if (!p) return fallback;
        expect_tags(*p, {"boolean"});
        only_attributes(*p, {"value"});
        const std::string text = lower(value(*p));
        if (text == "true") return true;
        if (text == "false") return false;
        fail(*p, property_name(*p) + ": " + in_quotes(value(*p)) + " is not true or false");
    }

    std::optional<std::string> optional_string(std::string_view name) const {
        const XmlElement* p = property(name);
        if (!p) return std::nullopt;
        expect_tags(*p, {"string"});
        only_attributes(*p, {"value"});
        return value(*p);
    }

    // <rgb value="r, g, b"> or one value, <spectrum value="v"> (a constant spectrum), or a
    // <float>: each component in [min, max]. Textures and other spectra are refused.
    std::optional<glm::dvec3> optional_color(std::string_view name, double max, std::string_view max_reason) const {
        for (const XmlElement& child : element_.children) {
            const std::string* n = child.attribute("name");
            if (is_property_tag(child.tag) || !n || *n != name) continue;
            const XmlElement& object = resolve(child);
            const std::string* type = object.attribute("type");
            fail(child, std::string(name) + ": " + object.tag + (type ? " " + in_quotes(*type) : "") +
                            ": not supported (supported: <rgb>, <spectrum value=\"v\">, <float>; no textures)");
        }
        const XmlElement* p = property(name);
        if (!p) return std::nullopt;
        expect_tags(*p, {"rgb", "spectrum", "float"});
        only_attributes(*p, {"value"});
        const std::string& text = value(*p);
        const std::vector<std::string> words = tokens(text);
        glm::dvec3 color;
        // Mitsuba's RGB modes read a wavelength:value list by its colour-matching integral
        // (scene/spectrum.h), and a spectrum of emitted light as an illuminant, whose colour
        // against their D65 white is not grey: a flat 0.5 is (0.60, 0.47, 0.45), by an integral
        // other than the lists' (0.04% apart), which is not reproduced.
        const bool emission = name == "radiance" || name == "irradiance";
        if (p->tag == "spectrum" && text.find(':') != std::string::npos) {
            color = spectrum_colour(*p, words,
                                    emission    ? SpectrumKind::Emission
                                    : max > 1.0 ? SpectrumKind::Index
                                                : SpectrumKind::Reflectance);
        } else if (p->tag == "spectrum" && emission) {
            fail(*p, property_name(*p) +
                         ": a <spectrum> of one radiance is not supported (Mitsuba converts it as "
                         "an illuminant, not grey; give an <rgb> or a wavelength:value list)");
        } else if (words.size() == 1) {
            color = glm::dvec3(real(*p, property_name(*p), words[0]));
        } else if (words.size() == 3 && p->tag == "rgb") {
            for (int i = 0; i < 3; ++i) color[i] = real(*p, property_name(*p), words[std::size_t(i)]);
        } else {
            fail(*p, property_name(*p) + ": " + in_quotes(text) + " must be " +
                         (p->tag == "rgb" ? "one or three numbers" : "one number"));
        }
        for (int i = 0; i < 3; ++i) {
            if (color[i] < 0.0) fail(*p, property_name(*p) + ": must be >= 0, got " + format_number(color[i]));
            if (color[i] > max)
                fail(*p, property_name(*p) + ": must be <= " + format_number(max) + std::string(max_reason) + ", got " +
                             format_number(color[i]));
        }
        return color;
    }

    // A <spectrum>'s value "w1:v1, w2:v2, ..." (wavelengths in nm, increasing), as Mitsuba's
    // RGB variants read a property of that kind.
    glm::dvec3 spectrum_colour(const XmlElement& p, const std::vector<std::string>& words, SpectrumKind kind) const {
        const std::string what = property_name(p);
        std::vector<double> wavelengths, values;
        for (const std::string& word : words) {
            const std::size_t colon = word.find(':');
            if (colon == std::string::npos) fail(p, what + ": " + in_quotes(word) + " is not wavelength:value");
            const double w = real(p, what, word.substr(0, colon)), v = real(p, what, word.substr(colon + 1));
            if (!wavelengths.empty() && !(w > wavelengths.back()))
                fail(p, what + ": wavelengths must increase, got " + format_number(w) + " after " +
                            format_number(wavelengths.back()));
            if (v < 0.0) fail(p, what + ": must be >= 0, got " + format_number(v));
            wavelengths.push_back(w);
            values.push_back(v);
        }
        if (wavelengths.size() < 2) fail(p, what + ": a wavelength:value list needs two entries at least");
        return spectrum_to_srgb(wavelengths, values, kind);
    }

    std::optional<glm::dvec3> optional_point(std::string_view name) const {
        const XmlElement* p = property(name);
        if (!p) return std::nullopt;
        expect_tags(*p, {"point", "vector"});
        return xyz(*p, property_name(*p), 0.0, true);
    }

    // x, y, z attributes (missing ones `fallback`), or value="v" or value="x, y, z".
    glm::dvec3 xyz(const XmlElement& at, const std::string& what, double fallback, bool all_required) const {
        for (const auto& [name, value] : at.attributes) {
            if (name != "name" && name != "x" && name != "y" && name != "z" && name != "value" &&
                !(at.tag == "rotate" && name == "angle"))
                fail(at, what + ": unexpected attribute " + in_quotes(name));
        }
        if (const std::string* value = at.attribute("value")) {
            if (at.attribute("x") || at.attribute("y") || at.attribute("z"))
                fail(at, what + ": cannot mix value and x, y, z");
            const std::vector<std::string> words = tokens(*value);
            if (words.size() == 1) return glm::dvec3(real(at, what, words[0]));
            if (words.size() != 3) fail(at, what + ": value must be 1 or 3 numbers, got " + in_quotes(*value));
            return {real(at, what, words[0]), real(at, what, words[1]), real(at, what, words[2])};
        }
        glm::dvec3 v(fallback);
        const char* names[] = {"x", "y", "z"};
        for (int i = 0; i < 3; ++i) {
            const std::string* text = at.attribute(names[i]);
            if (text)
                v[i] = real(at, what, *text);
            else if (all_required)
                fail(at, what + ": missing attribute '" + names[i] + "'");
        }
        return v;
    }

    std::optional<glm::dmat4> optional_transform(std::string_view name) const;

 private:
    const XmlElement& element_;
    const IdTable& ids_;
    std::string type_, what_;
};

// ---- transforms ----

glm::dvec3 vector3(const Plugin& plugin, const XmlElement& at, const std::string& what, std::string_view text) {
    const std::vector<std::string> words = tokens(text);
    if (words.size() != 3) plugin.fail(at, what + ": must be 3 numbers, got " + in_quotes(text));
    return {plugin.real(at, what, words[0]), plugin.real(at, what, words[1]), plugin.real(at, what, words[2])};
}

// Mitsuba's coordinate_system(n).first (Duff et al. 2017): the up of a <lookat> without one.
glm::dvec3 perpendicular(const glm::dvec3& n) {
    const double sign = std::copysign(1.0, n.z), a = -1.0 / (sign + n.z), b = n.x * n.y * a;
    return {std::copysign(n.x * n.x * a, n.z) + 1.0, std::copysign(b, n.z), -std::copysign(n.x, n.z)};
}

// Mitsuba's Transform::look_at: columns left = up x dir, up' = dir x left, dir, origin.
glm::dmat4 look_at(const Plugin& plugin, const XmlElement& at) {
    const std::string what = "lookat";
    for (const auto& [name, value] : at.attributes) {
        if (name != "origin" && name != "target" && name != "up")
            plugin.fail(at, what + ": unexpected attribute " + in_quotes(name));
    }
    const std::string *origin_text = at.attribute("origin"), *target_text = at.attribute("target");
    if (!origin_text || !target_text) plugin.fail(at, what + ": needs origin and target");
    const glm::dvec3 origin = vector3(plugin, at, what + " origin", *origin_text);
    const glm::dvec3 target = vector3(plugin, at, what + " target", *target_text);
    const std::string* up_text = at.attribute("up");
    glm::dvec3 up = up_text ? vector3(plugin, at, what + " up", *up_text) : glm::dvec3(0.0);
    if (target == origin) plugin.fail(at, what + ": target must differ from origin");
    const glm::dvec3 dir = glm::normalize(target - origin);
    if (up == glm::dvec3(0.0)) up = perpendicular(dir);
    const glm::dvec3 left_unnormalized = glm::cross(up, dir);
    if (!(glm::length(left_unnormalized) > 1e-6 * glm::length(up)))
        plugin.fail(at, what + ": up must not be parallel to target - origin");
    const glm::dvec3 left = glm::normalize(left_unnormalized), new_up = glm::cross(dir, left);
    glm::dmat4 m(1.0);
    m[0] = glm::dvec4(left, 0.0);
    m[1] = glm::dvec4(new_up, 0.0);
    m[2] = glm::dvec4(dir, 0.0);
    m[3] = glm::dvec4(origin, 1.0);
    return m;
}

glm::dmat4 transform_step(const Plugin& plugin, const XmlElement& step) {
    if (step.tag == "translate") return glm::translate(glm::dmat4(1.0), plugin.xyz(step, "translate", 0.0, false));
    if (step.tag == "scale") {
        const glm::dvec3 s = plugin.xyz(step, "scale", 1.0, false);
        if (s.x == 0.0 || s.y == 0.0 || s.z == 0.0) plugin.fail(step, "scale: no component may be 0");
        return glm::scale(glm::dmat4(1.0), s);
    }
    if (step.tag == "rotate") {
        const glm::dvec3 axis = plugin.xyz(step, "rotate", 0.0, false);
        const std::string* angle = step.attribute("angle");
        if (!angle) plugin.fail(step, "rotate: missing attribute 'angle'");
        if (axis == glm::dvec3(0.0)) plugin.fail(step, "rotate: the axis must not be zero");
        const double radians = glm::radians(plugin.real(step, "rotate angle", *angle));
        // Mitsuba's (Dr.Jit's) rotation matrix, with the axis as given: not normalized, as there.
        const double c = std::cos(radians), s = std::sin(radians);
        const glm::dvec3& a = axis;
        glm::dmat4 m(1.0);
        for (int row = 0; row < 3; ++row)
            for (int column = 0; column < 3; ++column) m[column][row] = (1.0 - c) * a[row] * a[column];
        for (int i = 0; i < 3; ++i) m[i][i] += c;
        m[1][0] -= s * a.z;  // row 0, column 1
        m[2][0] += s * a.y;
        m[0][1] += s * a.z;
        m[2][1] -= s * a.x;
        m[0][2] -= s * a.y;
        m[1][2] += s * a.x;
        return m;
    }
    if (step.tag == "matrix") {
        for (const auto& [name, value] : step.attributes)
            if (name != "value") plugin.fail(step, "matrix: unexpected attribute " + in_quotes(name));
        const std::string* value = step.attribute("value");
        if (!value) plugin.fail(step, "matrix: missing attribute 'value'");
        const std::vector<std::string> words = tokens(*value);
        if (words.size() != 16 && words.size() != 9)
            plugin.fail(step, "matrix: must be 16 (or 9) numbers, row by row, got " + std::to_string(words.size()));
        const int n = words.size() == 16 ? 4 : 3;
        glm::dmat4 m(1.0);
        for (int row = 0; row < n; ++row)
            for (int column = 0; column < n; ++column)
                m[column][row] = plugin.real(step, "matrix", words[std::size_t(row * n + column)]);
        if (m[0][3] != 0.0 || m[1][3] != 0.0 || m[2][3] != 0.0 || m[3][3] != 1.0)
            plugin.fail(step, "matrix: the last row must be 0 0 0 1 (affine transforms only)");
        return m;
    }
    if (step.tag == "lookat") return look_at(plugin, step);
    plugin.fail(step, "<" + step.tag +
                          "> inside a transform: not supported (supported: translate, rotate, scale, "
                          "matrix, lookat)");
}

std::optional<glm::dmat4> Plugin::optional_transform(std::string_view name) const {
    const XmlElement* p = property(name);
    if (!p) return std::nullopt;
    expect_tags(*p, {"transform"});
    only_attributes(*p, {});
    // Each step applies after those before it, as Mitsuba composes them.
    glm::dmat4 m(1.0);
    for (const XmlElement& step : p->children) m = transform_step(*this, step) * m;
    for (int column = 0; column < 4; ++column)
        for (int row = 0; row < 3; ++row)
            if (!(std::fabs(m[column][row]) <= kMaxSceneMagnitude))
                fail(*p, property_name(*p) + ": an entry's magnitude is beyond " + format_number(kMaxSceneMagnitude));
    return m;
}

// ---- the reader ----

// An index of refraction: a number, or one of Mitsuba's names.
double ior(const Plugin& plugin, std::string_view name, const char* fallback) {
    const XmlElement* p = plugin.property(name);
    std::string text = fallback;
    if (p && p->tag != "string") {
        const double value = *plugin.optional_number(name);
        if (!(value > 0.0)) plugin.fail(*p, plugin.property_name(*p) + ": must be > 0, got " + format_number(value));
        return value;
    }
    if (p) text = *plugin.optional_string(name);
    if (std::optional<double> value = named_ior(text)) return *value;
    plugin.fail(
        *p, plugin.property_name(*p) + ": unknown material " + in_quotes(text) + " (known: " + named_ior_list() + ")");
}

// A conductor's index: `eta` and `k`, or a named `material` (default "none", a perfect mirror).
void read_conductor_index(const Plugin& bsdf, Material& m) {
    std::optional<glm::dvec3> eta = bsdf.optional_color("eta", kMaxSceneMagnitude, "");
    std::optional<glm::dvec3> k = bsdf.optional_color("k", kMaxSceneMagnitude, "");
    const XmlElement* name = bsdf.property("material");
    if (eta || k) {
        if (name) bsdf.fail(*name, "material: give either material or eta and k, not both");
        if (!eta || !k) bsdf.fail(std::string(eta ? "eta" : "k") + ": needs " + (eta ? "k" : "eta") + " beside it");
        m.eta = *eta;
        m.k = *k;
        return;
    }
    const std::string metal = name ? *bsdf.optional_string("material") : "none";
    std::optional<ComplexIor> index = named_conductor(metal);
    if (!index) {
        bsdf.fail(*name,
                  "material: unknown conductor " + in_quotes(metal) + " (known: " + named_conductor_list() + ")");
    }
    m.eta = index->eta;
    m.k = index->k;
}

// A rough material's `distribution` (default beckmann) and `alpha` or `alpha_u` and `alpha_v` (default 0.1);
// a roughness that is a texture is 0 here (Reader::bsdf_material reads the texture).
void read_microfacet(const Plugin& bsdf, Material& m) {
    if (const XmlElement* p = bsdf.property("distribution")) {
        const std::string name = *bsdf.optional_string("distribution");
        if (name != "beckmann" && name != "ggx")
            bsdf.fail(*p, "distribution: unknown " + in_quotes(name) + " (expected beckmann or ggx)");
        m.distribution = name == "ggx" ? Microfacet::GGX : Microfacet::Beckmann;
    }
    auto roughness = [&](std::string_view name) {
        if (bsdf.texture(name)) return 0.0;
        const double alpha = *bsdf.optional_number(name);
        if (!(alpha >= kMinRoughness)) {
            bsdf.fail(*bsdf.property(name), std::string(name) + ": must be >= " + format_number(kMinRoughness) +
                                                ", got " + format_number(alpha));
        }
        return alpha;
    };
    auto given = [&](std::string_view name) { return bsdf.property(name) || bsdf.texture(name); };
    const bool alpha = given("alpha"), alpha_u = given("alpha_u"), alpha_v = given("alpha_v");
    if (alpha_u || alpha_v) {
        if (alpha) {
            const char* both = "alpha: give either alpha or alpha_u and alpha_v, not both";
            if (const XmlElement* p = bsdf.property("alpha")) bsdf.fail(*p, both);
            bsdf.fail(both);
        }
        if (!alpha_u || !alpha_v) bsdf.fail("alpha_u and alpha_v: give both");
        m.alpha_u = roughness("alpha_u");
        m.alpha_v = roughness("alpha_v");
    } else if (alpha) {
        m.alpha_u = m.alpha_v = roughness("alpha");
    }
}

// A BSDF as a wavepath material (without emission). To add a BSDF: a function
// here and its row in kBsdfs.
using BsdfReader = Material (*)(const Plugin&, const std::function<Material(const XmlElement&)>& nested);

// The BSDF properties that may be textures, and the material parameter each
// one is (docs/scene-format.md); Reader::bsdf_material reads the textures.
struct TexturableProperty {
    std::string_view bsdf, property;
    TexturedParameter parameter;
};
constexpr TexturableProperty kTexturableProperties[] = {
    {"diffuse", "reflectance", TexturedParameter::Albedo},
    {"conductor", "specular_reflectance", TexturedParameter::SpecularReflectance},
    {"roughconductor", "specular_reflectance", TexturedParameter::SpecularReflectance},
    {"plastic", "diffuse_reflectance", TexturedParameter::Albedo},
    {"plastic", "specular_reflectance", TexturedParameter::SpecularReflectance},
    {"roughplastic", "diffuse_reflectance", TexturedParameter::Albedo},
    {"roughplastic", "specular_reflectance", TexturedParameter::SpecularReflectance},
    {"roughconductor", "alpha", TexturedParameter::AlphaU},
    {"roughconductor", "alpha", TexturedParameter::AlphaV},
    {"roughconductor", "alpha_u", TexturedParameter::AlphaU},
    {"roughconductor", "alpha_v", TexturedParameter::AlphaV},
    {"roughdielectric", "alpha", TexturedParameter::AlphaU},
    {"roughdielectric", "alpha", TexturedParameter::AlphaV},
    {"roughdielectric", "alpha_u", TexturedParameter::AlphaU},
    {"roughdielectric", "alpha_v", TexturedParameter::AlphaV},
    {"normalmap", "normalmap", TexturedParameter::NormalMap},
    {"mask", "opacity", TexturedParameter::Opacity},
};

// Every property must be one of `properties`, and every texture (nested or
// by <ref>) one of those kTexturableProperties lists for the BSDF's type.
void allow_bsdf_properties(const Plugin& bsdf, std::initializer_list<std::string_view> properties) {
    std::vector<std::string_view> texturable;
    for (const TexturableProperty& t : kTexturableProperties)
        if (t.bsdf == bsdf.type() && std::find(texturable.begin(), texturable.end(), t.property) == texturable.end())
            texturable.push_back(t.property);
    bsdf.allow(properties, {"texture"});
    bsdf.textures_only_as(texturable);
}

// A colour property that may be a texture: its constant in [0, 1], `fallback`
// without it, 0 where it is a texture (whose value the material reads instead).
glm::dvec3 colour_property(const Plugin& bsdf, std::string_view name, glm::dvec3 fallback) {
    if (bsdf.texture(name)) return glm::dvec3(0.0);
    return bsdf.optional_color(name, 1.0, " (energy gain)").value_or(fallback);
}

Material read_diffuse(const Plugin& bsdf, const std::function<Material(const XmlElement&)>&) {
    allow_bsdf_properties(bsdf, {"reflectance"});
    Material m;
    m.type = MaterialType::Diffuse;
    m.albedo = colour_property(bsdf, "reflectance", glm::dvec3(0.5));
    return m;
}

// Mitsuba's reflecting BSDFs are black from the back (Material::one_sided);
// a twosided BSDF is the BSDF it wraps, reflecting alike on both sides.
Material read_twosided(const Plugin& bsdf, const std::function<Material(const XmlElement&)>& nested) {
    bsdf.allow({}, {"bsdf"});
    const std::vector<const XmlElement*> inner = bsdf.objects("bsdf");
    if (inner.empty()) bsdf.fail("needs the BSDF it makes two-sided");
    if (inner.size() > 1) bsdf.fail(*inner[1], "another BSDF on the back side: not supported");
    Material m = nested(*inner.front());
    m.one_sided = false;
    if (m.type == MaterialType::Glass || m.type == MaterialType::RoughDielectric ||
        m.type == MaterialType::ThinDielectric)
        bsdf.fail(*inner.front(), "a dielectric inside it: not supported (Mitsuba's twosided reflects only)");
    return m;
}

// The one BSDF an adapter (`bsdf`: normalmap, bumpmap or mask) wraps, which
// may not be an adapter itself; `missing` is the error where it has none.
Material wrapped_bsdf(const Plugin& bsdf, const std::function<Material(const XmlElement&)>& nested,
                      const char* missing) {
    const std::vector<const XmlElement*> inner = bsdf.objects("bsdf");
    if (inner.empty()) bsdf.fail(missing);
    if (inner.size() > 1) bsdf.fail(*inner[1], "a second BSDF: " + std::string(bsdf.type()) + " wraps one");
    Material m = nested(*inner.front());
    if (m.adapted()) bsdf.fail(*inner.front(), "a normalmap, bumpmap or mask inside it");
    return m;
}

// The BSDF a normalmap or bumpmap adapter (`bsdf`) wraps: like twosided,
// one, and one that reflects only, nor another adapter (the JSON reader's
// read_adapted_material says why).
Material read_adapted_bsdf(const Plugin& bsdf, const std::function<Material(const XmlElement&)>& nested) {
    const Material m = wrapped_bsdf(bsdf, nested, "needs the BSDF it perturbs");
    if (m.type == MaterialType::Glass || m.type == MaterialType::RoughDielectric ||
        m.type == MaterialType::ThinDielectric)
        bsdf.fail(*bsdf.objects("bsdf").front(), "a dielectric inside it: not supported (" + std::string(bsdf.type()) +
                                                     " wraps a BSDF that reflects only)");
    return m;
}

// Mitsuba's normalmap adapter: the BSDF it wraps, with the texture
// `normalmap` perturbing its shading normal (kernels/shared/normal_map.h;
// bsdf_material sets the texture).
Material read_normalmap(const Plugin& bsdf, const std::function<Material(const XmlElement&)>& nested) {
    bsdf.allow({}, {"bsdf", "texture"});
    bsdf.textures_only_as({"normalmap"});
    if (!bsdf.texture("normalmap")) bsdf.fail("missing texture normalmap");
    return read_adapted_bsdf(bsdf, nested);
}

// Mitsuba's bumpmap adapter: the BSDF it wraps, with its shading normal
// bent by the gradient of its one texture (a height, under any name:
// bsdf_material sets it) times `scale` (kernels/shared/normal_map.h'
// bump_mapped).
Material read_bumpmap(const Plugin& bsdf, const std::function<Material(const XmlElement&)>& nested) {
    bsdf.allow({"scale"}, {"bsdf", "texture"});
    const std::vector<const XmlElement*> heights = bsdf.objects("texture");
    if (heights.empty()) bsdf.fail("missing its texture (the height)");
    if (heights.size() > 1) bsdf.fail(*heights[1], "a second texture: bumpmap takes one");
    Material m = read_adapted_bsdf(bsdf, nested);
    m.bump_scale = bsdf.number("scale", 1.0);
    return m;
}

// Mitsuba's mask: the BSDF it wraps scatters with probability `opacity` (a
// float in [0, 1] or a texture, which bsdf_material sets; default 0.5), and
// a ray passes straight through otherwise (kernels/shared/materials/mask.h).
// No adapter inside it (the JSON reader's read_mask says why).
Material read_mask(const Plugin& bsdf, const std::function<Material(const XmlElement&)>& nested) {
    bsdf.allow({"opacity"}, {"bsdf", "texture"});
    bsdf.textures_only_as({"opacity"});
    Material m = wrapped_bsdf(bsdf, nested, "needs the BSDF it masks");
    if (bsdf.texture("opacity")) {
        m.opacity = 0.0;
        return m;
    }
    m.opacity = bsdf.number("opacity", 0.5);
    if (!(m.opacity >= 0.0 && m.opacity <= 1.0))
        bsdf.fail(*bsdf.property("opacity"), "opacity: must be in [0, 1], got " + format_number(m.opacity));
    return m;
}

Material read_dielectric(const Plugin& bsdf, const std::function<Material(const XmlElement&)>&) {
    bsdf.allow({"int_ior", "ext_ior"});
    Material m;
    m.type = MaterialType::Glass;
    // wavepath's glass has the outside's index 1; only the ratio reaches the image.
    m.ior = ior(bsdf, "int_ior", "bk7") / ior(bsdf, "ext_ior", "air");
    return m;
}

Material read_conductor(const Plugin& bsdf, const std::function<Material(const XmlElement&)>&) {
    allow_bsdf_properties(bsdf, {"material", "eta", "k", "specular_reflectance"});
    Material m;
    m.type = MaterialType::Conductor;
    read_conductor_index(bsdf, m);
    m.specular_reflectance = colour_property(bsdf, "specular_reflectance", glm::dvec3(1.0));
    return m;
}

Material read_roughconductor(const Plugin& bsdf, const std::function<Material(const XmlElement&)>&) {
    allow_bsdf_properties(
        bsdf, {"material", "eta", "k", "specular_reflectance", "distribution", "alpha", "alpha_u", "alpha_v"});
    Material m;
    m.type = MaterialType::RoughConductor;
    read_conductor_index(bsdf, m);
    m.specular_reflectance = colour_property(bsdf, "specular_reflectance", glm::dvec3(1.0));
    read_microfacet(bsdf, m);
    return m;
}

Material read_roughdielectric(const Plugin& bsdf, const std::function<Material(const XmlElement&)>&) {
    allow_bsdf_properties(bsdf, {"int_ior", "ext_ior", "distribution", "alpha", "alpha_u", "alpha_v"});
    Material m;
    m.type = MaterialType::RoughDielectric;
    m.ior = ior(bsdf, "int_ior", "bk7") / ior(bsdf, "ext_ior", "air");
    read_microfacet(bsdf, m);
    return m;
}

Material read_thindielectric(const Plugin& bsdf, const std::function<Material(const XmlElement&)>&) {
    bsdf.allow({"int_ior", "ext_ior"});
    Material m;
    m.type = MaterialType::ThinDielectric;
    m.ior = ior(bsdf, "int_ior", "bk7") / ior(bsdf, "ext_ior", "air");
    return m;
}

// The base and coat of plastic and roughplastic, with Mitsuba's defaults.
Material plastic_coat(const Plugin& bsdf, MaterialType type) {
    Material m;
    m.type = type;
    m.albedo = colour_property(bsdf, "diffuse_reflectance", glm::dvec3(0.5));
    m.specular_reflectance = colour_property(bsdf, "specular_reflectance", glm::dvec3(1.0));
    m.ior = ior(bsdf, "int_ior", "polypropylene") / ior(bsdf, "ext_ior", "air");
    m.nonlinear = bsdf.boolean("nonlinear", false);
    return m;
}

Material read_plastic(const Plugin& bsdf, const std::function<Material(const XmlElement&)>&) {
    allow_bsdf_properties(bsdf, {"diffuse_reflectance", "specular_reflectance", "int_ior", "ext_ior", "nonlinear"});
    return plastic_coat(bsdf, MaterialType::Plastic);
}

// Mitsuba's roughplastic is isotropic: `alpha`, no alpha_u and alpha_v.
Material read_roughplastic(const Plugin& bsdf, const std::function<Material(const XmlElement&)>&) {
    allow_bsdf_properties(bsdf, {"diffuse_reflectance", "specular_reflectance", "int_ior", "ext_ior", "nonlinear",
                                 "distribution", "alpha"});
    Material m = plastic_coat(bsdf, MaterialType::RoughPlastic);
    read_microfacet(bsdf, m);
    return m;
}

const std::pair<const char*, BsdfReader> kBsdfs[] = {
    {"diffuse", read_diffuse},
    {"twosided", read_twosided},
    {"dielectric", read_dielectric},
    {"conductor", read_conductor},
    {"roughconductor", read_roughconductor},
    {"roughdielectric", read_roughdielectric},
    {"thindielectric", read_thindielectric},
    {"plastic", read_plastic},
    {"roughplastic", read_roughplastic},
    {"normalmap", read_normalmap},
    {"bumpmap", read_bumpmap},
    {"mask", read_mask},
};

// The BSDFs that reflect on their front only in Mitsuba (a dielectric has two sides of its own;
// the adapters are their nested BSDF's).
bool is_one_sided(std::string_view bsdf) {
    for (std::string_view reflecting : {"diffuse", "conductor", "roughconductor", "plastic", "roughplastic"})
        if (bsdf == reflecting) return true;
    return false;
}

struct MaterialKey {
    const XmlElement* bsdf;  // nullptr: Mitsuba's default BSDF
    glm::dvec3 emission;
    bool operator<(const MaterialKey& o) const {
        if (bsdf != o.bsdf) return std::less<>()(bsdf, o.bsdf);
        return std::tie(emission.x, emission.y, emission.z) < std::tie(o.emission.x, o.emission.y, o.emission.z);
    }
};

// A <texture> element as the reader reads it: as it is, or a checkerboard
// with its colours swapped (Reader::texture_index).
struct TextureUse {
    const XmlElement* element;
    bool swapped;
    bool operator<(const TextureUse& o) const { return std::tie(element, swapped) < std::tie(o.element, o.swapped); }
};

class Reader {
 public:
    Reader(XmlScene xml, const std::string& path, const MeshImportLimits& mesh_import, const ShapeProgress& progress)
        : xml_(std::move(xml)), importer_(mesh_import), progress_(progress) {
        out_.scene.source = path;
        index_ids(xml_.root);
    }

    MitsubaScene read() {
        const Plugin scene(xml_.root, ids_);
        // BSDFs, textures, films, samplers and filters at the top level are read where a reference uses them.
        scene.allow({}, {"integrator", "sensor", "shape", "bsdf", "emitter", "texture", "film", "sampler", "rfilter"});
        // Without an integrator, Mitsuba's path integrator with its defaults.
        out_.scene.render.max_depth = kMaxDepthLimit;
        out_.scene.render.rr_depth = 5;
        const XmlElement* integrator = scene.only_object("integrator");
        if (integrator) read_integrator(*integrator);
        const std::vector<const XmlElement*> sensors = scene.objects("sensor");
        if (sensors.empty()) fail_at(xml_.root, "scene: no sensor (wavepath needs a perspective sensor)");
        read_sensor(*sensors.front());
        for (const XmlElement* emitter : scene.objects("emitter")) read_emitter(*emitter);
        const std::vector<const XmlElement*> shapes = scene.objects("shape");
        importer_.expect(named_mesh_files(shapes));
        for (std::size_t i = 0; i < shapes.size(); ++i) {
            read_shape(*shapes[i]);
            if (progress_) progress_(i + 1, shapes.size());
        }
        return std::move(out_);
    }

 private:
    void index_ids(const XmlElement& element) {
        for (const XmlElement& child : element.children) {
            if (const std::string* id = child.attribute("id"); id && child.tag != "ref") {
                auto [at, inserted] = ids_.emplace(*id, &child);
                if (!inserted)
                    fail_at(child, "<" + child.tag + ">: id " + in_quotes(*id) + " is also the id of the <" +
                                       at->second->tag + "> at " + at->second->where());
            }
            index_ids(child);
        }
    }

    void warn(const XmlElement& at, const std::string& message) {
        out_.warnings.push_back(at.where() + ": " + message);
    }

    // ---- integrator, sensor, film, sampler ----

    void read_integrator(const XmlElement& element) {
        const Plugin integrator(element, ids_);
        if (integrator.type() != "path")
            integrator.fail("not supported (supported: path; -D can choose it where the scene has a $default for it)");
        integrator.allow({"max_depth", "rr_depth", "hide_emitters"});
        RenderSettings& render = out_.scene.render;
        // Mitsuba counts path segments (1: emitters seen directly), wavepath scattering events (0: the same);
        // -1 is unbounded: wavepath's most (docs/mitsuba.md, the converter's mapping inverted).
        const std::int64_t max_depth =
            integrator.optional_integer("max_depth", -1, std::numeric_limits<int>::max()).value_or(-1);
        if (max_depth == 0)
            integrator.fail(*integrator.property("max_depth"),
                            "integer \"max_depth\": 0 renders nothing (black); 1 shows the emitters seen directly");
        render.max_depth = max_depth < 0 ? kMaxDepthLimit : int(std::min<std::int64_t>(max_depth - 1, kMaxDepthLimit));
        render.rr_depth = int(integrator.optional_integer("rr_depth", 1, std::numeric_limits<int>::max()).value_or(5));
        if (integrator.boolean("hide_emitters", false))
            integrator.fail(*integrator.property("hide_emitters"), "boolean \"hide_emitters\": true is not supported");
    }

    void read_sensor(const XmlElement& element) {
        const Plugin sensor(element, ids_);
        if (sensor.type() != "perspective") sensor.fail("not supported (supported: perspective)");
        sensor.allow({"fov", "fov_axis", "focal_length", "to_world", "near_clip", "far_clip", "focus_distance"},
                     {"film", "sampler"});
        Camera& camera = out_.scene.camera;
        camera.width = 768;
        camera.height = 576;
        camera.filter = {.type = FilterType::Gaussian};  // Mitsuba's default film has its default rfilter
        if (const XmlElement* film = sensor.only_object("film")) read_film(*film);
        if (const XmlElement* sampler = sensor.only_object("sampler"))
            read_sampler(*sampler);
        else
            out_.scene.render.spp = 4;

        const glm::dmat4 m = sensor.optional_transform("to_world").value_or(glm::dmat4(1.0));
        const XmlElement& at = sensor.property("to_world") ? *sensor.property("to_world") : element;
        const glm::dmat3 linear(m);
        const glm::dmat3 gram = glm::transpose(linear) * linear;
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j)
                if (std::fabs(gram[i][j] - (i == j ? 1.0 : 0.0)) > 1e-3)
                    sensor.fail(at, "transform \"to_world\": must not scale or shear (as in Mitsuba)");
        if (glm::determinant(linear) < 0.0)
            sensor.fail(at, "transform \"to_world\": mirrors the image (negative determinant): not supported");
        // Mitsuba's camera looks along +z with +y up; its image's left is +x.
        camera.position = glm::dvec3(m[3]);
        camera.look_at = camera.position + glm::dvec3(m[2]);
        camera.up = glm::dvec3(m[1]);

        const double aspect = camera.aspect();
        const double x_fov = horizontal_fov(sensor, aspect);
        camera.fov_y_degrees = glm::degrees(2.0 * std::atan(std::tan(glm::radians(x_fov) / 2.0) / aspect));
        if (!(camera.fov_y_degrees > 0.0 && camera.fov_y_degrees < 180.0))
            sensor.fail("the vertical field of view " + format_number(camera.fov_y_degrees) + " is not in (0, 180)");
    }

    // Mitsuba's parse_fov: the horizontal field of view in degrees.
    static double horizontal_fov(const Plugin& sensor, double aspect) {
        const std::optional<double> fov = sensor.optional_number("fov");
        const std::optional<std::string> focal_length = sensor.optional_string("focal_length");
        const std::optional<std::string> axis_given = sensor.optional_string("fov_axis");
        if (fov && focal_length) sensor.fail(*sensor.property("focal_length"), "give fov or focal_length, not both");
        std::string axis = lower(axis_given.value_or("x"));
        double degrees;
        if (fov) {
            degrees = *fov;
            if (!(degrees > 0.0 && degrees < 180.0))
                sensor.fail(*sensor.property("fov"),
                            "float \"fov\": must be in (0, 180), got " + format_number(degrees));
            if (axis == "smaller") axis = aspect > 1.0 ? "y" : "x";
            if (axis == "larger") axis = aspect > 1.0 ? "x" : "y";
        } else {
            std::string text = focal_length.value_or("50mm");
            if (text.size() >= 2 && text.substr(text.size() - 2) == "mm") text.resize(text.size() - 2);
            const XmlElement& at =
                sensor.property("focal_length") ? *sensor.property("focal_length") : sensor.element();
            const double millimetres = sensor.real(at, "string \"focal_length\"", text);
            if (!(millimetres > 0.0)) sensor.fail(at, "string \"focal_length\": must be > 0 mm");
            degrees = glm::degrees(2.0 * std::atan(std::sqrt(36.0 * 36.0 + 24.0 * 24.0) / (2.0 * millimetres)));
            axis = "diagonal";
        }
        if (axis == "x") return degrees;
        if (axis == "y") return glm::degrees(2.0 * std::atan(std::tan(glm::radians(degrees) / 2.0) * aspect));
        if (axis == "diagonal") {
            const double diagonal = 2.0 * std::tan(glm::radians(degrees) / 2.0);
            const double width = diagonal / std::sqrt(1.0 + 1.0 / (aspect * aspect));
            return glm::degrees(2.0 * std::atan(width / 2.0));
        }
        sensor.fail(*sensor.property("fov_axis"), "string \"fov_axis\": " + in_quotes(*axis_given) +
                                                      " is not one of x, y, diagonal, smaller, larger");
    }

    void read_film(const XmlElement& element) {
        const Plugin film(element, ids_);
        if (film.type() != "hdrfilm") film.fail("not supported (supported: hdrfilm)");
        // The output's format is -o's: pixel_format, component_format and file_format change nothing here.
        film.allow({"width", "height", "pixel_format", "component_format", "file_format", "sample_border"},
                   {"rfilter"});
        Camera& camera = out_.scene.camera;
        camera.width = int(film.optional_integer("width", 1, kMaxResolution).value_or(768));
        camera.height = int(film.optional_integer("height", 1, kMaxResolution).value_or(576));
        if (std::int64_t(camera.width) * camera.height > kMaxPixels)
            film.fail("width * height must be <= " + std::to_string(kMaxPixels) + ", got " +
                      std::to_string(camera.width) + " * " + std::to_string(camera.height));
        film.boolean("sample_border", false);
        if (const XmlElement* rfilter = film.only_object("rfilter")) camera.filter = read_rfilter(*rfilter);
    }

    // Mitsuba 3's box, tent (radius, default 1) and gaussian (stddev, default
    // 0.5, windowed at 4 stddev), in pixels.
    PixelFilter read_rfilter(const XmlElement& element) {
        const Plugin rfilter(element, ids_);
        PixelFilter filter;
        if (rfilter.type() == "box") {
            rfilter.allow({});
        } else if (rfilter.type() == "tent") {
            rfilter.allow({"radius"});
            filter.type = FilterType::Tent;
            filter.radius = filter_width(rfilter, "radius", filter.radius, 1.0);
        } else if (rfilter.type() == "gaussian") {
            rfilter.allow({"stddev"});
            filter.type = FilterType::Gaussian;
            filter.stddev = filter_width(rfilter, "stddev", filter.stddev, 4.0);
        } else {
            rfilter.fail("not supported (supported: box, tent, gaussian)");
        }
        return filter;
    }

    // A filter's width `name`: > 0 and within kMaxFilterRadius (`per_radius`:
    // the filter's radius over it).
    static double filter_width(const Plugin& rfilter, std::string_view name, double fallback, double per_radius) {
        const double width = rfilter.number(name, fallback), most = kMaxFilterRadius / per_radius;
        if (!(width > 0.0 && width <= most))
            rfilter.fail(*rfilter.property(name), "float \"" + std::string(name) + "\": must be > 0 and <= " +
                                                      format_number(most) + " pixels, got " + format_number(width));
        return width;
    }

    void read_sampler(const XmlElement& element) {
        const Plugin sampler(element, ids_);
        // Each of these estimates the same image; wavepath uses its own sampler (render.sampler).
        const std::string& type = sampler.type();
        if (type != "independent" && type != "stratified" && type != "multijitter" && type != "orthogonal" &&
            type != "ldsampler")
            sampler.fail("not supported (supported: independent, stratified, multijitter, orthogonal, ldsampler)");
        sampler.allow({"sample_count", "seed", "jitter", "strength"});
        out_.scene.render.spp = int(sampler.optional_integer("sample_count", 1, kMaxSpp).value_or(4));
        out_.scene.render.seed =
            std::uint32_t(sampler.optional_integer("seed", 0, std::numeric_limits<std::uint32_t>::max()).value_or(0));
        sampler.boolean("jitter", true);
        sampler.optional_number("strength");
    }

    // ---- emitters ----

    void read_emitter(const XmlElement& element) {
        const Plugin emitter(element, ids_);
        if (emitter.type() == "area") {
            if (!emitter.id().empty()) return;  // a shape's, by reference (read there)
            emitter.fail("an area emitter must be inside the shape that emits, or referred to from it by its id");
        }
        if (emitter.type() == "directional") {
            read_directional(emitter);
            return;
        }
        if (emitter.type() == "envmap") {
            read_envmap(emitter);
            return;
        }
        if (emitter.type() == "point") {
            read_point(emitter);
            return;
        }
        if (emitter.type() == "spot") {
            read_spot(emitter);
            return;
        }
        if (emitter.type() != "constant")
            emitter.fail("not supported (supported: constant, directional, envmap, point, spot; area inside a shape)");
        emitter.allow({"radiance"});
        if (out_.scene.environment_map) emitter.fail(kSecondEnvironment);
        out_.scene.background += emitter.optional_color("radiance", kMaxSceneMagnitude, "").value_or(glm::dvec3(1.0));
        for (int i = 0; i < 3; ++i)
            if (out_.scene.background[i] > kMaxSceneMagnitude)
                emitter.fail("the constant emitters' radiance sums beyond " + format_number(kMaxSceneMagnitude));
    }

    // Mitsuba's directional emitter: its light travels along `direction`, or
    // along to_world's +z (the default: +z itself); `irradiance` (default 1).
    void read_directional(const Plugin& emitter) {
        emitter.allow({"irradiance", "direction", "to_world"});
        if (emitter.property("direction") && emitter.property("to_world"))
            emitter.fail("give \"direction\" or \"to_world\", not both (as in Mitsuba)");
        DirectionalLight light;
        const glm::dmat4 m = emitter.optional_transform("to_world").value_or(glm::dmat4(1.0));
        glm::dvec3 direction = emitter.optional_point("direction").value_or(glm::dvec3(m * glm::dvec4(0, 0, 1, 0)));
        if (!(glm::length(direction) > 0.0) || !std::isfinite(glm::length(direction)))
            emitter.fail(emitter.property("direction") ? *emitter.property("direction") : emitter.element(),
                         "the direction must be finite and not zero-length");
        light.direction = glm::normalize(direction);
        light.irradiance = emitter.optional_color("irradiance", kMaxSceneMagnitude, "").value_or(glm::dvec3(1.0));
        out_.scene.directional_lights.push_back(light);
    }

    // Mitsuba's point: `intensity` (default 1) at `position` or to_world's origin, not both.
    void read_point(const Plugin& emitter) {
        emitter.allow({"intensity", "position", "to_world"});
        if (emitter.property("position") && emitter.property("to_world"))
            emitter.fail("give \"position\" or \"to_world\", not both (as in Mitsuba)");
        const glm::dmat4 m = emitter.optional_transform("to_world").value_or(glm::dmat4(1.0));
        PointLight light;
        light.position = emitter.optional_point("position").value_or(glm::dvec3(m[3]));
        check_light_position(emitter, light.position);
        light.intensity = emitter.optional_color("intensity", kMaxSceneMagnitude, "").value_or(glm::dvec3(1.0));
        out_.scene.point_lights.push_back(light);
    }

    // Mitsuba's spot: at to_world's origin, pointing along its +z (a
    // <lookat> from origin to target), `intensity` (default 1) on its axis,
    // `cutoff_angle` (default 20) and `beam_width` (default 3/4 of it) in degrees.
    void read_spot(const Plugin& emitter) {
        emitter.allow({"intensity", "cutoff_angle", "beam_width", "to_world"});
        const glm::dmat4 m = emitter.optional_transform("to_world").value_or(glm::dmat4(1.0));
        PointLight light;
        light.position = glm::dvec3(m[3]);
        check_light_position(emitter, light.position);
        light.intensity = emitter.optional_color("intensity", kMaxSceneMagnitude, "").value_or(glm::dvec3(1.0));
        SpotCone cone;
        const glm::dvec3 axis(m * glm::dvec4(0, 0, 1, 0));
        if (!(glm::length(axis) > 0.0) || !std::isfinite(glm::length(axis)))
            emitter.fail(*emitter.property("to_world"), "to_world leaves the spot no direction (its +z)");
        cone.axis = glm::normalize(axis);
        cone.cutoff_angle = emitter.number("cutoff_angle", 20.0);
        if (!(cone.cutoff_angle > 0.0 && cone.cutoff_angle <= 90.0))
            emitter.fail(*emitter.property("cutoff_angle"),
                         "float \"cutoff_angle\": must be in (0, 90] degrees, got " + format_number(cone.cutoff_angle));
        cone.beam_width = emitter.number("beam_width", cone.cutoff_angle * 0.75);
        if (!(cone.beam_width >= 0.0 && cone.beam_width <= cone.cutoff_angle))
            emitter.fail(*emitter.property("beam_width"), "float \"beam_width\": must be in [0, cutoff_angle " +
                                                              format_number(cone.cutoff_angle) + "] degrees, got " +
                                                              format_number(cone.beam_width));
        light.cone = cone;
        out_.scene.point_lights.push_back(light);
    }

    static void check_light_position(const Plugin& emitter, const glm::dvec3& position) {
        if (!std::isfinite(glm::length(position)) ||
            glm::any(glm::greaterThan(glm::abs(position), glm::dvec3(kMaxSceneMagnitude))))
            emitter.fail(emitter.property("position") ? *emitter.property("position") : emitter.element(),
                         "the position must be finite and within the scene's range");
    }

    static constexpr const char* kSecondEnvironment =
        "a second environment: wavepath renders one (an envmap, or constant emitters)";

    // Mitsuba's envmap: `filename` (found as Mitsuba finds it), `scale`
    // (default 1) and `to_world`, which may rotate or mirror only.
    void read_envmap(const Plugin& emitter) {
        emitter.allow({"filename", "scale", "to_world"});
        if (out_.scene.environment_map || SharedMath<double>::emits(out_.scene.background))
            emitter.fail(kSecondEnvironment);
        EnvironmentMap map;
        map.scale = emitter.number("scale", 1.0);
        if (!(map.scale > 0.0 && map.scale <= kMaxSceneMagnitude))
            emitter.fail(*emitter.property("scale"), "float \"scale\": must be > 0, got " + format_number(map.scale));
        map.to_world = glm::dmat3(emitter.optional_transform("to_world").value_or(glm::dmat4(1.0)));
        const glm::dmat3 product = glm::transpose(map.to_world) * map.to_world;
        for (int column = 0; column < 3; ++column)
            if (glm::length(product[column] - glm::dmat3(1.0)[column]) > 1e-6)
                emitter.fail(*emitter.property("to_world"), "transform \"to_world\": must rotate or mirror only");
        const std::optional<std::string> filename = emitter.optional_string("filename");
        if (!filename) emitter.fail("missing property filename");
        map.file = *filename;
        map.path = resolve_scene_file(xml_, *filename).string();
        try {
            read_environment_map_file(map.path, map);
        } catch (const std::runtime_error& error) {
            emitter.fail(*emitter.property("filename"), *filename + ": " + error.what());
        }
        out_.scene.environment_map = std::move(map);
    }

    glm::dvec3 area_emission(const Plugin& shape) {
        const XmlElement* element = shape.only_object("emitter");
        if (!element) return glm::dvec3(0.0);
        const Plugin emitter(*element, ids_);
        if (emitter.type() != "area") emitter.fail("not supported on a shape (supported: area)");
        emitter.allow({"radiance"});
        const std::optional<glm::dvec3> radiance = emitter.optional_color("radiance", kMaxSceneMagnitude, "");
        if (!radiance) emitter.fail("missing property radiance");
        return *radiance;
    }

    // ---- materials ----

    Material bsdf_material(const XmlElement& element) {
        if (std::find(converting_.begin(), converting_.end(), &element) != converting_.end()) {
            std::string cycle;
            for (const XmlElement* e : converting_) {
                const std::string* id = e->attribute("id");
                cycle += (id ? in_quotes(*id) : e->where()) + " -> ";
            }
            const std::string* id = element.attribute("id");
            fail_at(element, "bsdf: cyclic reference: " + cycle + (id ? in_quotes(*id) : element.where()));
        }
        const Plugin bsdf(element, ids_);
        std::string supported;
        for (const auto& [name, reader] : kBsdfs) {
            supported += (supported.empty() ? "" : ", ") + std::string(name);
            if (bsdf.type() != name) continue;
            converting_.push_back(&element);
            Material m = reader(bsdf, [this](const XmlElement& inner) { return bsdf_material(inner); });
            converting_.pop_back();
            for (const TexturableProperty& t : kTexturableProperties)
                if (t.bsdf == bsdf.type())
                    if (const XmlElement* texture = bsdf.texture(t.property))
                        m.texture(t.parameter) = textured_parameter(bsdf, t, *texture);
            if (bsdf.type() == "bumpmap") m.texture(TexturedParameter::BumpMap) = bump_height(bsdf);
            if (is_one_sided(bsdf.type())) m.one_sided = true;
            return m;
        }
        bsdf.fail("not supported (supported: " + supported + ")");
    }

    // ---- textures ----

    // One of `names`' values by the string property `name`, or `fallback` without it.
    template <class Value, std::size_t N>
    static Value choice(const Plugin& plugin, std::string_view name, Value fallback,
                        const std::pair<const char*, Value> (&names)[N]) {
        const std::optional<std::string> given = plugin.optional_string(name);
        if (!given) return fallback;
        std::string known;
        for (const auto& [key, value] : names) {
            if (*given == key) return value;
            known += (known.empty() ? "" : ", ") + std::string(key);
        }
        plugin.fail(*plugin.property(name), "string " + in_quotes(name) + ": unknown value " + in_quotes(*given) +
                                                " (supported: " + known + ")");
    }

    // The texture of BSDF property t as its index into the scene's textures; a roughness texture must
    // be one everywhere (roughness_texture_problem).
    int textured_parameter(const Plugin& bsdf, const TexturableProperty& t, const XmlElement& texture) {
        const bool roughness = t.parameter == TexturedParameter::AlphaU || t.parameter == TexturedParameter::AlphaV;
        const int index = texture_index(texture, roughness || t.parameter == TexturedParameter::Opacity);
        if (roughness) {
            const std::string problem = roughness_texture_problem(out_.scene.textures[std::size_t(index)]);
            if (!problem.empty()) bsdf.fail(std::string(t.property) + ": " + problem);
        }
        return index;
    }

    // A bumpmap's one texture (read_bumpmap checked there is one) as its
    // index into the scene's textures: a bitmap (bump_texture_problem).
    int bump_height(const Plugin& bsdf) {
        const XmlElement& height = *bsdf.objects("texture").front();
        const int index = texture_index(height);
        const std::string problem = bump_texture_problem(out_.scene.textures[std::size_t(index)]);
        if (!problem.empty()) bsdf.fail(height, problem);
        return index;
    }

    // A <texture> as an index into the scene's textures (each element read
    // once for each way it is read). `as_scalar`: a BSDF reads it as a number
    // (Mitsuba's eval_1: a roughness, an opacity). Mitsuba 3.9.1's
    // checkerboard then gives color1 where its colour lookup gives color0;
    // wavepath's is one pattern for every parameter, so such a use reads a
    // checkerboard with its colours swapped (under the same name, which
    // errors quote), and the image is Mitsuba's.
    int texture_index(const XmlElement& element, bool as_scalar = false) {
        const std::string* type = element.attribute("type");
        const TextureUse use{&element, as_scalar && type && *type == "checkerboard"};
        if (auto found = textures_.find(use); found != textures_.end()) return found->second;
        const Plugin plugin(element, ids_);
        Texture t;
        t.name = plugin.id().empty() ? plugin.type() : plugin.id();
        if (plugin.type() == "bitmap") {
            plugin.allow({"filename", "filter_type", "wrap_mode", "raw", "to_uv"});
            t.type = TextureType::Bitmap;
            const std::optional<std::string> filename = plugin.optional_string("filename");
            if (!filename) plugin.fail("missing property filename");
            t.file = *filename;
            t.filter = choice(plugin, "filter_type", TextureFilter::Bilinear,
                              {std::pair{"bilinear", TextureFilter::Bilinear}, {"nearest", TextureFilter::Nearest}});
            t.wrap = choice(plugin, "wrap_mode", TextureWrap::Repeat,
                            {std::pair{"repeat", TextureWrap::Repeat},
                             {"mirror", TextureWrap::Mirror},
                             {"clamp", TextureWrap::Clamp}});
            try {
                read_bitmap_file(resolve_scene_file(xml_, *filename).string(),
                                 plugin.boolean("raw", false) ? TextureChannels::Raw : TextureChannels::Colour, t);
            } catch (const std::runtime_error& error) {
                plugin.fail(*plugin.property("filename"), *filename + ": " + error.what());
            }
        } else if (plugin.type() == "checkerboard") {
            plugin.allow({"color0", "color1", "to_uv"});
            t.type = TextureType::Checkerboard;
            t.color0 = plugin.optional_color("color0", 1.0, " (energy gain)").value_or(glm::dvec3(0.4));
            t.color1 = plugin.optional_color("color1", 1.0, " (energy gain)").value_or(glm::dvec3(0.2));
            if (use.swapped) std::swap(t.color0, t.color1);
        } else {
            plugin.fail("not supported (supported: bitmap, checkerboard)");
        }
        // Mitsuba keeps the 4x4 transform's rows and columns x, y and w: an affine map of the plane.
        if (const std::optional<glm::dmat4> m = plugin.optional_transform("to_uv"))
            t.to_uv = {(*m)[0][0], (*m)[1][0], (*m)[3][0], (*m)[0][1], (*m)[1][1], (*m)[3][1]};
        texels_ += t.texels.size() / 3;
        if (texels_ > kMaxTextureTexels)
            plugin.fail("the textures so far have " + std::to_string(texels_) + " texels, more than the " +
                        std::to_string(kMaxTextureTexels) + " a scene may have");
        out_.scene.textures.push_back(std::move(t));
        const int index = int(out_.scene.textures.size()) - 1;
        textures_.emplace(use, index);
        return index;
    }

    int material_index(const Plugin& shape, const glm::dvec3& emission) {
        const XmlElement* bsdf = shape.only_object("bsdf");
        const MaterialKey key{bsdf, emission};
        if (auto found = materials_.find(key); found != materials_.end()) return found->second;
        Material m;
        if (bsdf) {
            m = bsdf_material(*bsdf);
        } else {
            // Mitsuba's default BSDF (render/shape.cpp): diffuse, 0.5, black on an emitter.
            m.type = MaterialType::Diffuse;
            m.albedo = glm::dvec3(emits(emission) ? 0.0 : 0.5);
            m.one_sided = true;
        }
        std::string name = bsdf && bsdf->attribute("id") ? *bsdf->attribute("id") : "";
        if (name.empty()) name = bsdf ? *bsdf->attribute("type") : "default";
        if (emits(emission)) {
            // A diffuse BSDF glows; any other becomes an emitter, black but for its emission.
            if (m.type != MaterialType::Diffuse) {
                m = Material{};
                m.type = MaterialType::Emitter;
            }
            m.emission = emission;
            name += " (area emitter)";
        }
        m.name = unique_name(name);
        out_.scene.materials.push_back(m);
        const int index = int(out_.scene.materials.size()) - 1;
        materials_.emplace(key, index);
        return index;
    }

    static bool emits(const glm::dvec3& e) { return e.x > 0.0 || e.y > 0.0 || e.z > 0.0; }

    std::string unique_name(const std::string& base) {
        std::string name = base;
        for (int n = 2; !names_.insert(name).second; ++n) name = base + " " + std::to_string(n);
        return name;
    }

    // ---- shapes ----

    void read_shape(const XmlElement& element) {
        const Plugin shape(element, ids_);
        const std::string& type = shape.type();
        if (type == "obj" || type == "ply") {
            shape.allow({"filename", "to_world", "face_normals", "flip_normals", "flip_tex_coords"},
                        {"bsdf", "emitter"});
            shape.boolean("flip_tex_coords", true);
            read_file_mesh(shape);
        } else if (type == "serialized") {
            shape.allow({"filename", "shape_index", "to_world", "face_normals", "flip_normals"}, {"bsdf", "emitter"});
            read_serialized(shape);
        } else if (type == "cube") {
            shape.allow({"to_world", "flip_normals"}, {"bsdf", "emitter"});
            add_mesh(shape, cube_mesh(), "", false, true);
        } else if (type == "disk") {
            shape.allow({"to_world", "flip_normals"}, {"bsdf", "emitter"});
            // An analytic shape in Mitsuba: its front is to_world's normal of +z, mirrored or not.
            add_mesh(shape, disk_mesh(), "", false, false);
        } else if (type == "rectangle") {
            shape.allow({"to_world", "flip_normals"}, {"bsdf", "emitter"});
            read_rectangle(shape);
        } else if (type == "sphere") {
            shape.allow({"center", "radius", "to_world", "flip_normals"}, {"bsdf", "emitter"});
            read_sphere(shape);
        } else {
            shape.fail("not supported (supported: obj, ply, serialized, rectangle, cube, sphere, disk)");
        }
    }

    const XmlElement& transform_or_shape(const Plugin& shape) const {
        const XmlElement* p = shape.property("to_world");
        return p ? *p : shape.element();
    }

    static void check_invertible(const Plugin& shape, const XmlElement& at, const glm::dmat4& m) {
        if (glm::determinant(glm::dmat3(m)) == 0.0) shape.fail(at, "transform \"to_world\": is singular (flattens it)");
    }

    void read_rectangle(const Plugin& shape) {
        const glm::dmat4 m = shape.optional_transform("to_world").value_or(glm::dmat4(1.0));
        check_invertible(shape, transform_or_shape(shape), m);
        Quad quad;
        quad.corner = glm::dvec3(m * glm::dvec4(-1.0, -1.0, 0.0, 1.0));
        quad.edge1 = glm::dvec3(m * glm::dvec4(2.0, 0.0, 0.0, 0.0));
        quad.edge2 = glm::dvec3(m * glm::dvec4(0.0, 2.0, 0.0, 0.0));
        // Mitsuba's front is to_world's normal of +z; edge1 x edge2 points the other way when it mirrors.
        if ((glm::determinant(glm::dmat3(m)) < 0.0) != shape.boolean("flip_normals", false))
            std::swap(quad.edge1, quad.edge2);
        const glm::dvec3 n = glm::cross(quad.edge1, quad.edge2);
        if (!(glm::length(n) > 1e-6 * glm::length(quad.edge1) * glm::length(quad.edge2)))
            shape.fail(transform_or_shape(shape), "transform \"to_world\": flattens the rectangle");
        quad.material = material_index(shape, area_emission(shape));
        out_.scene.quads.push_back(quad);
    }

    void read_sphere(const Plugin& shape) {
        const glm::dmat4 to_world = shape.optional_transform("to_world").value_or(glm::dmat4(1.0));
        const glm::dvec3 center = shape.optional_point("center").value_or(glm::dvec3(0.0));
        const double radius = shape.number("radius", 1.0);
        if (!(radius > 0.0))
            shape.fail(*shape.property("radius"), "float \"radius\": must be > 0, got " + format_number(radius));
        // Mitsuba's sphere: to_world * translate(center) * scale(radius).
        const glm::dmat4 m = glm::scale(glm::translate(to_world, center), glm::dvec3(radius));
        const glm::dmat3 linear(m);
        const double r = glm::length(linear[0]);
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j)
                if (std::fabs(glm::dot(linear[i], linear[j]) - (i == j ? r * r : 0.0)) > 1e-6 * r * r)
                    shape.fail(transform_or_shape(shape),
                               "transform \"to_world\": a sphere's may not scale unevenly or shear");
        const bool flipped = (glm::determinant(linear) < 0.0) != shape.boolean("flip_normals", false);
        Sphere sphere;
        sphere.center = glm::dvec3(m[3]);
        sphere.radius = r;
        if (!(r > 0.0) || r > kMaxSceneMagnitude) shape.fail("its radius " + format_number(r) + " is out of range");
        sphere.material = material_index(shape, area_emission(shape));
        const Material& material = out_.scene.materials[std::size_t(sphere.material)];
        if (flipped && (material.emits() || material.type == MaterialType::Glass))
            shape.fail(
                "inward normals (flip_normals, or a mirroring to_world) on an emitting or dielectric sphere: "
                "not supported");
        out_.scene.spheres.push_back(sphere);
    }

    // The OBJ and PLY files the shapes name, in order, for the importer to
    // start on ahead; read_shape checks every shape as it comes (a malformed
    // one is left out here).
    std::vector<fs::path> named_mesh_files(const std::vector<const XmlElement*>& shapes) const {
        std::vector<fs::path> files;
        for (const XmlElement* element : shapes) {
            const std::string* type = element->attribute("type");
            if (!type || (*type != "obj" && *type != "ply")) continue;
            const XmlElement* filename = Plugin(*element, ids_).property("filename");
            const std::string* value = filename && filename->tag == "string" ? filename->attribute("value") : nullptr;
            if (value && !value->empty()) files.push_back(resolve_scene_file(xml_, *value));
        }
        return files;
    }

    // A mesh file's absolute name: as Mitsuba resolves it (the <path>s, then the scene's folder).
    fs::path mesh_path(const Plugin& shape, std::string& name) const {
        const std::optional<std::string> filename = shape.optional_string("filename");
        if (!filename) shape.fail("missing property filename");
        if (filename->empty()) shape.fail(*shape.property("filename"), "string \"filename\": must not be empty");
        name = *filename;
        return resolve_scene_file(xml_, *filename);
    }

    void read_file_mesh(const Plugin& shape) {
        std::string name;
        const fs::path path = mesh_path(shape, name);
        ImportedScene imported;
        try {
            imported = importer_.import(path);
        } catch (const MeshFileError& error) {
            shape.fail(*shape.property("filename"), name + ": " + error.what());
        }
        orient_file_uvs(path, imported);
        bool exact = true;
        ImportedMesh mesh = merge_imported(imported, exact);
        add_mesh(shape, std::move(mesh), path.string(), exact, true);
    }

    void read_serialized(const Plugin& shape) {
        std::string name;
        const fs::path path = mesh_path(shape, name);
        const std::int64_t index =
            shape.optional_integer("shape_index", 0, std::numeric_limits<int>::max()).value_or(0);
        ImportedMesh mesh;
        try {
            mesh = read_serialized_mesh(path, index);
        } catch (const MeshFileError& error) {
            shape.fail(*shape.property("filename"), name + ": " + error.what());
        }
        add_mesh(shape, std::move(mesh), "", false, true);
    }

    // `from_corners`: Mitsuba's front is the side its transformed corners wind counter-clockwise
    // around (meshes), else to_world's normal of the local front (analytic shapes, wavepath's rule).
    void add_mesh(const Plugin& shape, ImportedMesh local, const std::string& file, bool exact, bool from_corners) {
        const glm::dmat4 to_world = shape.optional_transform("to_world").value_or(glm::dmat4(1.0));
        const XmlElement& at = transform_or_shape(shape);
        check_invertible(shape, at, to_world);
        const bool face_normals = shape.boolean("face_normals", false);
        const bool mirrors = glm::determinant(glm::dmat3(to_world)) < 0.0;
        const bool flip = shape.boolean("flip_normals", false) != (from_corners && mirrors);
        if (face_normals) {
            local.has_normals = false;
            local.normals.clear();
        }
        if (flip)
            for (glm::uvec3& t : local.triangles) std::swap(t.y, t.z);
        MeshOrigin origin;
        origin.to_world = to_world;
        origin.face_normals = face_normals;
        origin.file = file;
        origin.as_file = !file.empty() && exact && !flip && (face_normals || local.has_normals);

        ImportedScene scene;
        scene.meshes.push_back(local);
        scene.nodes.push_back(ImportedNode{});
        scene.nodes[0].transform = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
        scene.nodes[0].meshes = {0};
        const std::string* filename =
            shape.property("filename") ? shape.property("filename")->attribute("value") : nullptr;
        Mesh mesh;
        try {
            mesh = mesh_from_import(scene, MeshFileOptions{to_world, face_normals, {}});
        } catch (const MeshFileError& error) {
            shape.fail(filename ? *shape.property("filename") : at, (filename ? *filename + ": " : "") + error.what());
        }
        // Mitsuba smooths a mesh without normals unless face_normals; wavepath would not.
        const bool smooth = !face_normals && mesh.normals.empty() && shape.type() != "cube" && shape.type() != "disk";
        if (smooth) {
            compute_vertex_normals(mesh);
            // The same normals in the mesh's own coordinates, for `wavepath convert`'s file.
            const glm::dmat3 to_local_normal = glm::transpose(glm::dmat3(to_world));
            local.has_normals = true;
            local.normals.clear();
            for (const glm::dvec3& n : mesh.normals)
                local.normals.push_back(glm::vec3(glm::normalize(to_local_normal * n)));
        }
        mesh.file = filename ? *filename : shape.type();
        mesh.material = material_index(shape, area_emission(shape));
        origin.local = std::move(local);
        triangles_ += mesh.triangles.size();
        if (triangles_ > kMaxTriangles)
            shape.fail("the meshes so far have " + std::to_string(triangles_) + " triangles, more than the " +
                       std::to_string(kMaxTriangles) + " a scene may have");
        out_.scene.meshes.push_back(std::move(mesh));
        out_.meshes.push_back(std::move(origin));
    }

    XmlScene xml_;
    MeshImporter importer_;  // one helper for all the scene's mesh files
    const ShapeProgress& progress_;
    IdTable ids_;
    MitsubaScene out_;
    std::map<MaterialKey, int> materials_;
    std::map<TextureUse, int> textures_;  // texture_index's
    std::size_t texels_ = 0;              // of every texture read
    std::set<std::string> names_;
    std::vector<const XmlElement*> converting_;
    std::size_t triangles_ = 0;
};

}  // namespace

bool is_mitsuba_scene_path(const std::string& path) {
    const std::string extension = lower(fs::path(path).extension().string());
    return extension == ".xml";
}

MitsubaScene read_mitsuba_scene(const std::string& path, const XmlDefines& defines, const MeshImportLimits& mesh_import,
                                const ShapeProgress& progress) {
    return Reader(read_xml_scene(path, defines), path, mesh_import, progress).read();
}

MitsubaScene parse_mitsuba_scene(const std::string& text, const std::string& path, const XmlDefines& defines,
                                 const MeshImportLimits& mesh_import, const ShapeProgress& progress) {
    return Reader(parse_xml_scene(text, path, defines), path, mesh_import, progress).read();
}

Scene load_mitsuba_scene(const std::string& path, const XmlDefines& defines, const MeshImportLimits& mesh_import,
                         std::vector<std::string>* warnings, const ShapeProgress& progress) {
    MitsubaScene read = read_mitsuba_scene(path, defines, mesh_import, progress);
    finish_scene(read.scene);
    if (warnings) *warnings = std::move(read.warnings);
    return std::move(read.scene);
}

}  // namespace wp
