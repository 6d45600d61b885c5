#include "wavefront/compaction.h"

#include "interface/queues.h"
#include "opencl/kernel_arguments.h"

namespace wp {

std::string compaction_build_option(Compaction compaction) {
    return compaction == Compaction::Scan ? " -DWP_COMPACT_SCAN" : "";
}

LaneProgram wavefront_lanes(Compaction compaction, bool meshes) {
    return LaneProgram::wavefront(compaction == Compaction::Scan, meshes);
}

ScanCompaction::ScanCompaction(const cl::Context& context, const cl::Program& program, const cl::Buffer& queues,
                               const cl::Buffer& counts, std::size_t capacity)
    : blocks_(divide_rounding_up(capacity, WP_COMPACT_BLOCK)),
      block_counts_(context, CL_MEM_READ_WRITE, sizeof(std::uint32_t) * WP_QUEUE_COUNT * blocks_),
      count_(program, "compact_count"),
      scan_(program, "compact_scan"),
      write_(program, "compact_write") {
    count_.setArg(arg::CompactCount::queues, queues);
    count_.setArg(arg::CompactCount::capacity, cl_uint(capacity));
    count_.setArg(arg::CompactCount::block_counts, block_counts_);
    scan_.setArg(arg::CompactScan::capacity, cl_uint(capacity));
    scan_.setArg(arg::CompactScan::block_counts, block_counts_);
    scan_.setArg(arg::CompactScan::counts, counts);
    write_.setArg(arg::CompactWrite::queues, queues);
    write_.setArg(arg::CompactWrite::capacity, cl_uint(capacity));
    write_.setArg(arg::CompactWrite::block_counts, block_counts_);
}

void ScanCompaction::compact(KernelLauncher& launcher, const CompactionMasks& masks) {
    const std::uint32_t lengths = masks.built | masks.counted, counted_only = masks.counted & ~masks.built;
    count_.setArg(arg::CompactCount::queue_mask, cl_uint(lengths));
    count_.setArg(arg::CompactCount::clear_mask, cl_uint(masks.cleared & counted_only));  // compact_write skips them
    scan_.setArg(arg::CompactScan::queue_mask, cl_uint(lengths));
    write_.setArg(arg::CompactWrite::queue_mask, cl_uint(masks.built));
    write_.setArg(arg::CompactWrite::clear_mask, cl_uint(masks.cleared & masks.built));
    launcher.launch(count_, "compact_count", blocks_, 0);
    launcher.launch(scan_, "compact_scan", WP_QUEUE_COUNT, 0);
    if (masks.built) launcher.launch(write_, "compact_write", blocks_, 0);
}

}  // namespace wp
