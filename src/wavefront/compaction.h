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

// The stage kernels' program as resolve_lanes sees it (opencl/lanes.h).
LaneProgram wavefront_lanes(Compaction compaction);

// The three kernels of kernels/compact.cl over one queues buffer: each queue
// selected by a mask is rebuilt from its marks, in ascending slot order.
class ScanCompaction {
 public:
    ScanCompaction(const cl::Context& context, const cl::Program& program, const cl::Buffer& queues,
                   const cl::Buffer& counts, std::size_t capacity);
    // Rebuilds queue q (and sets its length) for every bit q of queue_mask,
    // and clears its marks where clear_mask has bit q too.
    void compact(KernelLauncher& launcher, std::uint32_t queue_mask, std::uint32_t clear_mask = 0);

 private:
    std::size_t blocks_;
    cl::Buffer block_counts_;
    cl::Kernel count_, scan_, write_;
};

}  // namespace wp
