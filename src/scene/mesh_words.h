// Words of a mesh file's text lines: split at blanks (space and tab) only,
// as assimp's OFF and PLY readers split a line, or at any white space.
#pragma once

#include <charconv>
#include <cstdint>
#include <string_view>
#include <system_error>
#include <vector>

namespace wp {

inline bool is_blank(char c) { return c == ' ' || c == '\t'; }

// Any ASCII white space, as std::isspace in the C locale.
inline bool is_space(char c) { return c == ' ' || (c >= '\t' && c <= '\r'); }

// The words of `text` between runs of separators.
inline std::vector<std::string_view> split_words(std::string_view text, bool (*is_separator)(char)) {
    std::vector<std::string_view> words;
    for (std::size_t i = 0; i < text.size();) {
        while (i < text.size() && is_separator(text[i])) ++i;
        const std::size_t start = i;
        while (i < text.size() && !is_separator(text[i])) ++i;
        if (i > start) words.push_back(text.substr(start, i - start));
    }
    return words;
}

inline std::vector<std::string_view> blank_separated_words(std::string_view line) {
    return split_words(line, is_blank);
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
