// Validators for numeric flags, worded like the scene loader's messages so
// that a flag and the scene key it overrides fail the same way.
#pragma once

#include <CLI/CLI.hpp>
#include <cstdint>

namespace wp::cli {

// Accepts a decimal integer in [min, max]; otherwise CLI11 reports
// "--flag: must be in [min, max], got <text>" (exit 2).
CLI::Validator integer_in(std::int64_t min, std::int64_t max);

}  // namespace wp::cli
