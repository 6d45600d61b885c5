#include "cli/flag_checks.h"

#include <charconv>
#include <string>

namespace wp::cli {

namespace {

std::string range_text(std::int64_t min, std::int64_t max) {
    return "[" + std::to_string(min) + ", " + std::to_string(max) + "]";
}

}  // namespace

CLI::Validator integer_in(std::int64_t min, std::int64_t max) {
    return CLI::Validator(
        [min, max](std::string& text) -> std::string {
            std::int64_t value = 0;
            const char* end = text.data() + text.size();
            const auto [stop, error] = std::from_chars(text.data(), end, value);
            if (error != std::errc() || stop != end)
                return "must be an integer in " + range_text(min, max) + ", got " + text;
            if (value < min || value > max) return "must be in " + range_text(min, max) + ", got " + text;
            return {};
        },
        "INT in " + range_text(min, max));
}

}  // namespace wp::cli
