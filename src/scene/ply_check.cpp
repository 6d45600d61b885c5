#include "scene/ply_check.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "scene/mesh_file.h"
#include "scene/mesh_words.h"

namespace wp {
namespace {

// The header must end within this prefix of the file.
constexpr std::size_t kHeaderLimit = 1 << 16;
// assimp reads a list's count into 32 bits, wrapping larger ones.
constexpr std::uint64_t kMaxListCount = 0xffffffffu;

// ---- types and layout ----

// A scalar type as the header names it.
struct PlyType {
    std::string_view name;
    std::uint64_t bytes;
    bool real;  // float or double; an integer otherwise
    bool is_signed;
};

constexpr std::array kPlyTypes{
    PlyType{"char", 1, false, true},    PlyType{"int8", 1, false, true},    PlyType{"uchar", 1, false, false},
    PlyType{"uint8", 1, false, false},  PlyType{"short", 2, false, true},   PlyType{"int16", 2, false, true},
    PlyType{"ushort", 2, false, false}, PlyType{"uint16", 2, false, false}, PlyType{"int", 4, false, true},
    PlyType{"int32", 4, false, true},   PlyType{"uint", 4, false, false},   PlyType{"uint32", 4, false, false},
    PlyType{"float", 4, true, true},    PlyType{"float32", 4, true, true},  PlyType{"double", 8, true, true},
    PlyType{"float64", 8, true, true},
};

const PlyType* find_type(std::string_view name) {
    const auto* type =
        std::find_if(kPlyTypes.begin(), kPlyTypes.end(), [&](const PlyType& t) { return t.name == name; });
    return type == kPlyTypes.end() ? nullptr : type;
}

struct PlyProperty {
    std::string name;
    const PlyType* type = nullptr;        // of the value, or of a list's items
    const PlyType* count_type = nullptr;  // a list's; null for a scalar
};

struct PlyElement {
    std::string name;
    std::uint64_t count = 0;
    std::vector<PlyProperty> properties;
};

struct PlyLayout {
    bool binary = false;
    bool big_endian = false;
    std::vector<PlyElement> elements;
};

// "face" element 2 of 4, for messages.
std::string describe(const PlyElement& element, std::uint64_t index) {
    return "\"" + element.name + "\" element " + std::to_string(index + 1) + " of " + std::to_string(element.count);
}

// A list's count if `value` is one: a whole number assimp reads as it is.
std::optional<std::uint64_t> as_list_count(double value) {
    if (!(value >= 0.0 && value <= double(kMaxListCount) && value == std::floor(value))) return std::nullopt;
    return static_cast<std::uint64_t>(value);
}

// A word for a message: bytes that are not printable as \xNN, long ones cut.
std::string quoted(std::string_view word) {
    constexpr std::size_t kShown = 32;
    std::string text = "\"";
    for (const char c : word.substr(0, kShown)) {
        const auto byte = static_cast<unsigned char>(c);
        if (std::isprint(byte) != 0) {
            text += c;
        } else {
            constexpr std::string_view kHex = "0123456789abcdef";
            text += std::string("\\x") + kHex[byte >> 4] + kHex[byte & 15];
        }
    }
    return text + (word.size() > kShown ? "...\"" : "\"");
}

// The first byte below 0x20 but a tab: assimp ends a line at \r, \f and NUL
// too, and splits words at blanks only, so such a byte would make its lines
// or words differ from ours (fuzz_mesh: NULs in a header line and a body line).
std::optional<std::string_view> find_control_byte(std::string_view line) {
    const auto control = std::find_if(line.begin(), line.end(),
                                      [](char c) { return static_cast<unsigned char>(c) < 0x20 && c != '\t'; });
    if (control == line.end()) return std::nullopt;
    return line.substr(static_cast<std::size_t>(control - line.begin()), 1);
}

// ---- the header ----

// The header's lines, strictly as the PLY format defines them: assimp's
// reader loops forever on some it does not expect (found by fuzz_mesh).
class PlyHeader {
 public:
    // Reads the next line (without its line end); true at end_header.
    bool read_line(std::string_view line) {
        ++line_;
        if (const auto control = find_control_byte(line)) fail("a control byte " + quoted(*control) + " in the line");
        const std::vector<std::string_view> words = blank_separated_words(line);
        if (line_ == 1 && (words.size() != 1 || words[0] != "ply")) fail("expected \"ply\"");
        if (line_ == 1) return false;
        if (line_ == 2) return read_format(words), false;
        const std::string_view keyword = words.empty() ? std::string_view() : words[0];
        if (keyword == "comment") return false;
        // assimp ends an element's properties at any line but a comment and drops later ones.
        if (keyword == "property" && after_obj_info_) fail("a property after an obj_info line (assimp drops it)");
        after_obj_info_ = keyword == "obj_info";
        if (keyword == "obj_info") return false;
        if (keyword == "element") return read_element(words), false;
        if (keyword == "property") return read_property(words), false;
        if (keyword == "end_header" && words.size() == 1) return true;
        fail("not a format, element, property, comment, obj_info or end_header line");
    }

