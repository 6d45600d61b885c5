// The wavefront's queues of path slots and its counters on the device
// (kernels/interface/queues.h), and the bookkeeping between stages that the
// compaction asks for.
#pragma once

#include <CL/opencl.hpp>
#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include "interface/queues.h"
#include "opencl/launcher.h"
#include "wavefront/compaction.h"
#include "wavefront/queue_plan.h"
#include "wavefront/stage.h"

namespace wp {

// Queue lengths then counters, as in kernels/interface/queues.h.
using DeviceCounts = std::array<std::uint32_t, WP_COUNTS_SIZE>;

class QueueSet {
 public:
    // `program` holds kernels/compact.cl (used with scan compaction); `plan`
    // is the bookkeeping of the iterations the stages run in (plan_queues);
    // `host_mapped`: the host maps the queues and counts
    // (wavefront/host_trace.h), so they are allocated for it to reach
    // without a copy.
    QueueSet(const cl::Context& context, cl::CommandQueue& queue, const cl::Program& program, std::size_t capacity,
             Compaction compaction, const QueuePlan& plan, bool host_mapped = false);

    const cl::Buffer& queues() const { return queues_; }
    const cl::Buffer& counts() const { return counts_; }

    // Every slot in `free_queue` (FREE, or PHOTON_FREE for SPPM's photon
    // pass), every other queue empty, no marks, the counters at 0.
    void reset(std::uint32_t free_queue = WP_QUEUE_FREE);
    // Tells the next generate how many work items of the pass earlier ones handed out.
    void set_issued(std::uint32_t issued);
    // The bookkeeping around a stage of the iteration (wavefront/queue_plan.h).
    // Before it, atomic: empties the queues it is the first to refill. After
    // it, scan: builds or counts the queues it completed, clearing the marks
    // of those built or counted for the last time before their consumer.
    void start_stage(Stage stage);
    void finish_stage(KernelLauncher& launcher, Stage stage);
    // Waits for the queue and reads the lengths and counters.
    DeviceCounts read_counts();

    // For stage tests: running one stage alone, empty the queues it fills
    // before (the one it also takes, intersect_and_shade's RAY, keeps its
    // length: only its marks are cleared), and make them readable after.
    void empty_outputs(Stage stage);
    void compact_outputs(KernelLauncher& launcher, Stage stage);
    // For stage tests: set a queue's slots and length, read a queue.
    void set_queue(std::uint32_t queue, const std::vector<std::uint32_t>& slots);
    std::vector<std::uint32_t> read_queue(std::uint32_t queue);

 private:
    cl::CommandQueue& queue_;
    std::size_t capacity_;
    Compaction compaction_;
    cl::Buffer queues_, counts_, identity_slots_;
    std::optional<ScanCompaction> scan_;
    QueuePlan plan_;
    std::uint32_t issued_ = 0;  // host copy of the last set_issued value, read by the queue

    void clear_counts(std::uint32_t queue_mask);
    void clear_marks(std::uint32_t queue);
    std::size_t queue_bytes() const { return capacity_ * sizeof(std::uint32_t); }
};

}  // namespace wp
