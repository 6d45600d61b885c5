#include "cli/flag_checks.h"

#include <charconv>
#include <string>

#include "core/number_text.h"

namespace wp::cli {

namespace {

std::string range_text(std::int64_t min, std::int64_t max) {
    return "[" + std::to_string(min) + ", " + std::to_string(max) + "]";
}

std::string range_text(double min, double max) { return "[" + format_number(min) + ", " + format_number(max) + "]"; }

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

CLI::Validator number_in(double min, double max) {
    return CLI::Validator(
        [min, max](std::string& text) -> std::string {
            double value = 0;
            const char* end = text.data() + text.size();
            const auto [stop, error] = std::from_chars(text.data(), end, value);
            // NaN fails both comparisons; from_chars reads "nan" as it.
            if (error != std::errc() || stop != end || !(value >= min && value <= max))
                return "must be a number in " + range_text(min, max) + ", got " + text;
            return {};
        },
        "FLOAT in " + range_text(min, max));
}

}  // namespace wp::cli
