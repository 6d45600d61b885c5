#include "scene/json_syntax.h"

#include <algorithm>
#include <set>
#include <vector>

#include "scene/json_field.h"
#include "scene/scene.h"

namespace wp {
namespace {

// Checks a text without building it: finds where and why it fails to parse
// (unlike json::parse's exceptions, this also locates number overflow such as
// 1e999) and which key, if any, appears twice in one object.
class SyntaxChecker : public nlohmann::json_sax<nlohmann::json> {
 public:
    std::size_t error_byte = 0;  // 1-based; one past the end for a premature end of input
    std::string error_message;
    std::string duplicate_key_path;

    bool null() override { return value(); }
    bool boolean(bool) override { return value(); }
    bool number_integer(number_integer_t) override { return value(); }
    bool number_unsigned(number_unsigned_t) override { return value(); }
    bool number_float(number_float_t, const string_t&) override { return value(); }
    bool string(string_t&) override { return value(); }
    bool binary(binary_t&) override { return value(); }
    bool start_object(std::size_t) override { return open(true); }
    bool start_array(std::size_t) override { return open(false); }
    bool end_object() override { return close(); }
    bool end_array() override { return close(); }

    bool key(string_t& name) override {
        Scope& object = scopes_.back();
        object.key = name;
        if (object.keys.insert(name).second) return true;
        duplicate_key_path = path();
        return false;
    }

    bool parse_error(std::size_t byte, const std::string&, const nlohmann::json::exception& error) override {
        error_byte = byte;
        error_message = error.what();
        return false;
    }

 private:
    struct Scope {
        bool is_object = false;
        std::set<std::string> keys;  // objects: the keys seen so far
        std::string key;             // objects: the current member
        std::size_t elements = 0;    // arrays: elements seen so far
    };

    bool value() {
        if (!scopes_.empty() && !scopes_.back().is_object) ++scopes_.back().elements;
        return true;
    }
    bool open(bool is_object) {
        value();
        scopes_.push_back({is_object, {}, {}, 0});
        return true;
    }
    bool close() {
        scopes_.pop_back();
        return true;
    }

    // Appended in place: copying the path at every level would cost the square of the depth
    // (fuzz_scene: a duplicate key under 40,000 nested arrays took 20 s under AddressSanitizer).
    std::string path() const {
        std::string path;
        for (const Scope& scope : scopes_) {
            if (scope.is_object)
                path = json_member_path(std::move(path), scope.key);
            else
                path.append("[").append(std::to_string(scope.elements - 1)).append("]");
        }
        return path;
    }

    std::vector<Scope> scopes_;
};

// "line L, column C" of the character at 1-based `byte`.
std::string text_position(const std::string& text, std::size_t byte) {
    std::size_t index = std::min(byte > 0 ? byte - 1 : 0, text.size());
    std::size_t line = 1, line_start = 0;
    for (std::size_t i = 0; i < index; ++i) {
        if (text[i] == '\n') {
            ++line;
            line_start = i + 1;
        }
    }
    return "line " + std::to_string(line) + ", column " + std::to_string(index - line_start + 1);
}

// nlohmann's message without "[json.exception.parse_error.101] parse error at line 2, column 13: ".
std::string parse_problem(std::string message) {
    if (std::size_t end = message.find("] "); end != std::string::npos) message.erase(0, end + 2);
    std::size_t colon = message.find(": ");
    if (message.starts_with("parse error") && colon != std::string::npos) message.erase(0, colon + 2);
    return message;
}

}  // namespace

nlohmann::json parse_json_strictly(const std::string& text, const std::string& source) {
    SyntaxChecker checker;
    if (!nlohmann::json::sax_parse(text, &checker)) {
        if (!checker.duplicate_key_path.empty()) {
            throw SceneError(source + ": " + checker.duplicate_key_path + ": duplicate key");
        }
        throw SceneError(source + ": " + text_position(text, checker.error_byte) +
                         ": malformed JSON: " + parse_problem(checker.error_message));
    }
    return nlohmann::json::parse(text);
}

}  // namespace wp