    const PlyLayout& layout() const { return layout_; }
    int lines() const { return line_; }

 private:
    [[noreturn]] void fail(const std::string& problem) const {
        throw MeshFileError("PLY header line " + std::to_string(line_) + ": " + problem);
    }

    void read_format(const std::vector<std::string_view>& words) {
        if (words.size() != 3 || words[0] != "format" ||
            (words[1] != "ascii" && words[1] != "binary_little_endian" && words[1] != "binary_big_endian"))
            fail("expected \"format ascii|binary_little_endian|binary_big_endian VERSION\"");
        layout_.binary = words[1] != "ascii";
        layout_.big_endian = words[1] == "binary_big_endian";
    }

    void read_element(const std::vector<std::string_view>& words) {
        PlyElement element;
        if (words.size() != 3 || !parse_whole_number(words[2], UINT64_MAX, element.count))
            fail("expected \"element NAME COUNT\"");
        element.name = words[1];
        // assimp reads the count of an element of another name from its name (as 0).
        if (element.name != "vertex" && element.name != "face" && element.name != "tristrips" &&
            element.name != "edge" && element.name != "material")
            fail("element \"" + element.name + "\": assimp reads vertex, face, tristrips, edge and material elements");
        layout_.elements.push_back(element);
    }

    void read_property(const std::vector<std::string_view>& words) {
        if (layout_.elements.empty()) fail("a property before any element");
        PlyProperty property;
        if (words.size() == 3) {
            property = {std::string(words[2]), find_type(words[1])};
        } else if (words.size() == 5 && words[1] == "list") {
            property = {std::string(words[4]), find_type(words[3]), find_type(words[2])};
            if (property.count_type == nullptr) property.type = nullptr;
        }
        if (property.type == nullptr) fail("expected \"property TYPE NAME\" or \"property list COUNT_TYPE TYPE NAME\"");
        layout_.elements.back().properties.push_back(property);
    }

    int line_ = 0;
    bool after_obj_info_ = false;  // the last line but comments was obj_info
    PlyLayout layout_;
};

// ---- an ASCII body: one element a line ----

// An ASCII value of an integer type: decimal, in the type's range.
std::optional<std::int64_t> parse_integer(std::string_view word, const PlyType& type) {
    if (word.starts_with('+')) word.remove_prefix(1);
    std::int64_t value = 0;
    auto [end, error] = std::from_chars(word.data(), word.data() + word.size(), value);
    if (error != std::errc() || end != word.data() + word.size()) return std::nullopt;
    const int bits = static_cast<int>(8 * type.bytes);
    const std::int64_t min = type.is_signed ? -(std::int64_t{1} << (bits - 1)) : 0;
    const std::int64_t max = (std::int64_t{1} << (type.is_signed ? bits - 1 : bits)) - 1;
    if (value < min || value > max) return std::nullopt;
    return value;
}

bool is_value(std::string_view word, const PlyType& type) {
    return type.real ? is_real(word) : parse_integer(word, type).has_value();
}

std::optional<std::uint64_t> ascii_list_count(std::string_view word, const PlyType& type) {
    if (!type.real) {
        const std::optional<std::int64_t> value = parse_integer(word, type);
        return value ? as_list_count(double(*value)) : std::nullopt;
    }
    if (word.starts_with('+')) word.remove_prefix(1);
    double value = 0.0;
    auto [end, error] = std::from_chars(word.data(), word.data() + word.size(), value);
    if (error != std::errc() || end != word.data() + word.size()) return std::nullopt;
    return as_list_count(value);
}

class AsciiBodyChecker {
 public:
    AsciiBodyChecker(std::string_view body, int header_lines) : body_(body), line_(header_lines) {}

