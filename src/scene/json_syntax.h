// Strict JSON parsing for scene files: one SceneError line on failure.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

namespace wp {

// Parses `text`, or throws SceneError naming the source and either the line
// and column of a syntax error or number overflow ("<source>: line 2,
// column 7: malformed JSON: ..."), or the JSON path of a duplicate key
// ("<source>: camera.fov_y: duplicate key").
nlohmann::json parse_json_strictly(const std::string& text, const std::string& source);

}  // namespace wp
