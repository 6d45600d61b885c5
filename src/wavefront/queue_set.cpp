#include "wavefront/queue_set.h"

#include <numeric>

namespace wp {

QueueSet::QueueSet(const cl::Context& context, cl::CommandQueue& queue, const cl::Program& program,
                   std::size_t capacity, Compaction compaction)
    : queue_(queue),
      capacity_(capacity),
      compaction_(compaction),
      // With scan compaction, the marks of every queue after the queues.
      queues_(context, CL_MEM_READ_WRITE, WP_QUEUE_COUNT * (compaction == Compaction::Scan ? 2 : 1) * queue_bytes()),
      counts_(context, CL_MEM_READ_WRITE, sizeof(std::uint32_t) * WP_COUNTS_PROFILED_SIZE) {
    std::vector<std::uint32_t> identity(capacity);
    std::iota(identity.begin(), identity.end(), 0u);
    identity_slots_ = cl::Buffer(context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, queue_bytes(), identity.data());
    queue_.enqueueFillBuffer(counts_, std::uint32_t(0), 0, counts_.getInfo<CL_MEM_SIZE>());
    if (compaction == Compaction::Scan) {
        scan_.emplace(context, program, queues_, counts_, capacity);
        queue_.enqueueFillBuffer(queues_, std::uint32_t(0), 0, queues_.getInfo<CL_MEM_SIZE>());
    }
}

void QueueSet::reset() {
    if (scan_)  // no marks left from the last pass
        queue_.enqueueFillBuffer(queues_, std::uint32_t(0), WP_QUEUE_COUNT * queue_bytes(),
                                 WP_QUEUE_COUNT * queue_bytes());
    queue_.enqueueCopyBuffer(identity_slots_, queues_, 0, WP_QUEUE_FREE * queue_bytes(), queue_bytes());
    DeviceCounts counts{};
    counts[WP_QUEUE_FREE] = static_cast<std::uint32_t>(capacity_);
    queue_.enqueueWriteBuffer(counts_, CL_TRUE, 0, sizeof counts, counts.data());
}

void QueueSet::set_issued(std::uint32_t issued) {
    issued_ = issued;
    queue_.enqueueWriteBuffer(counts_, CL_FALSE, WP_COUNTER_WORK * sizeof(std::uint32_t), sizeof issued_, &issued_);
}

void QueueSet::finish_stage(KernelLauncher& launcher, Stage stage) {
    if (!scan_) {
        if (stage == Stage::Generate) clear_counts(WP_QUEUE_FREE, 2);  // FREE consumed; HIT filled next
        if (stage == Stage::Intersect) clear_counts(WP_QUEUE_RAY, 3);  // RAY consumed; SHADOW, SCATTER filled next
        return;
    }
    auto bit = [](std::uint32_t queue) { return 1u << queue; };
    switch (stage) {
        case Stage::Generate:
            clear_marks(WP_QUEUE_FREE);
            scan_->compact(launcher, bit(WP_QUEUE_RAY));  // continuing paths and new camera rays
            break;
        case Stage::Intersect:
            clear_marks(WP_QUEUE_RAY);
            scan_->compact(launcher, bit(WP_QUEUE_HIT));
            break;
        case Stage::ShadeDirect:
            clear_marks(WP_QUEUE_HIT);
            scan_->compact(launcher, bit(WP_QUEUE_SHADOW) | bit(WP_QUEUE_SCATTER));
            break;
        case Stage::IntersectShadow:
            clear_marks(WP_QUEUE_SHADOW);
            break;
        case Stage::Scatter:
            clear_marks(WP_QUEUE_SCATTER);
            scan_->compact(launcher, bit(WP_QUEUE_FREE) | bit(WP_QUEUE_RAY));
            break;
    }
}

void QueueSet::empty_outputs(Stage stage) {
    for (std::uint32_t queue = 0; queue < WP_QUEUE_COUNT; ++queue) {
        if (!(stage_output_queues[static_cast<std::size_t>(stage)] & (1u << queue))) continue;
        clear_counts(queue, 1);
        if (scan_) clear_marks(queue);
    }
}

void QueueSet::compact_outputs(KernelLauncher& launcher, Stage stage) {
    if (scan_) scan_->compact(launcher, stage_output_queues[static_cast<std::size_t>(stage)]);
}

void QueueSet::clear_marks(std::uint32_t queue) {
    queue_.enqueueFillBuffer(queues_, std::uint32_t(0), WP_QUEUE_MARKS(queue) * queue_bytes(), queue_bytes());
}

void QueueSet::clear_counts(std::uint32_t first, std::uint32_t n) {
    queue_.enqueueFillBuffer(counts_, std::uint32_t(0), first * sizeof(std::uint32_t), n * sizeof(std::uint32_t));
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
