// The queue bookkeeping around each stage of an iteration, derived from the
// stages' declared queues (wavefront/stage.h), so that adding a stage or a
// push changes it without an edit here. QueueSet (wavefront/queue_set.h)
// carries it out.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "wavefront/stage.h"

namespace wp {

struct StageBookkeeping {
    // Atomic pushes, before the stage: the queues whose lengths go to 0, those
    // this stage is the first to push to after their consumer took them. No
    // earlier, so that when the iteration ends each length is what the
    // iteration pushed (the scheduler reads them).
    std::uint32_t counts_cleared_before = 0;
    // Scan compaction, after the stage: the queues built from their marks,
    // those it pushes to that no later stage of the iteration pushes to
    // before their consumer runs. So a queue is built once it is complete,
    // and every length is current when the iteration ends.
    std::uint32_t compacted_after = 0;
    // Scan compaction, after the stage: the queues whose marks that
    // compaction clears as it reads them, those it builds for the last time
    // before their consumer takes them: no stage pushes to them in between,
    // round the loop of iterations (RAY is built after shade or
    // intersect_and_shade, for the iteration's count, and again after
    // generate, which clears it). A queue
    // no stage of the iteration consumes (SHADOW where shade traces the
    // shadow rays itself: built only to be counted) is cleared where built.
    // So clearing marks costs no command of its own.
    std::uint32_t marks_cleared_after = 0;
};

// Indexed by Stage; a stage that is not in the iteration has nothing to do.
using QueuePlan = std::array<StageBookkeeping, kStageCount>;

// The bookkeeping of an iteration that runs `iteration`, in that order.
QueuePlan plan_queues(const std::vector<Stage>& iteration);
// The bookkeeping of loops of iterations that never run at once (the camera
// pass and SPPM's photon pass): each stage's is its loop's.
QueuePlan plan_queues(const std::vector<std::vector<Stage>>& loops);

}  // namespace wp
