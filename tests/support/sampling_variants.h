// The render settings' sampling choices besides the default (NEE with
// multiple importance sampling, cosine hemisphere sampling and the Sobol'
// sampler): each is an
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
    Sampler sampler;
    const char* name;
};

inline constexpr SamplingVariant kSamplingVariants[] = {
    {false, false, Hemisphere::Cosine, Sampler::Sobol, "nee off"},
    {true, false, Hemisphere::Cosine, Sampler::Sobol, "mis off"},
    {true, true, Hemisphere::Uniform, Sampler::Sobol, "uniform hemisphere"},
    {true, false, Hemisphere::Uniform, Sampler::Sobol, "mis off, uniform hemisphere"},
    {false, false, Hemisphere::Uniform, Sampler::Sobol, "nee off, uniform hemisphere"},
    {true, true, Hemisphere::Cosine, Sampler::Independent, "independent sampler"},
};

inline Scene with_sampling(Scene scene, const SamplingVariant& variant) {
    scene.render.nee = variant.nee;
    scene.render.mis = variant.mis;
    scene.render.hemisphere = variant.hemisphere;
    scene.render.sampler = variant.sampler;
    return scene;
}

}  // namespace wp::test
