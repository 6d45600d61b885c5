#include "wavefront/stage.h"

namespace wp {

std::vector<Stage> iteration_stages(const FeatureSet& features) {
    std::vector<Stage> stages;
    for (std::size_t i = 0; i < kStageCount; ++i)
        if (path_feature_compiled(stage_declarations[i].runs_when, features)) stages.push_back(static_cast<Stage>(i));
    return stages;
}

}  // namespace wp
