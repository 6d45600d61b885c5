// The limits a mesh file's import runs under (docs/scene-format.md, "Mesh
// import limits"; the render flags --mesh-import-memory, --mesh-import-cpu
// and --mesh-import-time). The defaults fit meshes of a few tens of
// millions of triangles.
#pragma once

#include <cstdint>

namespace wp {

struct MeshImportLimits {
    // Address space the import may add to the helper's own at its start
    // (RLIMIT_AS): assimp's allocations, the file's contents, the answer.
    std::uint64_t memory_mib = 8192;
    // CPU time (RLIMIT_CPU), whole seconds.
    std::uint32_t cpu_s = 300;
    // Wall-clock time from the helper's start to its answer; wavepath then stops it.
    double wall_s = 600.0;
};

inline constexpr std::uint64_t kMaxImportMemoryMib = std::uint64_t{1} << 30;  // 1 PiB
inline constexpr std::uint32_t kMaxImportCpuS = 1000000;
inline constexpr double kMaxImportWallS = 1e6;

}  // namespace wp
