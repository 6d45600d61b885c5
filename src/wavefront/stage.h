// The wavefront's stage kernels, in the order an iteration runs them.
#pragma once

#include <array>
#include <cstdint>

#include "interface/queues.h"

namespace wp {

enum class Stage { Generate, Intersect, ShadeDirect, IntersectShadow, Scatter };
inline constexpr std::array<const char*, 5> stage_kernel_names{"generate", "intersect", "shade_direct",
                                                               "intersect_shadow", "scatter"};

// The queues (kernels/interface/queues.h) each stage pushes to, as bits 1 << queue, as its kernel says.
inline constexpr std::array<std::uint32_t, 5> stage_output_queues{
    1u << WP_QUEUE_RAY,                                                    // generate: new camera rays
    1u << WP_QUEUE_HIT | 1u << WP_QUEUE_FREE,                              // intersect: hits; misses end
    1u << WP_QUEUE_SHADOW | 1u << WP_QUEUE_SCATTER | 1u << WP_QUEUE_FREE,  // shade_direct
    0u,                                                                    // intersect_shadow: adds radiance only
    1u << WP_QUEUE_RAY | 1u << WP_QUEUE_FREE,                              // scatter: continuing, ended
};

}  // namespace wp
