#include "scene/json_field.h"

#include <cctype>
#include <cmath>

#include "scene/scene.h"

namespace wp {
namespace {

bool is_identifier(std::string_view key) {
    if (key.empty() || std::isdigit(static_cast<unsigned char>(key.front()))) return false;
    for (char c : key) {
        if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_' && c != '-') return false;
    }
    return true;
}

std::string join(std::initializer_list<std::string_view> words) {
    std::string joined;
    for (std::string_view word : words) {
        if (!joined.empty()) joined += ", ";
        joined += word;
    }
    return joined;
}

std::string range_text(std::int64_t min, std::int64_t max) {
    std::string text = "[";
    return text.append(std::to_string(min)).append(", ").append(std::to_string(max)).append("]");
}

}  // namespace

std::string json_member_path(std::string parent, std::string_view key) {
    if (!is_identifier(key)) return parent.append("[").append(nlohmann::json(key).dump()).append("]");
    return parent.empty() ? std::string(key) : parent.append(".").append(key);
}

JsonField::JsonField(const nlohmann::json& value, std::string path, const std::string& source)
    : value_(value), path_(std::move(path)), source_(source) {}

JsonField root_field(const nlohmann::json& document, const std::string& source) {
    return JsonField(document, "", source);
}

JsonField JsonField::child(const nlohmann::json& value, std::string path) const {
    return JsonField(value, std::move(path), source_);
}

void JsonField::fail(std::string_view problem) const {
    throw SceneError(source_ + ": " + (path_.empty() ? "(root)" : path_) + ": " + std::string(problem));
}

void JsonField::fail_type(std::string_view expected) const {
    fail("must be " + std::string(expected) + ", got " + value_.type_name());
}

const nlohmann::json::object_t& JsonField::object() const {
    if (!value_.is_object()) fail_type("an object");
    return value_.get_ref<const nlohmann::json::object_t&>();
}

void JsonField::allow_only_keys(std::initializer_list<std::string_view> keys) const {
    for (const auto& [key, value] : object()) {
        bool known = false;
        for (std::string_view allowed : keys) known |= key == allowed;
        if (!known)
            child(value, json_member_path(path_, key)).fail("unknown key (expected one of: " + join(keys) + ")");
    }
}

std::optional<JsonField> JsonField::optional_member(std::string_view key) const {
    const auto& members = object();
    auto found = members.find(std::string(key));
    if (found == members.end()) return std::nullopt;
    return child(found->second, json_member_path(path_, key));
}

JsonField JsonField::member(std::string_view key) const {
    std::optional<JsonField> field = optional_member(key);
    if (!field) child(value_, json_member_path(path_, key)).fail("missing required key");
    return *field;
}

std::size_t JsonField::array_size() const {
    if (!value_.is_array()) fail_type("an array");
    return value_.size();
}

JsonField JsonField::element(std::size_t index) const {
    return child(value_.at(index), path_ + "[" + std::to_string(index) + "]");
}

double JsonField::number() const {
    if (!value_.is_number()) fail_type("a number");
    double value = value_.get<double>();  // finite: the parser rejects overflow
    if (std::fabs(value) > kMaxSceneMagnitude) {
        fail("magnitude must be <= " + format_number(kMaxSceneMagnitude) + ", got " + format_number(value));
    }
    return value;
}

std::int64_t JsonField::integer(std::int64_t min, std::int64_t max) const {
    if (value_.is_number_float()) fail("must be an integer, got " + format_number(value_.get<double>()));
    if (!value_.is_number_integer()) fail_type("an integer");
    bool too_large = value_.is_number_unsigned() && value_.get<std::uint64_t>() > static_cast<std::uint64_t>(max);
    std::int64_t value = too_large ? max : value_.get<std::int64_t>();
    if (too_large || value < min || value > max) fail("must be in " + range_text(min, max) + ", got " + value_.dump());
    return value;
}

bool JsonField::boolean() const {
    if (!value_.is_boolean()) fail_type("a boolean");
    return value_.get<bool>();
}

std::string JsonField::string() const {
    if (!value_.is_string()) fail_type("a string");
    return value_.get<std::string>();
}

glm::dvec3 JsonField::vec3() const {
    if (!value_.is_array()) fail_type("an array of 3 numbers");
    if (value_.size() != 3) fail("must be an array of 3 numbers, got " + std::to_string(value_.size()) + " elements");
    return {element(0).number(), element(1).number(), element(2).number()};
}

glm::dvec3 JsonField::vec3_in(double min, double max, std::string_view max_reason) const {
    glm::dvec3 v = vec3();
    for (int i = 0; i < 3; ++i) {
        std::string got = ", got " + format_number(v[i]);
        if (v[i] < min) element(i).fail("must be >= " + format_number(min) + got);
        if (v[i] > max) element(i).fail("must be <= " + format_number(max) + std::string(max_reason) + got);
    }
    return v;
}

}  // namespace wp
