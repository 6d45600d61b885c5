// What a film's sums depend on besides its range of work items, so that a
// checkpoint or a partial film is only ever continued or merged by a render
// that would have produced the same bits: the scene's content, the settings
// that change the estimator, and the estimator's arithmetic.
#pragma once

#include <cstdint>
#include <string>

#include "longrun/adaptive.h"
#include "scene/scene.h"

namespace wp {

struct RenderIdentity {
    // FNV-1a 64 of the camera (view and resolution), background, materials,
    // shapes and mesh triangles as loaded (not of the file's text: formatting
    // and key order do not matter, but any number that changes the image does).
    std::uint64_t scene = 0;
    // FNV-1a 64 of max_depth, rr_depth, seed, nee, mis, hemisphere and sampler, with
    // adaptive sampling its threshold and minimum samples, and with the sppm
    // integrator its photons per iteration, initial radius and alpha. Not spp: a
    // film's sums over its first N work items are the same for any spp, so a
    // render can be continued to more samples than first asked for.
    std::uint64_t settings = 0;
    // "opencl" (wavefront and megakernel tracing with the OpenCL BVH, whose
    // images are bit-identical), "reference-float" or "reference-double";
    // "opencl-embree" and "reference-embree" (float) where the wavefront or
    // the reference traces with Embree (near ties go otherwise: a few bits
    // differ). At most 16 characters (the film file's field).
    std::string estimator;

    bool operator==(const RenderIdentity&) const = default;
};

// `estimator` as above.
RenderIdentity render_identity(const Scene& scene, const std::string& estimator, const AdaptiveSampling& adaptive = {});

// FNV-1a 64 of `size` bytes, continuing from `hash` (start: kFnvOffset).
inline constexpr std::uint64_t kFnvOffset = 0xcbf29ce484222325ull;
std::uint64_t fnv1a64(const void* data, std::size_t size, std::uint64_t hash = kFnvOffset);

}  // namespace wp
