// What the C++ benchmarks share: their statistics, what every result is
// recorded with, and the bunny's subdivision (the meshes above its size).
#pragma once

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <glm/vec3.hpp>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>
#include <unordered_map>
#include <vector>

#include "scene/scene.h"

namespace wp::bench {

using Clock = std::chrono::steady_clock;

inline double seconds_since(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

inline double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    std::size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}
inline double minimum(const std::vector<double>& v) { return *std::min_element(v.begin(), v.end()); }

inline std::string command_output(const std::string& command) {
    std::string out;
    if (FILE* pipe = ::popen(command.c_str(), "r")) {
        char buffer[256];
        while (std::fgets(buffer, sizeof buffer, pipe)) out += buffer;
        ::pclose(pipe);
    }
    while (!out.empty() && (out.back() == '\n' || out.back() == ' ')) out.pop_back();
    return out;
}

// Commit, date and machine: recorded with every result.
inline nlohmann::json machine_metadata() {
    std::string git = "git -C '" WAVEPATH_SOURCE_DIR "' ";
    std::string commit = command_output(git + "rev-parse --short=12 HEAD 2>/dev/null");
    if (commit.empty()) commit = "unknown";
    if (!command_output(git + "status --porcelain --untracked-files=no 2>/dev/null").empty()) commit += "+dirty";
    std::time_t now = std::time(nullptr);
    char date[32];
    std::strftime(date, sizeof date, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&now));
    std::string cpu = "unknown";
    std::ifstream cpuinfo("/proc/cpuinfo");
    for (std::string line; std::getline(cpuinfo, line);) {
        if (line.rfind("model name", 0) == 0) {
            cpu = line.substr(line.find(':') + 2);
            break;
        }
    }
    return {{"commit", commit}, {"date", date}, {"cpu", cpu}, {"cores", std::thread::hardware_concurrency()}};
}

// 1->4 midpoint subdivision; shared edges share their midpoint, so a closed
// mesh stays closed. Face normals only, as the bunny has.
inline Mesh subdivide(const Mesh& mesh) {
    Mesh out;
    out.file = mesh.file;
    out.material = mesh.material;
    out.positions = mesh.positions;
    std::unordered_map<std::uint64_t, std::uint32_t> midpoints;
    auto midpoint = [&](std::uint32_t a, std::uint32_t b) {
        std::uint64_t key = std::uint64_t(std::min(a, b)) << 32 | std::max(a, b);
        auto [it, added] = midpoints.try_emplace(key, std::uint32_t(out.positions.size()));
        if (added) out.positions.push_back(0.5 * (mesh.positions[a] + mesh.positions[b]));
        return it->second;
    };
    out.triangles.reserve(4 * mesh.triangles.size());
    for (const glm::uvec3& t : mesh.triangles) {
        std::uint32_t ab = midpoint(t.x, t.y), bc = midpoint(t.y, t.z), ca = midpoint(t.z, t.x);
        out.triangles.insert(out.triangles.end(), {{t.x, ab, ca}, {ab, t.y, bc}, {ca, bc, t.z}, {ab, bc, ca}});
    }
    return out;
}

}  // namespace wp::bench
