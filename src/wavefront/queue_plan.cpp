#include "wavefront/queue_plan.h"

#include <algorithm>

namespace wp {
namespace {

bool pushes_to(Stage stage, std::uint32_t queue) { return declaration(stage).pushes >> queue & 1u; }

StageBookkeeping& of(QueuePlan& plan, Stage stage) { return plan[static_cast<std::size_t>(stage)]; }

// The position in `iteration` after the stage that consumes `queue`, or 0
// when no stage of the iteration consumes it.
std::size_t after_consumer(const std::vector<Stage>& iteration, std::uint32_t queue) {
    auto consumer = std::find_if(iteration.begin(), iteration.end(),
                                 [&](Stage stage) { return declaration(stage).consumes == queue; });
    return consumer == iteration.end() ? 0 : std::size_t(consumer - iteration.begin()) + 1;
}

// Whether, walking `steps` stages on from position `at` (round the loop of
// iterations), `queue`'s consumer comes before any stage that pushes to it,
// or neither comes.
bool consumer_comes_first(const std::vector<Stage>& iteration, std::size_t at, std::uint32_t queue, std::size_t steps) {
    for (std::size_t step = 1; step <= steps; ++step) {
        Stage later = iteration[(at + step) % iteration.size()];
        if (declaration(later).consumes == queue) return true;
        if (pushes_to(later, queue)) return false;
    }
    return true;
}

// Whether no later stage of the iteration pushes to `queue` before its consumer runs.
bool complete_after(const std::vector<Stage>& iteration, std::size_t at, std::uint32_t queue) {
    return consumer_comes_first(iteration, at, queue, iteration.size() - 1 - at);
}

// Whether the queue built or counted after position `at` is so for the last
// time before its consumer: round the loop, no stage pushes to it first.
bool last_compaction_before_consumer(const std::vector<Stage>& iteration, std::size_t at, std::uint32_t queue) {
    return consumer_comes_first(iteration, at, queue, iteration.size() - 1);
}

}  // namespace

QueuePlan plan_queues(const std::vector<Stage>& iteration, std::uint32_t entries_read) {
    QueuePlan plan{};
    const std::size_t n = iteration.size();
    for (std::uint32_t queue = 0; queue < WP_QUEUE_COUNT; ++queue) {
        // From the consumer on, round the loop of iterations (for atomic
        // compaction, under which no stage pushes to the queue it consumes,
        // wavefront/stage.h).
        for (std::size_t step = 0, start = after_consumer(iteration, queue); step < n; ++step) {
            Stage stage = iteration[(start + step) % n];
            if (pushes_to(stage, queue)) {
                of(plan, stage).counts_cleared_before |= 1u << queue;
                break;
            }
        }
    }
    for (std::size_t at = 0; at < n; ++at) {
        StageBookkeeping& stage = of(plan, iteration[at]);
        for (std::uint32_t queue = 0; queue < WP_QUEUE_COUNT; ++queue) {
            if (!pushes_to(iteration[at], queue) || !complete_after(iteration, at, queue)) continue;
            const bool last = last_compaction_before_consumer(iteration, at, queue);
            const bool consumed = after_consumer(iteration, queue) != 0;
            const bool read = (last && consumed) || (entries_read >> queue & 1u);
            (read ? stage.built_after : stage.counted_after) |= 1u << queue;
            if (last) stage.marks_cleared_after |= 1u << queue;
        }
    }
    return plan;
}

QueuePlan plan_queues(const std::vector<std::vector<Stage>>& loops, std::uint32_t entries_read) {
    QueuePlan plan{};
    for (const std::vector<Stage>& loop : loops) {
        const QueuePlan of_loop = plan_queues(loop, entries_read);
        for (Stage stage : loop) plan[static_cast<std::size_t>(stage)] = of_loop[static_cast<std::size_t>(stage)];
    }
    return plan;
}

}  // namespace wp
