// Path-aware, validating access to a parsed JSON document. Every value read
// through a JsonField knows where it sits ("shapes[3].radius"), so that any
// problem becomes one SceneError line "<source>: <path>: <problem>".
#pragma once

#include <cstdint>
#include <glm/vec3.hpp>
#include <initializer_list>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>

#include "core/number_text.h"

namespace wp {

// The largest magnitude accepted for any real number in a scene: keeps
// squared distances, areas and light powers far from overflow, in float too.
inline constexpr double kMaxSceneMagnitude = 1e12;

// "camera" + "fov_y" -> "camera.fov_y"; odd names are quoted: materials["my light"].
std::string json_member_path(std::string parent, std::string_view key);

class JsonField {
 public:
    JsonField(const nlohmann::json& value, std::string path, const std::string& source);

    const std::string& path() const { return path_; }
    [[noreturn]] void fail(std::string_view problem) const;
    // "must be <expected>, got <JSON type>".
    [[noreturn]] void fail_type(std::string_view expected) const;

    // For values that may take more than one form.
    bool is_number() const { return value_.is_number(); }
    bool is_array() const { return value_.is_array(); }
    bool is_string() const { return value_.is_string(); }
    bool is_object() const { return value_.is_object(); }

    // Objects. `allow_only_keys` also checks that this is an object.
    void allow_only_keys(std::initializer_list<std::string_view> keys) const;
    JsonField member(std::string_view key) const;  // fails if missing
    std::optional<JsonField> optional_member(std::string_view key) const;
    const nlohmann::json::object_t& object() const;

    // Arrays.
    std::size_t array_size() const;
    JsonField element(std::size_t index) const;

    // Leaves.
    double number() const;  // within kMaxSceneMagnitude (the parser already rejects overflow)
    std::int64_t integer(std::int64_t min, std::int64_t max) const;
    bool boolean() const;
    std::string string() const;
    glm::dvec3 vec3() const;
    // Every component in [min, max]; the error names the component.
    glm::dvec3 vec3_in(double min, double max, std::string_view max_reason = {}) const;

 private:
    JsonField child(const nlohmann::json& value, std::string path) const;

    const nlohmann::json& value_;
    std::string path_;
    const std::string& source_;
};

// The document's top level as a JsonField; the JSON itself must already parse.
JsonField root_field(const nlohmann::json& document, const std::string& source);

}  // namespace wp
