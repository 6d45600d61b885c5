// How the stage kernels fill the queues of the stages after them, decided
// once here: the default, the lanes it allows, and the prefix-sum kernels.
#pragma once

#include <CL/opencl.hpp>
#include <cstdint>
#include <string>

#include "opencl/lanes.h"
#include "opencl/launcher.h"

namespace wp {

enum class Compaction {
    Atomic,  // a push through a global atomic counter, aggregated per work group (queue order not stable)
    Scan,    // marks per slot, then a prefix sum over them (kernels/compact.cl): ascending slot order
};
// Scan: the stages then read the path state in memory order, without atomics
// or barriers, and may run several lanes; measured faster than atomic pushes on
// PoCL (bench/results/defaults.md).
inline constexpr Compaction kDefaultCompaction = Compaction::Scan;

// " -DWP_COMPACT_SCAN" for scan compaction, "" for atomic.
std::string compaction_build_option(Compaction compaction);

// The stage kernels' program as resolve_lanes sees it (opencl/lanes.h), for a scene with or without meshes.
LaneProgram wavefront_lanes(Compaction compaction, bool meshes);

// What one compaction does to each queue, as bits 1 << queue.
struct CompactionMasks {
    std::uint32_t built = 0;    // rebuilt from its marks, in ascending slot order, and its length set
    std::uint32_t counted = 0;  // only its length set
    std::uint32_t cleared = 0;  // of those, the marks cleared once read
};

// The three kernels of kernels/compact.cl over one queues buffer.
class ScanCompaction {
 public:
    ScanCompaction(const cl::Context& context, const cl::Program& program, const cl::Buffer& queues,
                   const cl::Buffer& counts, std::size_t capacity);
    void compact(KernelLauncher& launcher, const CompactionMasks& masks);

 private:
    std::size_t blocks_;
    cl::Buffer block_counts_;
    cl::Kernel count_, scan_, write_;
};

}  // namespace wp