    void check(const PlyLayout& layout) {
        for (const PlyElement& element : layout.elements)
            for (std::uint64_t i = 0; i < element.count; ++i) check_element(element, i);
        check_rest();
    }

 private:
    [[noreturn]] void fail(const std::string& problem) const {
        throw MeshFileError("PLY line " + std::to_string(line_) + ": " + problem);
    }

    // The next line, without its line end; nullopt at the end of the body.
    std::optional<std::string_view> next_line() {
        if (pos_ == body_.size()) return std::nullopt;
        ++line_;
        const std::size_t end = std::min(body_.find('\n', pos_), body_.size());
        std::string_view line = body_.substr(pos_, end - pos_);
        pos_ = std::min(end + 1, body_.size());
        if (line.ends_with('\r')) line.remove_suffix(1);
        if (const auto control = find_control_byte(line)) fail("a control byte " + quoted(*control) + " in the line");
        return line;
    }

    // A problem with one of an element's properties.
    [[noreturn]] void fail(const PlyElement& element, std::uint64_t index, const PlyProperty& property,
                           const std::string& problem) const {
        fail(describe(element, index) + ", property \"" + property.name + "\": " + problem);
    }

    void check_value(std::string_view word, const PlyElement& element, std::uint64_t index,
                     const PlyProperty& property) const {
        if (!is_value(word, *property.type))
            fail(element, index, property,
                 quoted(word) + " is not a value of type " + std::string(property.type->name));
    }

    void check_element(const PlyElement& element, std::uint64_t index) {
        const std::optional<std::string_view> line = next_line();
        if (!line) {
            throw MeshFileError("PLY file ends after line " + std::to_string(line_) + ", before " +
                                describe(element, index));
        }
        const std::vector<std::string_view> words = blank_separated_words(*line);
        std::size_t next = 0;
        for (const PlyProperty& property : element.properties) {
            if (next == words.size()) fail(element, index, property, "missing");
            const std::string_view word = words[next++];
            if (property.count_type == nullptr) {
                check_value(word, element, index, property);
                continue;
            }
            const std::optional<std::uint64_t> count = ascii_list_count(word, *property.count_type);
            if (!count) {
                fail(element, index, property,
                     quoted(word) + " is not a list count of type " + std::string(property.count_type->name));
            }
            if (*count > words.size() - next) {
                fail(element, index, property,
                     "a list of " + std::to_string(*count) + " but " + std::to_string(words.size() - next) +
                         " words follow its count");
            }
            for (std::uint64_t i = 0; i < *count; ++i) check_value(words[next++], element, index, property);
        }
        if (next != words.size()) {
            fail(describe(element, index) + ": " + std::to_string(words.size() - next) +
                 " words after its last property");
        }
    }

    void check_rest() {
        for (std::optional<std::string_view> line; (line = next_line());) {
            if (!blank_separated_words(*line).empty()) fail("text after the last element");
        }
    }

    std::string_view body_;
    std::size_t pos_ = 0;
    int line_;  // of the line last read
};

// ---- a binary body ----

class BinaryBodyChecker {
 public:
    BinaryBodyChecker(std::string_view file, std::size_t body_start, bool big_endian)
        : file_(file), pos_(body_start), big_endian_(big_endian) {}

    // Bytes after the last element are ignored, as assimp ignores them.
    void check(const PlyLayout& layout) {
        for (const PlyElement& element : layout.elements) {
            const bool has_list = std::any_of(element.properties.begin(), element.properties.end(),
                                              [](const PlyProperty& p) { return p.count_type != nullptr; });
            if (has_list) {
                for (std::uint64_t i = 0; i < element.count; ++i) check_element(element, i);
            } else {
                skip_fixed_size(element);
            }
        }
    }

