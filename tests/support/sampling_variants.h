// The render settings' sampling choices besides the default (NEE with
// multiple importance sampling and cosine hemisphere sampling): each is an
// unbiased estimator of the same image, so tests run them against the same
// expected values.
#pragma once

#include <string>

#include "scene/scene.h"

namespace wp::test {

struct SamplingVariant {
    bool nee;
    bool mis;
    Hemisphere hemisphere;
    const char* name;
};

inline constexpr SamplingVariant kSamplingVariants[] = {
    {false, false, Hemisphere::Cosine, "nee off"},
    {true, false, Hemisphere::Cosine, "mis off"},
    {true, true, Hemisphere::Uniform, "uniform hemisphere"},
    {true, false, Hemisphere::Uniform, "mis off, uniform hemisphere"},
    {false, false, Hemisphere::Uniform, "nee off, uniform hemisphere"},
};

inline Scene with_sampling(Scene scene, const SamplingVariant& variant) {
    scene.render.nee = variant.nee;
    scene.render.mis = variant.mis;
    scene.render.hemisphere = variant.hemisphere;
    return scene;
}

}  // namespace wp::test
