#include "scene/off_check.h"

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "scene/mesh_file.h"
#include "scene/mesh_words.h"

namespace wp {
namespace {

// assimp copies a line into 4096 bytes and then writes its terminator.
constexpr std::size_t kMaxLineBytes = 4095;
// assimp drops a face of more vertices (and of none).
constexpr std::uint64_t kMaxFaceVertices = 9;
// assimp reads counts and indices into 32 bits, wrapping larger ones.
constexpr std::uint64_t kMaxCount = 0xffffffffu;

// Between the header's words, as assimp skips them.
bool is_header_space(char c) { return is_blank(c) || c == '\r' || c == '\n'; }

// assimp ends a line at any of these and skips the empty lines between.
bool is_line_end(char c) { return c == '\r' || c == '\n' || c == '\f'; }

// The layout the header announces.
struct OffHeader {
    std::uint64_t coordinates = 3;  // numbers before a vertex's normal, colour and texture coordinates
    std::uint64_t vertices = 0;
    std::uint64_t faces = 0;
};

class OffChecker {
 public:
    explicit OffChecker(std::string_view text) : text_(text) {}

    void check() {
        read_header();
        if (const std::size_t nul = text_.find('\0'); nul != std::string_view::npos)
            fail_at(nul, "a NUL byte (assimp's OFF reader ends the text there)");
        for (std::uint64_t v = 0; v < header_.vertices; ++v) check_vertex(next_body_line(), v);
        for (std::uint64_t f = 0; f < header_.faces; ++f) check_face(next_body_line(), f);
        check_rest();
    }

 private:
    [[noreturn]] void fail(const std::string& problem) const { throw MeshFileError(problem); }

    [[noreturn]] void fail_at(std::size_t offset, const std::string& problem) const {
        const auto line = 1 + std::count(text_.begin(), text_.begin() + static_cast<std::ptrdiff_t>(offset), '\n');
        fail("OFF line " + std::to_string(line) + ": " + problem);
    }

    // ---- the header, read a word at a time ----

    // Past blanks, line ends and lines from '#' on, to the next word.
    void skip_to_header_word() {
        while (pos_ < text_.size() && (is_header_space(text_[pos_]) || text_[pos_] == '#')) {
            if (text_[pos_] == '#') {
                while (pos_ < text_.size() && text_[pos_] != '\r' && text_[pos_] != '\n') ++pos_;
            } else {
                ++pos_;
            }
        }
    }

    std::string_view next_header_word() {
        skip_to_header_word();
        const std::size_t start = pos_;
        while (pos_ < text_.size() && !is_header_space(text_[pos_])) ++pos_;
        return text_.substr(start, pos_ - start);
    }

    std::uint64_t read_count() {
        std::uint64_t count = 0;
        if (!parse_whole_number(next_header_word(), kMaxCount, count))
            fail("OFF header: expected the vertex, face and edge counts (whole numbers below 2^32)");
        return count;
    }

    void read_header() {
        skip_to_header_word();
        const std::size_t first_word = pos_;
        std::uint64_t ignored = 0;
        if (const std::string_view word = next_header_word(); parse_whole_number(word, kMaxCount, ignored)) {
            // assimp takes a leading 4 for the prefix of 4OFF and reads the count from the next digit on.
            if (word.starts_with('4'))
                fail("OFF header: a vertex count that begins with 4 needs the OFF keyword before it");
            pos_ = first_word;  // no keyword (the format allows that): the vertex count
        } else {
            read_keyword(word);
        }
        header_.vertices = read_count();
        header_.faces = read_count();
        read_count();           // edges, which assimp reads and ignores
        skip_to_header_word();  // the first vertex line starts at the next word
    }

