// Numbers in messages, written as they read back.
#pragma once

#include <array>
#include <charconv>
#include <string>

namespace wp {

// Shortest text that reads back as the same double ("-1", "0.1", "1e+13").
inline std::string format_number(double value) {
    std::array<char, 32> buffer{};
    auto result = std::to_chars(buffer.data(), buffer.data() + buffer.size(), value);
    return std::string(buffer.data(), result.ptr);
}

}  // namespace wp
