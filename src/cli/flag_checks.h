// Validators for numeric flags, worded like the scene loader's messages so
// that a flag and the scene key it overrides fail the same way.
#pragma once

#include <CLI/CLI.hpp>
#include <cstdint>

namespace wp::cli {

// Accepts a decimal integer in [min, max]; otherwise CLI11 reports
// "--flag: must be in [min, max], got <text>" (exit 2).
CLI::Validator integer_in(std::int64_t min, std::int64_t max);

// Accepts a decimal number in [min, max] (not NaN, which CLI::Range lets
// through); otherwise "--flag: must be a number in [min, max], got <text>".
CLI::Validator number_in(double min, double max);

}  // namespace wp::cli
