#include "wavefront/stage.h"

#include <bit>
#include <sstream>
#include <string>

namespace wp {
namespace {

// Whether the space-separated list of stages names `stage` (whole names:
// "intersect" is not "intersect_shadow").
bool names_stage(const char* stages, const char* stage) {
    std::istringstream list(stages);
    for (std::string name; list >> name;)
        if (name == stage) return true;
    return false;
}

}  // namespace

std::vector<Stage> iteration_stages(const FeatureSet& features, StageLoop loop) {
    std::vector<Stage> stages;
    for (std::size_t i = 0; i < kStageCount; ++i)
        if (stage_declarations[i].loop == loop && path_feature_compiled(stage_declarations[i].runs_when, features))
            stages.push_back(static_cast<Stage>(i));
    return stages;
}

StageBytes stage_bytes_per_item(const StageDeclaration& stage, const FeatureSet& features) {
    constexpr std::size_t kQueueEntry = sizeof(std::uint32_t);  // a path slot (interface/queues.h)
    StageBytes bytes;
    for (const PathStateField& f : path_state_fields()) {
        if (!path_feature_compiled(f.feature, features)) continue;
        if (names_stage(f.readers, stage.kernel)) bytes.state_read += f.bytes;
        if (names_stage(f.writers, stage.kernel)) bytes.state_written += f.bytes;
    }
    bytes.queue_read = kQueueEntry;
    bytes.queue_written = kQueueEntry * std::size_t(std::popcount(stage.pushes));
    return bytes;
}

}  // namespace wp
