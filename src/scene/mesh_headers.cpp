#include "scene/mesh_headers.h"

#include <algorithm>
#include <assimp/Importer.hpp>
#include <cctype>
#include <charconv>
#include <cstdint>
#include <fstream>
#include <string>
#include <string_view>
#include <vector>

#include "scene/mesh_file.h"
#include "scene/off_check.h"

namespace wp {
namespace {

// Headers are read from this prefix of the file; a PLY header must end in it.
constexpr std::size_t kHeaderLimit = 1 << 16;

// Its first `size` bytes (fewer if it is shorter).
std::string read_file(const std::filesystem::path& path, std::uintmax_t size) {
    std::ifstream in(path, std::ios::binary);
    std::string text(size, '\0');
    in.read(text.data(), static_cast<std::streamsize>(text.size()));
    text.resize(static_cast<std::size_t>(in.gcount()));
    return text;
}

std::string to_lower(std::string text) {
    std::transform(text.begin(), text.end(), text.begin(), [](unsigned char c) { return std::tolower(c); });
    return text;
}

bool is_space(char c) { return std::isspace(static_cast<unsigned char>(c)) != 0; }

// The next word of `text` from `i` on (empty at the end), `i` moved past it.
std::string_view next_word(std::string_view text, std::size_t& i) {
    while (i < text.size() && is_space(text[i])) ++i;
    const std::size_t start = i;
    while (i < text.size() && !is_space(text[i])) ++i;
    return text.substr(start, i - start);
}

std::vector<std::string_view> split_words(std::string_view line) {
    std::vector<std::string_view> words;
    std::size_t i = 0;
    for (std::string_view word = next_word(line, i); !word.empty(); word = next_word(line, i)) words.push_back(word);
    return words;
}

// A count as the header writes it; false for anything but decimal digits.
bool parse_count(std::string_view word, std::uint64_t& count) {
    auto [end, error] = std::from_chars(word.data(), word.data() + word.size(), count);
    return error == std::errc() && end == word.data() + word.size();
}

// Fails if `count` elements of at least `min_bytes` each do not fit in the
// `available` bytes; otherwise takes their smallest size from `available`.
void take_elements(std::string_view format, std::uint64_t count, std::string_view what, std::uint64_t min_bytes,
                   std::uint64_t& available) {
    const std::uint64_t fit = min_bytes == 0 ? count : available / min_bytes;
    if (count > fit) {
        throw MeshFileError(std::string(format) + " header declares " + std::to_string(count) + " " +
                            std::string(what) + ", more than the remaining " + std::to_string(available) +
                            " bytes of the file can hold");
    }
    available -= count * min_bytes;
}

// ---- PLY ----

// Bytes of a PLY scalar type, 0 for a word that is not one.
std::uint64_t ply_scalar_bytes(std::string_view type) {
    if (type == "char" || type == "uchar" || type == "int8" || type == "uint8") return 1;
    if (type == "short" || type == "ushort" || type == "int16" || type == "uint16") return 2;
    if (type == "int" || type == "uint" || type == "float" || type == "int32" || type == "uint32" || type == "float32")
        return 4;
    if (type == "double" || type == "float64") return 8;
    return 0;
}

struct PlyElement {
    std::string name;
    std::uint64_t count = 0;
    std::uint64_t min_bytes = 0;  // of one element: ASCII 2 per property ("0 "), binary its fixed sizes
};

// The header's lines, strictly as the PLY format defines them: assimp's
// reader loops forever on some it does not expect (found by fuzz_mesh).
class PlyHeader {
 public:
    // Reads the next line's words; true at end_header.
    bool read_line(const std::vector<std::string_view>& words) {
        ++line_;
        if (line_ == 1 && (words.size() != 1 || words[0] != "ply")) fail("expected \"ply\"");
        if (line_ == 1) return false;
        if (line_ == 2) return read_format(words), false;
        const std::string_view keyword = words.empty() ? std::string_view() : words[0];
        if (keyword == "comment" || keyword == "obj_info") return false;
        if (keyword == "element") return read_element(words), false;
        if (keyword == "property") return read_property(words), false;
        if (keyword == "end_header" && words.size() == 1) return true;
        fail("not a format, element, property, comment, obj_info or end_header line");
    }

