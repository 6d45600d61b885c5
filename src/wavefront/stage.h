// The wavefront's stages, from their declaration (kernels/interface/stages.h):
// the Stage enum and each stage's kernel and queues, in the order an
// iteration runs them.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "interface/queues.h"
#include "interface/stages.h"
#include "scene/scene.h"
#include "wavefront/path_state.h"

namespace wp {

#define WP_STAGE_ENUMERATOR(stage, loop, consumes, pushes, runs_when, traces) stage,
enum class Stage { WP_STAGES(WP_STAGE_ENUMERATOR) };
#undef WP_STAGE_ENUMERATOR

// The loops of iterations (kernels/interface/stages.h): the camera paths', and
// SPPM's photon pass, which runs once the camera pass of its iteration drained.
enum class StageLoop { CAMERA, PHOTON };

// The rays a stage traces, those of the paths it consumes (what the host
// traces before the stage's kernel with --intersector embree, wavefront/host_trace.h).
enum class StageTrace { NO_RAYS, CLOSEST_HIT, ANY_HIT };

struct StageDeclaration {
    const char* kernel;      // defined in kernels/<kernel>.cl
    StageLoop loop;          // the loop it belongs to
    std::uint32_t consumes;  // the queue it takes its paths from
    std::uint32_t pushes;    // the queues it may push to, as bits 1 << queue
    PathFeature runs_when;   // the path state feature it needs (ALWAYS, NEE, SPPM)
    StageTrace traces;
};

#define WP_STAGE_DECLARATION(stage, loop, consumes, pushes, runs_when, traces) \
    StageDeclaration{#stage, StageLoop::loop, WP_QUEUE_##consumes, pushes, PathFeature::runs_when, StageTrace::traces},
inline constexpr std::array stage_declarations{WP_STAGES(WP_STAGE_DECLARATION)};
#undef WP_STAGE_DECLARATION

inline constexpr std::size_t kStageCount = stage_declarations.size();

// What the host's queue bookkeeping (wavefront/queue_plan.h) relies on: one
// consumer per queue in a program (two stages may consume one queue where
// they are never compiled together), and no stage pushing to the queue it
// is reading but intersect_and_shade, which runs only with scan compaction
// (its kernel does not compile otherwise, and the wavefront never asks for
// it then): compaction builds the queue again after the stage, from marks
// the stage does not read.
constexpr bool never_in_one_program(PathFeature a, PathFeature b) {
    return (a == PathFeature::HIT_STAGE && b == PathFeature::INTERSECT_AND_SHADE) ||
           (a == PathFeature::INTERSECT_AND_SHADE && b == PathFeature::HIT_STAGE);
}
constexpr bool every_queue_has_at_most_one_consumer() {
    for (std::size_t a = 0; a < kStageCount; ++a)
        for (std::size_t b = a + 1; b < kStageCount; ++b)
            if (stage_declarations[a].consumes == stage_declarations[b].consumes &&
                !never_in_one_program(stage_declarations[a].runs_when, stage_declarations[b].runs_when))
                return false;
    return true;
}
constexpr bool only_scan_compacted_stages_push_to_the_queue_they_consume() {
    for (const auto& stage : stage_declarations)
        if (stage.pushes >> stage.consumes & 1u && stage.runs_when != PathFeature::INTERSECT_AND_SHADE) return false;
    return true;
}
static_assert(every_queue_has_at_most_one_consumer(), "kernels/interface/stages.h: two stages consume one queue");
static_assert(only_scan_compacted_stages_push_to_the_queue_they_consume(),
              "kernels/interface/stages.h: a stage pushes to the queue it consumes");

inline constexpr const StageDeclaration& declaration(Stage stage) {
    return stage_declarations[static_cast<std::size_t>(stage)];
}

// The stages an iteration of `loop` runs with kernels built for `features`, in order.
std::vector<Stage> iteration_stages(const FeatureSet& features, StageLoop loop = StageLoop::CAMERA);

// The bytes a stage moves per item (per queue entry it takes), from the
// declarations alone: the path state fields (kernels/interface/path_state.h)
// whose buffers exist for `features` and that name the stage among their
// readers or writers, its queue entry, and one entry for each queue it may
// push to. An upper bound: a field read or written under a condition, or
// only in some compilations, counts fully, and so does every push target,
// though a path takes some of them only instead of others. Scene data,
// pass radiance and SPPM's per-pixel state are not counted.
struct StageBytes {
    std::size_t state_read = 0;
    std::size_t state_written = 0;
    std::size_t queue_read = 0;     // the entry the stage takes
    std::size_t queue_written = 0;  // an entry per push target
    std::size_t total() const { return state_read + state_written + queue_read + queue_written; }
};
StageBytes stage_bytes_per_item(const StageDeclaration& stage, const FeatureSet& features);

}  // namespace wp