 private:
    [[noreturn]] void fail_at(std::size_t offset, const std::string& problem) const {
        throw MeshFileError("PLY byte " + std::to_string(offset) + ": " + problem);
    }

    std::uint64_t remaining() const { return file_.size() - pos_; }

    // Elements of scalars only, all at once.
    void skip_fixed_size(const PlyElement& element) {
        std::uint64_t bytes = 0;
        for (const PlyProperty& property : element.properties) bytes += property.type->bytes;
        if (bytes == 0) return;
        const std::uint64_t fit = remaining() / bytes;
        if (element.count > fit) fail_at(pos_ + fit * bytes, "the file ends within " + describe(element, fit));
        pos_ += element.count * bytes;
    }

    void check_element(const PlyElement& element, std::uint64_t index) {
        for (const PlyProperty& property : element.properties) {
            const std::size_t start = pos_;
            const PlyType& first = property.count_type != nullptr ? *property.count_type : *property.type;
            if (first.bytes > remaining()) fail_at(start, "the file ends within " + describe(element, index));
            const double value = read_value(first);
            if (property.count_type != nullptr) read_list(value, start, element, index, property);
        }
    }

    // The items of a list whose count, at `start`, is `value`.
    void read_list(double value, std::size_t start, const PlyElement& element, std::uint64_t index,
                   const PlyProperty& property) {
        const auto where = [&] { return describe(element, index) + ", property \"" + property.name + "\": "; };
        const std::optional<std::uint64_t> count = as_list_count(value);
        if (!count) fail_at(start, where() + "list count " + to_text(value) + " is not a whole number below 2^32");
        if (*count > remaining() / property.type->bytes) {
            fail_at(start, where() + "a list of " + std::to_string(*count) + " " + std::string(property.type->name) +
                               " but " + std::to_string(remaining()) + " bytes follow its count");
        }
        pos_ += *count * property.type->bytes;
    }

    // The value at pos_, which has its bytes; pos_ moved past it.
    double read_value(const PlyType& type) {
        std::uint64_t bits = 0;
        for (std::uint64_t i = 0; i < type.bytes; ++i) {
            const auto byte = static_cast<unsigned char>(file_[pos_ + (big_endian_ ? i : type.bytes - 1 - i)]);
            bits = bits << 8 | byte;
        }
        pos_ += type.bytes;
        if (type.real) {
            return type.bytes == 4 ? double(std::bit_cast<float>(static_cast<std::uint32_t>(bits)))
                                   : std::bit_cast<double>(bits);
        }
        const int unused = static_cast<int>(64 - 8 * type.bytes);
        return type.is_signed ? double(static_cast<std::int64_t>(bits << unused) >> unused) : double(bits);
    }

    static std::string to_text(double value) {
        std::array<char, 32> text{};
        return std::string(text.data(), std::to_chars(text.data(), text.data() + text.size(), value).ptr);
    }

    std::string_view file_;
    std::size_t pos_;
    bool big_endian_;
};

}  // namespace

void check_ply(std::string_view file) {
    PlyHeader header;
    const std::string_view head = file.substr(0, kHeaderLimit);
    std::size_t start = 0;
    for (std::size_t newline; (newline = head.find('\n', start)) != std::string_view::npos;) {
        std::string_view line = head.substr(start, newline - start);
        start = newline + 1;
        if (line.ends_with('\r')) line.remove_suffix(1);
        if (!header.read_line(line)) continue;
        if (header.layout().binary)
            return BinaryBodyChecker(file, start, header.layout().big_endian).check(header.layout());
        return AsciiBodyChecker(file.substr(start), header.lines()).check(header.layout());
    }
    throw MeshFileError(head.size() < kHeaderLimit ? "PLY header has no end_header line"
                                                   : "PLY header has no end_header line in the first " +
                                                         std::to_string(kHeaderLimit) + " bytes");
}

}  // namespace wp