    // Fails if the elements do not fit in the `available` bytes after the header.
    void check_sizes(std::uint64_t available) const {
        for (const PlyElement& e : elements_)
            take_elements("PLY", e.count, "\"" + e.name + "\" elements", e.min_bytes, available);
    }

    bool binary() const { return binary_; }

 private:
    [[noreturn]] void fail(const std::string& problem) const {
        throw MeshFileError("PLY header line " + std::to_string(line_) + ": " + problem);
    }

    void read_format(const std::vector<std::string_view>& words) {
        if (words.size() != 3 || words[0] != "format" ||
            (words[1] != "ascii" && words[1] != "binary_little_endian" && words[1] != "binary_big_endian"))
            fail("expected \"format ascii|binary_little_endian|binary_big_endian VERSION\"");
        binary_ = words[1] != "ascii";
    }

    void read_element(const std::vector<std::string_view>& words) {
        PlyElement element;
        if (words.size() != 3 || !parse_count(words[2], element.count)) fail("expected \"element NAME COUNT\"");
        element.name = words[1];
        elements_.push_back(element);
    }

    void read_property(const std::vector<std::string_view>& words) {
        const bool list = words.size() == 5 && words[1] == "list";
        if (elements_.empty()) fail("a property before any element");
        if (!(words.size() == 3 || list) || ply_scalar_bytes(words[1]) + list == 0 ||
            (list && (ply_scalar_bytes(words[2]) == 0 || ply_scalar_bytes(words[3]) == 0)))
            fail("expected \"property TYPE NAME\" or \"property list COUNT_TYPE TYPE NAME\"");
        elements_.back().min_bytes += !binary_ ? 2 : ply_scalar_bytes(words[list ? 2 : 1]);
    }

    int line_ = 0;
    bool binary_ = false;
    std::vector<PlyElement> elements_;
};

// An ASCII PLY's body is text: a NUL byte in a number makes assimp's reader
// allocate gigabytes (15 GB for a face line, found by fuzz_mesh).
void check_ply_text(const std::string& text, std::size_t body_start) {
    if (const std::size_t nul = text.find('\0', body_start); nul != std::string::npos)
        throw MeshFileError("PLY byte " + std::to_string(nul) + ": a NUL byte in an ASCII PLY's body");
}

void check_ply(const std::filesystem::path& path, const std::string& head, std::uintmax_t file_size) {
    PlyHeader header;
    std::size_t start = 0;
    for (std::size_t newline; (newline = head.find('\n', start)) != std::string::npos;) {
        const std::vector<std::string_view> words = split_words(std::string_view(head).substr(start, newline - start));
        start = newline + 1;
        if (!header.read_line(words)) continue;
        header.check_sizes(file_size - start);
        if (!header.binary()) check_ply_text(read_file(path, file_size), start);
        return;
    }
    throw MeshFileError(head.size() < kHeaderLimit ? "PLY header has no end_header line"
                                                   : "PLY header has no end_header line in the first " +
                                                         std::to_string(kHeaderLimit) + " bytes");
}

// ---- OFF ----

// Whether assimp reads the file with its OFF reader: it picks the reader by
// the extension, and for one no reader claims, by the first three bytes
// ("off" in any case), after readers that come earlier in its list have
// declined it (which this does not try to foresee: it checks such a file as OFF).
bool read_as_off(const std::filesystem::path& path, const std::string& head) {
    const std::string extension = to_lower(path.extension().string());
    if (extension == ".off") return true;
    return to_lower(head.substr(0, 3)) == "off" && !Assimp::Importer().IsExtensionSupported(extension);
}

}  // namespace

void check_mesh_header(const std::filesystem::path& path) {
    std::error_code error;
    const std::uintmax_t file_size = std::filesystem::file_size(path, error);
    if (error) return;  // not a regular file: reading it reports the problem
    const std::string head = read_file(path, std::min<std::uintmax_t>(file_size, kHeaderLimit));
    if (read_as_off(path, head)) return check_off(read_file(path, file_size));
    std::size_t start = 0;
    // In lower case: assimp takes "plY\xff..." for PLY too.
    const std::string magic = to_lower(std::string(next_word(head, start)));
    if (magic.starts_with("ply")) check_ply(path, head, file_size);
}

}  // namespace wp