    // [ST][C][N][4][n]OFF, the prefixes in that order, as assimp matches them.
    void read_keyword(std::string_view word) {
        if (word.starts_with("ST")) word.remove_prefix(2);
        if (word.starts_with('C')) word.remove_prefix(1);
        if (word.starts_with('N')) word.remove_prefix(1);
        const bool homogeneous = word.starts_with('4');
        if (homogeneous) word.remove_prefix(1);
        const bool dimension = word.starts_with('n');
        if (dimension) word.remove_prefix(1);
        if (word != "OFF")
            fail("OFF header: the first word must be OFF (after prefixes among ST, C, N, 4, n) or the vertex count");
        if (dimension && (!parse_whole_number(next_header_word(), 3, header_.coordinates) || header_.coordinates == 0))
            fail("OFF header: expected the dimension after nOFF, 1, 2 or 3");
        header_.coordinates += homogeneous ? 1 : 0;  // w, which divides the others
    }

    // ---- the body, read a line at a time ----

    // The next line as assimp cuts it (empty lines skipped); fails at the end of the text.
    std::string_view next_body_line() {
        if (pos_ == text_.size()) {
            fail("OFF header declares " + std::to_string(header_.vertices) + " vertices and " +
                 std::to_string(header_.faces) + " faces, but only " + std::to_string(body_lines_) +
                 " lines follow it");
        }
        line_start_ = pos_;
        while (pos_ < text_.size() && !is_line_end(text_[pos_])) ++pos_;
        const std::string_view line = text_.substr(line_start_, pos_ - line_start_);
        while (pos_ < text_.size() && is_line_end(text_[pos_])) ++pos_;
        if (line.size() > kMaxLineBytes)
            fail_at(line_start_, "longer than " + std::to_string(kMaxLineBytes) + " bytes, assimp's limit");
        ++body_lines_;
        return line;
    }

    void check_vertex(std::string_view line, std::uint64_t vertex) {
        const std::vector<std::string_view> words = blank_separated_words(line);
        if (words.size() < header_.coordinates ||
            !std::all_of(words.begin(), words.begin() + static_cast<std::ptrdiff_t>(header_.coordinates), is_real)) {
            fail_at(line_start_, "expected " + std::to_string(header_.coordinates) + " numbers (vertex " +
                                     std::to_string(vertex + 1) + " of " + std::to_string(header_.vertices) + ")");
        }
    }

    void check_face(std::string_view line, std::uint64_t face) {
        const std::vector<std::string_view> words = blank_separated_words(line);
        std::uint64_t size = 0;
        if (words.empty() || !parse_whole_number(words[0], kMaxCount, size)) {
            fail_at(line_start_, "expected a face's vertex count (face " + std::to_string(face + 1) + " of " +
                                     std::to_string(header_.faces) + ")");
        }
        if (size == 0 || size > kMaxFaceVertices) {
            fail_at(line_start_, "a face of " + std::to_string(size) + " vertices (assimp reads faces of 1 to " +
                                     std::to_string(kMaxFaceVertices) + ")");
        }
        if (words.size() <= size)
            fail_at(line_start_, "expected " + std::to_string(size) + " vertex indices after the face's count");
        for (std::uint64_t i = 1; i <= size; ++i) {
            std::uint64_t index = 0;
            if (!parse_whole_number(words[i], kMaxCount, index))
                fail_at(line_start_, "expected " + std::to_string(size) + " vertex indices after the face's count");
            if (index >= header_.vertices) {
                fail_at(line_start_, "vertex index " + std::to_string(index) + " out of range (" +
                                         std::to_string(header_.vertices) + " vertices)");
            }
        }
    }

    // assimp ignores what follows the faces; lines there other than comments
    // say the counts or the layout are not what the file holds.
    void check_rest() {
        while (pos_ < text_.size()) {
            const std::string_view line = next_body_line();
            const std::vector<std::string_view> words = blank_separated_words(line);
            if (!words.empty() && !words[0].starts_with('#')) {
                fail_at(line_start_, "more lines than the header declares (" + std::to_string(header_.vertices) +
                                         " vertices, " + std::to_string(header_.faces) + " faces)");
            }
        }
    }

    std::string_view text_;
    std::size_t pos_ = 0;
    std::size_t line_start_ = 0;
    std::uint64_t body_lines_ = 0;
    OffHeader header_;
};

}  // namespace

void check_off(std::string_view text) { OffChecker(text).check(); }

}  // namespace wp
