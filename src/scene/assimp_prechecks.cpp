#include "scene/assimp_prechecks.h"

#include <algorithm>
#include <assimp/Importer.hpp>
#include <cctype>
#include <cstdint>
#include <fstream>
#include <string>
#include <string_view>

#include "scene/mesh_file.h"
#include "scene/mesh_words.h"
#include "scene/off_check.h"
#include "scene/ply_check.h"

namespace wp {
namespace {

// The prefix of the file its kind is told from.
constexpr std::size_t kHeadBytes = 1 << 16;

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

// The next word of `text` from `i` on (empty at the end), `i` moved past it.
std::string_view next_word(std::string_view text, std::size_t& i) {
    while (i < text.size() && is_space(text[i])) ++i;
    const std::size_t start = i;
    while (i < text.size() && !is_space(text[i])) ++i;
    return text.substr(start, i - start);
}

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

void check_before_assimp(const std::filesystem::path& path) {
    std::error_code error;
    const std::uintmax_t file_size = std::filesystem::file_size(path, error);
    if (error) return;  // not a regular file: reading it reports the problem
    const std::string head = read_file(path, std::min<std::uintmax_t>(file_size, kHeadBytes));
    if (read_as_off(path, head)) return check_off(read_file(path, file_size));
    std::size_t start = 0;
    // In lower case: assimp takes "plY\xff..." for PLY too.
    const std::string magic = to_lower(std::string(next_word(head, start)));
    if (magic.starts_with("ply")) check_ply(read_file(path, file_size));
}

}  // namespace wp
