// The reference's photons for SPPM (docs/architecture.md, "Photon mapping"):
// one photon at a time from a light chosen by power, as a plain loop over
// its path, with the shared formulas (shared/photons.h, shared/materials/)
// and the path tracer's intersection and surfaces. Every random number comes
// from photon_uniform(seed, iteration, photon, bounce, dimension), so a
// photon's path depends on nothing but those numbers, as the wavefront's
// photon stages draw them.
#pragma once

#include <cstdint>

#include "reference/path_tracer.h"

namespace wp::reference {

// The random numbers of one photon.
template <class Real>
struct PhotonRng {
    std::uint32_t seed, iteration, photon;
    Real operator()(std::uint32_t bounce, std::uint32_t dimension) const {
        return SharedMath<Real>::photon_uniform(seed, iteration, photon, bounce, dimension);
    }
};

// Where a photon leaves a light: a point uniform by area, with the light's
// area, the material that emits there and the magnitude its error comes
// from (offset.h).
template <class Real>
struct EmissionPoint {
    typename SharedMath<Real>::AreaPoint at;
    Real area;
    int material;
    Real magnitude;
};

template <class Real>
EmissionPoint<Real> emission_point(const ReferenceScene<Real>& scene,
                                   const typename ReferenceScene<Real>::LightRef& light, const PhotonRng<Real>& rng) {
    using M = SharedMath<Real>;
    const Real u = rng(0, DIM_PHOTON_POINT_U), v = rng(0, DIM_PHOTON_POINT_V);
    switch (light.shape) {
        case ShapeType::Sphere: {
            const auto& s = scene.spheres[light.index];
            return {M::sphere_point(s.center, s.radius, u, v), M::sphere_area(s.radius), s.material,
                    M::sphere_magnitude(s.center, s.radius)};
        }
        case ShapeType::Mesh: {
            std::uint32_t k =
                light.first_triangle + M::select_light(&scene.light_triangle_cdf[light.first_triangle],
                                                       light.triangle_count, rng(0, DIM_PHOTON_LIGHT_TRIANGLE));
            const auto& t = scene.light_triangles[k];
            Vec3<Real> p0 = M::triangle_vertex(t.p0), p1 = M::triangle_vertex(t.p1), p2 = M::triangle_vertex(t.p2);
            return {M::triangle_point(p0, p1, p2, u, v), light.area, static_cast<int>(t.material),
                    M::triangle_magnitude(p0, p1, p2)};
        }
        default: {
            const auto& q = scene.quads[light.index];
            return {M::quad_point(q.corner, q.edge1, q.edge2, u, v), M::quad_area(q.edge1, q.edge2), q.material,
                    M::quad_magnitude(q.corner, q.edge1, q.edge2)};
        }
    }
}

// The photon of `rng` leaving a light chosen by power (the scene has one).
template <class Real>
typename SharedMath<Real>::EmittedPhoton emit_photon(const ReferenceScene<Real>& scene, const PhotonRng<Real>& rng) {
    using M = SharedMath<Real>;
    auto light_count = static_cast<std::uint32_t>(scene.lights.size());
    std::uint32_t index = M::select_light(scene.light_cdf.data(), light_count, rng(0, DIM_PHOTON_LIGHT_SELECT));
    EmissionPoint<Real> e = emission_point(scene, scene.lights[index], rng);
    const auto& emitter = scene.materials[e.material];
    return M::emit_photon(e.at, M::shape_point_error(e.magnitude), e.area,
                          M::light_selection_pmf(scene.light_cdf.data(), index), emitter.emission, emitter.two_sided,
                          rng(0, DIM_PHOTON_SIDE), rng(0, DIM_PHOTON_DIRECTION_U), rng(0, DIM_PHOTON_DIRECTION_V));
}

// Traces the photon of `rng` and calls deposit(point, direction, power,
// depth) at every non-specular surface it meets, `depth` being the scattering
// events before it (the visible points decide what counts: photon_depth_counts).
// It scatters through the shared materials with WP_TRANSPORT_IMPORTANCE and
// the adjoint correction (photon_bsdf_sample), and plays Russian roulette
// on its throughput as camera paths do.
template <class Real, class Deposit>
void trace_photon(const ReferenceScene<Real>& scene, const PhotonRng<Real>& rng, const Deposit& deposit,
                  RayCounts& counts) {
    using M = SharedMath<Real>;
    using vec3 = typename M::vec3;
    const typename M::EmittedPhoton photon = emit_photon(scene, rng);
    ++counts.photons;
    Ray<Real> ray{photon.origin, photon.direction};
    vec3 throughput(Real(1));
    for (std::uint32_t depth = 0;;) {
        ++counts.photon_rays;
        ShapeHit<Real> hit = closest_hit(scene, ray);
        if (!hit.found()) break;
        SurfacePoint<Real> surface = surface_at(scene, ray, hit);
        const auto material = material_at(scene, surface);
        if (material.type == MaterialType::Emitter) break;  // reflects nothing
        if (is_non_specular(material.type)) deposit(surface.point, ray.direction, photon.flux * throughput, depth);
        if (!M::photon_may_scatter(depth, static_cast<std::uint32_t>(scene.render.max_depth))) break;

        typename M::FacingNormals facing = M::normals_facing(ray.direction, surface.normal, surface.shading);
        const typename M::BsdfRandom random{rng(depth, DIM_PHOTON_BSDF_LOBE), rng(depth, DIM_PHOTON_BSDF_U),
                                            rng(depth, DIM_PHOTON_BSDF_V)};
        typename M::BsdfSample next =
            M::photon_bsdf_sample(scatter(scene, material, ray.direction, facing.front, facing.nf, facing.ns, random,
                                          WP_TRANSPORT_IMPORTANCE),
                                  -ray.direction, facing.nf, facing.ns, scene.shading_normals);
        if (!next.valid) break;
        throughput *= next.weight;
        ray = {M::offset_ray_origin(surface.point, next.leave_side, surface.error), next.direction};

        const std::uint32_t bounce = depth++;
        typename M::RouletteOutcome roulette = M::russian_roulette(
            throughput, Real(1), depth >= std::uint32_t(scene.render.rr_depth), rng(bounce, DIM_PHOTON_ROULETTE));
        if (!roulette.survives) break;
        throughput = roulette.throughput;
        if (!M::vec3_is_finite(throughput)) {
            ++counts.nonfinite[static_cast<std::size_t>(NonfiniteStage::scatter)];
            break;
        }
    }
}

}  // namespace wp::reference
