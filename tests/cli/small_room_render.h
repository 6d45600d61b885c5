// What the long-render and MPI tests share: `wavepath render` of
// scenes/test/room_small.json (32x32), byte comparison of its outputs, and
// the samples a run rendered.
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "support/temp_directory.h"

namespace wp::test {

inline const std::string kSmallRoomScene = std::string(WAVEPATH_SOURCE_DIR) + "/scenes/test/room_small.json";

// The arguments rendering the small room to `out` at `spp`, then `extra`.
// With --wavefront 64 a pass is one sample per pixel (1024 work items), so
// there are many passes to stop, checkpoint or split between.
inline std::vector<std::string> small_room_render_args(const std::string& out, int spp,
                                                       std::vector<std::string> extra = {}, int wavefront = 64) {
    std::vector<std::string> args{"render", kSmallRoomScene,     "-o",          out,
                                  "--spp",  std::to_string(spp), "--wavefront", std::to_string(wavefront)};
    args.insert(args.end(), extra.begin(), extra.end());
    return args;
}

// Whether two files exist, hold something and hold the same bytes.
inline bool same_bytes(const std::string& a, const std::string& b) {
    const std::string x = read_text(a), y = read_text(b);
    return !x.empty() && x == y;
}

// The camera samples (work items) a run rendered itself, from its
// --stats-json: for a resumed run only those its checkpoint did not hold, so
// that a resume which started over, and gave the same bits, is told apart.
inline std::uint64_t rendered_samples(const std::string& stats_json) {
    return nlohmann::json::parse(read_text(stats_json))["samples"].get<std::uint64_t>();
}

}  // namespace wp::test
