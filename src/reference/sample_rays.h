// Rays as the renderer traces them, for the tests and benchmarks of
// intersectors: camera rays (`samples` per pixel, jittered as samples 0,
// 1, ... are, a pixel's samples adjacent) and the incoherent rays of their
// first diffuse bounce (a cosine-distributed direction about the geometric
// normal, leaving from the offset origin).
#pragma once

#include <vector>

#include "reference/path_tracer.h"

namespace wp::reference {

struct SampleRays {
    std::vector<Ray<float>> camera, bounce;  // bounce: one per camera ray that hits
};

// A pixel's sample: its camera ray and, where that ray hits, the bounce.
inline void add_sample_rays(const ReferenceScene<float>& scene, int px, int py, std::uint32_t sample,
                            SampleRays& rays) {
    using M = SharedMath<float>;
    SampleRng<float> rng = sample_rng(scene, std::uint32_t(py * scene.camera.width + px), sample);
    Ray<float> ray = camera_ray(scene, px, py, rng);
    rays.camera.push_back(ray);
    ShapeHit<float> hit = closest_hit(scene, ray);
    if (!hit.found()) return;
    SurfacePoint<float> x = surface_at(scene, ray, hit);
    M::vec3 nf = glm::dot(ray.direction, x.normal) < 0.0f ? x.normal : -x.normal;
    M::CameraPair bounce = rng.pair(0, DIM_BSDF_U);
    M::vec3 local = M::sample_cosine_hemisphere(bounce.u, bounce.v);
    rays.bounce.push_back(
        {M::offset_ray_origin(x.point, nf, x.error), M::frame_to_world(M::frame_from_normal(nf), local)});
}

inline SampleRays sample_rays(const ReferenceScene<float>& scene, std::uint32_t samples = 1) {
    SampleRays rays;
    for (int py = 0; py < scene.camera.height; ++py)
        for (int px = 0; px < scene.camera.width; ++px)
            for (std::uint32_t sample = 0; sample < samples; ++sample) add_sample_rays(scene, px, py, sample, rays);
    return rays;
}

}  // namespace wp::reference
