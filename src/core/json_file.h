// JSON output files for tools (--stats-json, --profile-json), written atomically.
#pragma once

#include <nlohmann/json_fwd.hpp>
#include <string>

namespace wp {

// Writes `value` (indented) to `path` through write_atomically; throws OutputError.
void write_json_atomically(const nlohmann::json& value, const std::string& path);

}  // namespace wp
