#include "wavefront/queue_set.h"

#include <numeric>

namespace wp {

QueueSet::QueueSet(const cl::Context& context, cl::CommandQueue& queue, const cl::Program& program,
                   std::size_t capacity, Compaction compaction, const QueuePlan& plan, bool host_mapped)
    : queue_(queue),
      capacity_(capacity),
      compaction_(compaction),
      // With scan compaction, the marks of every queue after the queues.
      queues_(context, CL_MEM_READ_WRITE | (host_mapped ? CL_MEM_ALLOC_HOST_PTR : 0),
              WP_QUEUE_COUNT * (compaction == Compaction::Scan ? 2 : 1) * queue_bytes()),
      counts_(context, CL_MEM_READ_WRITE | (host_mapped ? CL_MEM_ALLOC_HOST_PTR : 0),
              sizeof(std::uint32_t) * WP_COUNTS_PROFILED_SIZE),
      plan_(plan) {
    std::vector<std::uint32_t> identity(capacity);
    std::iota(identity.begin(), identity.end(), 0u);
    identity_slots_ = cl::Buffer(context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, queue_bytes(), identity.data());
    queue_.enqueueFillBuffer(counts_, std::uint32_t(0), 0, counts_.getInfo<CL_MEM_SIZE>());
    if (compaction == Compaction::Scan) {
        scan_.emplace(context, program, queues_, counts_, capacity);
        queue_.enqueueFillBuffer(queues_, std::uint32_t(0), 0, queues_.getInfo<CL_MEM_SIZE>());
    }
}

void QueueSet::reset(std::uint32_t free_queue) {
    if (scan_)  // no marks left from the last pass
        queue_.enqueueFillBuffer(queues_, std::uint32_t(0), WP_QUEUE_COUNT * queue_bytes(),
                                 WP_QUEUE_COUNT * queue_bytes());
    queue_.enqueueCopyBuffer(identity_slots_, queues_, 0, free_queue * queue_bytes(), queue_bytes());
    DeviceCounts counts{};
    counts[free_queue] = static_cast<std::uint32_t>(capacity_);
    queue_.enqueueWriteBuffer(counts_, CL_TRUE, 0, sizeof counts, counts.data());
}

void QueueSet::set_issued(std::uint32_t issued) {
    issued_ = issued;
    queue_.enqueueWriteBuffer(counts_, CL_FALSE, WP_COUNTER_WORK * sizeof(std::uint32_t), sizeof issued_, &issued_);
}

void QueueSet::start_stage(Stage stage) {
    if (!scan_) clear_counts(plan_[static_cast<std::size_t>(stage)].counts_cleared_before);
}

void QueueSet::finish_stage(KernelLauncher& launcher, Stage stage) {
    if (!scan_) return;
    const StageBookkeeping& plan = plan_[static_cast<std::size_t>(stage)];
    if (plan.built_after | plan.counted_after)
        scan_->compact(launcher, {plan.built_after, plan.counted_after, plan.marks_cleared_after});
}

void QueueSet::empty_outputs(Stage stage) {
    const std::uint32_t pushes = declaration(stage).pushes;
    clear_counts(pushes & ~(1u << declaration(stage).consumes));
    for (std::uint32_t queue = 0; scan_ && queue < WP_QUEUE_COUNT; ++queue)
        if (pushes >> queue & 1u) clear_marks(queue);
}

void QueueSet::compact_outputs(KernelLauncher& launcher, Stage stage) {
    if (scan_) scan_->compact(launcher, {.built = declaration(stage).pushes});
}

void QueueSet::clear_marks(std::uint32_t queue) {
    queue_.enqueueFillBuffer(queues_, std::uint32_t(0), WP_QUEUE_MARKS(queue) * queue_bytes(), queue_bytes());
}

void QueueSet::clear_counts(std::uint32_t queue_mask) {
    for (std::uint32_t queue = 0; queue < WP_QUEUE_COUNT; ++queue)
        if (queue_mask >> queue & 1u)
            queue_.enqueueFillBuffer(counts_, std::uint32_t(0), queue * sizeof(std::uint32_t), sizeof(std::uint32_t));
}

DeviceCounts QueueSet::read_counts() {
    DeviceCounts counts;
    queue_.enqueueReadBuffer(counts_, CL_TRUE, 0, sizeof counts, counts.data());
    return counts;
}

void QueueSet::set_queue(std::uint32_t queue, const std::vector<std::uint32_t>& slots) {
    if (!slots.empty())
        queue_.enqueueWriteBuffer(queues_, CL_TRUE, queue * queue_bytes(), slots.size() * sizeof(std::uint32_t),
                                  slots.data());
    std::uint32_t length = static_cast<std::uint32_t>(slots.size());
    queue_.enqueueWriteBuffer(counts_, CL_TRUE, queue * sizeof(std::uint32_t), sizeof length, &length);
}

std::vector<std::uint32_t> QueueSet::read_queue(std::uint32_t queue) {
    std::vector<std::uint32_t> slots(read_counts()[queue]);
    if (!slots.empty())
        queue_.enqueueReadBuffer(queues_, CL_TRUE, queue * queue_bytes(), slots.size() * sizeof(std::uint32_t),
                                 slots.data());
    return slots;
}

}  // namespace wp
