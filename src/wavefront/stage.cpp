#include "wavefront/stage.h"

namespace wp {

std::vector<Stage> iteration_stages(const FeatureSet& features, StageLoop loop) {
    std::vector<Stage> stages;
    for (std::size_t i = 0; i < kStageCount; ++i)
        if (stage_declarations[i].loop == loop && path_feature_compiled(stage_declarations[i].runs_when, features))
            stages.push_back(static_cast<Stage>(i));
    return stages;
}

}  // namespace wp
