// The kernels' code for a material's microfacet distribution
// (kernels/shared/materials/microfacet.h), written once for every backend.
#pragma once

#include <cstdint>

#include "core/shared_math.h"
#include "scene/scene.h"

namespace wp {

// WP_MICROFACET_NONE for a material without microfacets: no lane of its asks
// for either distribution's work.
inline std::uint32_t microfacet_code(const Material& m) {
    if (!m.rough()) return WP_MICROFACET_NONE;
    return m.distribution == Microfacet::GGX ? WP_MICROFACET_GGX : WP_MICROFACET_BECKMANN;
}

}  // namespace wp
