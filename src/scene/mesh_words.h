// Words of a mesh file's text lines, as assimp's OFF and PLY readers split
// them: at blanks (space and tab) only.
#pragma once

#include <charconv>
#include <cstdint>
#include <string_view>
#include <system_error>
#include <vector>

namespace wp {

inline bool is_blank(char c) { return c == ' ' || c == '\t'; }

inline std::vector<std::string_view> blank_separated_words(std::string_view line) {
    std::vector<std::string_view> words;
    for (std::size_t i = 0; i < line.size();) {
        while (i < line.size() && is_blank(line[i])) ++i;
        const std::size_t start = i;
        while (i < line.size() && !is_blank(line[i])) ++i;
        if (i > start) words.push_back(line.substr(start, i - start));
    }
    return words;
}
// A whole word of decimal digits, at most `max`.
inline bool parse_whole_number(std::string_view word, std::uint64_t max, std::uint64_t& value) {
    auto [end, error] = std::from_chars(word.data(), word.data() + word.size(), value);
    return error == std::errc() && end == word.data() + word.size() && value <= max;
}

// A whole word that is a decimal real number, sign included (overflow
// included: assimp reads it as infinity, which the mesh checks report).
inline bool is_real(std::string_view word) {
    if (word.starts_with('+')) word.remove_prefix(1);
    double value = 0.0;
    auto [end, error] = std::from_chars(word.data(), word.data() + word.size(), value);
    return end == word.data() + word.size() && !word.empty() &&
           (error == std::errc() || error == std::errc::result_out_of_range);
}

}  // namespace wp
