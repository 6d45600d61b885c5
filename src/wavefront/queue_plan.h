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
    // before their consumer runs, and that their consumer takes next, round
    // the loop of iterations. So a queue is built once it is complete, and
    // only where its entries are read.
    std::uint32_t built_after = 0;
    // Scan compaction, after the stage: the queues only counted, complete as
    // above but read only for their length (the scheduler's): those a stage
    // adds to again before their consumer takes them (RAY after shade or
    // intersect_and_shade: generate adds to it, and RAY is built after
    // generate) and those no stage of the iteration consumes (SHADOW where
    // shade traces the shadow rays itself). So every length is current when
    // the iteration ends.
    std::uint32_t counted_after = 0;
    // Scan compaction, after the stage: the queues whose marks that
    // compaction clears as it reads them, those it builds or counts for the
    // last time before their consumer takes them: no stage pushes to them in
    // between, round the loop of iterations (RAY's after generate, not after
    // shade or intersect_and_shade). A queue no stage of the iteration
    // consumes is cleared where counted. So clearing marks costs no command
    // of its own.
    std::uint32_t marks_cleared_after = 0;
};

// Indexed by Stage; a stage that is not in the iteration has nothing to do.
using QueuePlan = std::array<StageBookkeeping, kStageCount>;

// The bookkeeping of an iteration that runs `iteration`, in that order.
// `entries_read` (bits 1 << queue): queues whose entries something besides
// their consumer reads (--profile's rays by depth reads SHADOW's), built
// wherever they would be only counted.
QueuePlan plan_queues(const std::vector<Stage>& iteration, std::uint32_t entries_read = 0);
// The bookkeeping of loops of iterations that never run at once (the camera
// pass and SPPM's photon pass): each stage's is its loop's.
QueuePlan plan_queues(const std::vector<std::vector<Stage>>& loops, std::uint32_t entries_read = 0);

}  // namespace wp
