// The render settings' sampling choices besides the default (NEE with
// cosine hemisphere sampling): each is an unbiased estimator of the same
// image, so tests run them against the same expected values.
#pragma once

#include <string>

#include "scene/scene.h"

namespace wp::test {

struct SamplingVariant {
    bool nee;
    Hemisphere hemisphere;
    const char* name;
};

inline constexpr SamplingVariant kSamplingVariants[] = {
    {false, Hemisphere::Cosine, "nee off"},
    {true, Hemisphere::Uniform, "uniform hemisphere"},
    {false, Hemisphere::Uniform, "nee off, uniform hemisphere"},
};

inline Scene with_sampling(Scene scene, const SamplingVariant& variant) {
    scene.render.nee = variant.nee;
    scene.render.hemisphere = variant.hemisphere;
    return scene;
}

}  // namespace wp::test
