// The reference path tracer: the estimator of docs/architecture.md ("Conventions"), one camera sample
// at a time, as a plain loop over the path in scalar code over ReferenceScene<Real>. Every formula
// at a vertex is the shared code's (kernels/shared: materials/, lights.h, estimator.h,
// direct_light.h, camera.h), which the kernels call too; this file reaches the scene's data and
// decides the path's course. Every random number comes from camera_uniform(seed, pixel, sample,
// bounce, dimension), so a sample's path depends on nothing but those five numbers.
//
// Choices the wavefront kernels must repeat to retrace these paths exactly:
//  - shapes are tested spheres, then planes, then quads, each in scene order,
//    and a later shape replaces the closest hit only when strictly closer;
//  - a hit's point, geometric normal and error bound are those of
//    shared/hit_point.h (a sphere hit moved back onto the sphere, a triangle
//    hit interpolated from its barycentric coordinates), and spawned rays
//    leave from offset_ray_origin(x, side, error);
#pragma once

#include <cstdint>
#include <glm/geometric.hpp>
#include <glm/vec3.hpp>
#include <type_traits>

#include "core/render.h"
#include "reference/reference_scene.h"

namespace wp::reference {

// What the paths of one thread traced and dropped.
struct RayCounts {
    std::uint64_t extension = 0;  // camera and bounce rays
    std::uint64_t shadow = 0;
    std::uint64_t photons = 0;          // SPPM: photons emitted
    std::uint64_t photon_rays = 0;      // their rays
    std::uint64_t photon_deposits = 0;  // photons added to a visible point
    NonfiniteCounts nonfinite{};        // non-finite values dropped, per NonfiniteStage
};

// Adds `term` to `radiance` unless the sum is not finite (a NaN or Inf term,
// or an overflowing sum): then it is dropped and counted in `stage`, as the
// kernels' add_finite does (kernels/device/guards.h).
template <class Real>
void add_finite(Vec3<Real>& radiance, const Vec3<Real>& term, NonfiniteStage stage, RayCounts& counts) {
    Vec3<Real> sum = radiance + term;
    if (SharedMath<Real>::vec3_is_finite(sum)) {
        radiance = sum;
    } else {
        ++counts.nonfinite[static_cast<std::size_t>(stage)];
    }
}

// The random numbers of one camera sample.
template <class Real>
struct SampleRng {
    std::uint32_t seed, pixel, sample;
    bool sobol;  // render.sampler
    Real operator()(std::uint32_t bounce, std::uint32_t dimension) const {
        return SharedMath<Real>::camera_uniform(seed, pixel, sample, bounce, dimension, sobol);
    }
    // Both numbers of the Sobol' pair whose first dimension is `first_dimension`.
    typename SharedMath<Real>::CameraPair pair(std::uint32_t bounce, std::uint32_t first_dimension) const {
        return SharedMath<Real>::camera_pair(seed, pixel, sample, bounce, first_dimension, sobol);
    }
};

// The random numbers of sample `sample` of pixel `pixel`, as the scene's render settings draw them.
template <class Real>
SampleRng<Real> sample_rng(const ReferenceScene<Real>& scene, std::uint32_t pixel, std::uint32_t sample) {
    return {scene.render.seed, pixel, sample, scene.render.sampler == Sampler::Sobol};
}

template <class Real>
struct Ray {
    Vec3<Real> origin, direction;  // direction is unit length
};

template <class Real>
struct ShapeHit {
    Real t = SharedMath<Real>::real_max;  // real_max: nothing hit
    ShapeType shape = ShapeType::Sphere;
    int index = -1;
    bool found() const { return index >= 0; }
};

// Where a ray met a surface.
template <class Real>
struct SurfacePoint {
    Vec3<Real> point;
    Vec3<Real> normal;   // geometric: outward, plane normal, or edge1 x edge2
    Vec3<Real> shading;  // on normal's side: a triangle's interpolated vertex normal, else normal
    int material;
    Real error;                                 // bound on the point's distance from the surface (shared/hit_point.h)
    typename SharedMath<Real>::TextureUV uv{};  // with textures (shared/texture.h); (0, 0) on planes
};

// A hit as the Embree intersector reports it (WP_SHAPE_* is ShapeType's order).
inline ShapeHit<float> shape_hit(const HostHit& hit) {
    if (hit.shape == WP_NO_HIT) return {};
    return {hit.t, static_cast<ShapeType>(hit.shape >> WP_SHAPE_TYPE_SHIFT),
            static_cast<int>(hit.shape & WP_SHAPE_INDEX_MASK)};
}

template <class Real>
ShapeHit<Real> closest_hit(const ReferenceScene<Real>& scene, const Ray<Real>& ray) {
    using M = SharedMath<Real>;
    if constexpr (std::is_same_v<Real, float>)
        if (scene.embree) return shape_hit(scene.embree->closest(ray.origin, ray.direction, M::real_max));
    ShapeHit<Real> hit;
    auto keep_if_closer = [&hit](Real t, ShapeType shape, int index) {
        if (t < hit.t) hit = {t, shape, index};
    };
    for (int i = 0; i < static_cast<int>(scene.spheres.size()); ++i) {
        const auto& s = scene.spheres[i];
        keep_if_closer(M::intersect_sphere(s.center, s.radius, ray.origin, ray.direction, hit.t), ShapeType::Sphere, i);
    }
    for (int i = 0; i < static_cast<int>(scene.planes.size()); ++i) {
        const auto& p = scene.planes[i];
        keep_if_closer(M::intersect_plane(p.point, p.normal, ray.origin, ray.direction, hit.t), ShapeType::Plane, i);
    }
    for (int i = 0; i < static_cast<int>(scene.quads.size()); ++i) {
        const auto& q = scene.quads[i];
        keep_if_closer(M::intersect_quad(q.corner, q.edge1, q.edge2, ray.origin, ray.direction, hit.t), ShapeType::Quad,
                       i);
    }
    if (!scene.bvh_nodes.empty()) {
        std::uint32_t triangle = 0;
        Real t = M::bvh_trace(scene.bvh_nodes.data(), scene.triangles.data(), ray.origin, ray.direction, hit.t, 0,
                              &triangle);
        keep_if_closer(t, ShapeType::Mesh, static_cast<int>(triangle));
    }
    return hit;
}

// True when any shape lies on the ray closer than `distance`.
template <class Real>
bool occluded(const ReferenceScene<Real>& scene, const Ray<Real>& ray, Real distance) {
    using M = SharedMath<Real>;
    if constexpr (std::is_same_v<Real, float>)
        if (scene.embree) return scene.embree->occluded(ray.origin, ray.direction, distance);
    for (const auto& s : scene.spheres) {
        if (M::intersect_sphere(s.center, s.radius, ray.origin, ray.direction, distance) < distance) return true;
    }
    for (const auto& p : scene.planes) {
        if (M::intersect_plane(p.point, p.normal, ray.origin, ray.direction, distance) < distance) return true;
    }
    for (const auto& q : scene.quads) {
        if (M::intersect_quad(q.corner, q.edge1, q.edge2, ray.origin, ray.direction, distance) < distance) return true;
    }
    std::uint32_t triangle = 0;
    return !scene.bvh_nodes.empty() && M::bvh_trace(scene.bvh_nodes.data(), scene.triangles.data(), ray.origin,
                                                    ray.direction, distance, 1, &triangle) < distance;
}

// Where the ray met `hit`'s shape, its uv left (0, 0).
template <class Real>
SurfacePoint<Real> untextured_surface_at(const ReferenceScene<Real>& scene, const Ray<Real>& ray,
                                         const ShapeHit<Real>& hit) {
    using M = SharedMath<Real>;
    auto with_material = [](const typename M::HitPoint& h, int material) {
        return SurfacePoint<Real>{h.point, h.normal, h.normal, material, h.error};
    };
    switch (hit.shape) {
        case ShapeType::Sphere: {
            const auto& s = scene.spheres[hit.index];
            return with_material(M::sphere_hit(s.center, s.radius, ray.origin, ray.direction, hit.t), s.material);
        }
        case ShapeType::Plane: {
            const auto& p = scene.planes[hit.index];
            return with_material(M::plane_hit(p.point, p.normal, ray.origin, ray.direction, hit.t), p.material);
        }
        case ShapeType::Quad: {
            const auto& q = scene.quads[hit.index];
            return with_material(M::quad_hit(q.corner, q.edge1, q.edge2, ray.origin, ray.direction, hit.t), q.material);
        }
        case ShapeType::Mesh: {
            const auto& tri = scene.triangles[hit.index];
            Vec3<Real> p0 = M::triangle_vertex(tri.p0), p1 = M::triangle_vertex(tri.p1),
                       p2 = M::triangle_vertex(tri.p2);
            SurfacePoint<Real> x =
                with_material(M::triangle_hit(p0, p1, p2, ray.origin, ray.direction), static_cast<int>(tri.material));
            if (scene.vertex_normals) {
                const auto& n = scene.triangle_normals[hit.index];
                x.shading = M::triangle_shading_normal(p0, p1, p2, M::triangle_vertex(n.n0), M::triangle_vertex(n.n1),
                                                       M::triangle_vertex(n.n2), x.normal, x.point);
            }
            return x;
        }
    }
    return {};
}

// The uv of `x`, a hit on `hit`'s shape (shared/texture.h).
template <class Real>
typename SharedMath<Real>::TextureUV surface_uv(const ReferenceScene<Real>& scene, const ShapeHit<Real>& hit,
                                                const SurfacePoint<Real>& x) {
    using M = SharedMath<Real>;
    switch (hit.shape) {
        case ShapeType::Sphere:
            return M::sphere_uv(x.normal);
        case ShapeType::Quad: {
            const auto& q = scene.quads[hit.index];
            return M::quad_uv(q.corner, q.edge1, q.edge2, x.point);
        }
        case ShapeType::Mesh: {
            const auto& tri = scene.triangles[hit.index];
            const auto& uv = scene.triangle_uvs[hit.index];
            typename M::TriangleBarycentrics b = M::triangle_barycentrics(
                M::triangle_vertex(tri.p0), M::triangle_vertex(tri.p1), M::triangle_vertex(tri.p2), x.point);
            return M::triangle_uv({uv.uv0[0], uv.uv0[1]}, {uv.uv1[0], uv.uv1[1]}, {uv.uv2[0], uv.uv2[1]}, b.b1, b.b2);
        }
        default:
            return {Real(0), Real(0)};
    }
}

// dp/du of `x`, a hit on `hit`'s shape (shared/normal_map.h); zero on planes.
template <class Real>
Vec3<Real> surface_dp_du(const ReferenceScene<Real>& scene, const ShapeHit<Real>& hit, const SurfacePoint<Real>& x) {
    using M = SharedMath<Real>;
    switch (hit.shape) {
        case ShapeType::Sphere:
            return M::sphere_dp_du(x.normal);
        case ShapeType::Quad:
            return scene.quads[hit.index].edge1;
        case ShapeType::Mesh: {
            const auto& tri = scene.triangles[hit.index];
            const auto& uv = scene.triangle_uvs[hit.index];
            return M::triangle_dp_du(M::triangle_vertex(tri.p0), M::triangle_vertex(tri.p1), M::triangle_vertex(tri.p2),
                                     uv.uv0[0], uv.uv0[1], uv.uv1[0], uv.uv1[1], uv.uv2[0], uv.uv2[1]);
        }
        default:
            return Vec3<Real>(0);
    }
}

// dp/du and dp/dv of `x`, a hit on `hit`'s shape, to their length (shared/normal_map.h' bump_mapped); zero on planes.
template <class Real>
typename SharedMath<Real>::SurfaceTangents surface_tangents(const ReferenceScene<Real>& scene,
                                                            const ShapeHit<Real>& hit, const SurfacePoint<Real>& x) {
    using M = SharedMath<Real>;
    switch (hit.shape) {
        case ShapeType::Sphere:
            return M::sphere_tangents(x.normal, scene.spheres[hit.index].radius);
        case ShapeType::Quad:
            return {scene.quads[hit.index].edge1, scene.quads[hit.index].edge2};
        case ShapeType::Mesh: {
            const auto& tri = scene.triangles[hit.index];
            const auto& uv = scene.triangle_uvs[hit.index];
            const Vec3<Real> p0 = M::triangle_vertex(tri.p0), p1 = M::triangle_vertex(tri.p1),
                             p2 = M::triangle_vertex(tri.p2);
            return {M::triangle_dp_du(p0, p1, p2, uv.uv0[0], uv.uv0[1], uv.uv1[0], uv.uv1[1], uv.uv2[0], uv.uv2[1]),
                    M::triangle_dp_dv(p0, p1, p2, uv.uv0[0], uv.uv0[1], uv.uv1[0], uv.uv1[1], uv.uv2[0], uv.uv2[1])};
        }
        default:
            return {Vec3<Real>(0), Vec3<Real>(0)};
    }
}

// Texture p (TexturedParameter) of x's material, or WP_NO_TEXTURE.
template <class Real>
std::uint32_t texture_of(const ReferenceScene<Real>& scene, const SurfacePoint<Real>& x, TexturedParameter p) {
    return scene.material_textures[x.material][static_cast<std::size_t>(p)];
}

template <class Real>
SurfacePoint<Real> surface_at(const ReferenceScene<Real>& scene, const Ray<Real>& ray, const ShapeHit<Real>& hit) {
    SurfacePoint<Real> x = untextured_surface_at(scene, ray, hit);
    if (scene.textures) x.uv = surface_uv(scene, hit, x);
    return x;
}

// At surface x of `hit`, reached from wo, whose normals `facing` turned to
// wo's side: where its material is a normalmap or bumpmap, the perturbed
// shading normal into facing.ns and the terminator term into `material`
// (the kernels' vertex_at); returns whether the material scatters the path
// at all (normal_map_shades).
template <class Real>
bool normal_mapped_vertex(const ReferenceScene<Real>& scene, const ShapeHit<Real>& hit, const SurfacePoint<Real>& x,
                          const Vec3<Real>& wo, typename SharedMath<Real>::FacingNormals& facing,
                          typename ReferenceScene<Real>::SurfaceMaterial& material) {
    using M = SharedMath<Real>;
    const std::uint32_t normal_map =
        scene.normal_map ? texture_of(scene, x, TexturedParameter::NormalMap) : WP_NO_TEXTURE;
    const std::uint32_t bump_map = scene.bump_map ? texture_of(scene, x, TexturedParameter::BumpMap) : WP_NO_TEXTURE;
    typename M::NormalMapped mapped;
    if (normal_map != WP_NO_TEXTURE) {
        mapped = M::normal_mapped(x.shading, facing.ns, surface_dp_du(scene, hit, x),
                                  M::texture_value(scene.texture_table[normal_map], scene.texels.data(), x.uv), wo);
    } else if (bump_map != WP_NO_TEXTURE) {
        const typename M::SurfaceTangents tangents = surface_tangents(scene, hit, x);
        const typename M::TextureUV gradient =
            M::texture_gradient(scene.texture_table[bump_map], scene.texels.data(), x.uv);
        mapped = M::bump_mapped(x.normal, x.shading, facing.ns, tangents.dp_du, tangents.dp_dv,
                                material.bump_scale * gradient.u, material.bump_scale * gradient.v, wo);
    } else {
        return true;
    }
    material.unperturbed_normal = facing.ns;
    material.terminator_alpha2 = mapped.terminator_alpha2;
    facing.ns = mapped.normal;
    return M::normal_map_shades(wo, facing.ns);
}

// Textured parameter p of surface x's material at x's uv, `untextured` where it has no texture (shared/texture.h).
template <class Real>
Vec3<Real> surface_colour(const ReferenceScene<Real>& scene, const SurfacePoint<Real>& x, TexturedParameter p,
                          const Vec3<Real>& untextured) {
    const std::uint32_t texture = scene.material_textures[x.material][static_cast<std::size_t>(p)];
    return SharedMath<Real>::colour_parameter(
        untextured, texture, scene.texture_table[texture == WP_NO_TEXTURE ? 0u : texture], scene.texels.data(), x.uv);
}

// Textured scalar parameter p of surface x's material at x's uv, as surface_colour (shared/texture.h).
template <class Real>
Real surface_scalar(const ReferenceScene<Real>& scene, const SurfacePoint<Real>& x, TexturedParameter p,
                    Real untextured) {
    const std::uint32_t texture = scene.material_textures[x.material][static_cast<std::size_t>(p)];
    return SharedMath<Real>::scalar_parameter(
        untextured, texture, scene.texture_table[texture == WP_NO_TEXTURE ? 0u : texture], scene.texels.data(), x.uv);
}

// The material at surface x with its textured parameters looked up at x's uv (the kernels' textured_material).
template <class Real>
typename ReferenceScene<Real>::SurfaceMaterial material_at(const ReferenceScene<Real>& scene,
                                                           const SurfacePoint<Real>& x) {
    typename ReferenceScene<Real>::SurfaceMaterial material = scene.materials[x.material];
    if (!scene.textures) return material;
    const Vec3<Real> albedo = surface_colour(scene, x, TexturedParameter::Albedo, material.albedo);
    const Vec3<Real> specular =
        surface_colour(scene, x, TexturedParameter::SpecularReflectance, material.specular_reflectance);
    material.albedo = material.plastic.diffuse_reflectance = material.roughplastic.diffuse_reflectance = albedo;
    material.specular_reflectance = material.plastic.specular_reflectance = material.roughplastic.specular_reflectance =
        specular;
    // roughplastic's roughness stays untextured (Mitsuba's tables depend on it): roughplastic.m keeps it
    material.microfacet.alpha_u = surface_scalar(scene, x, TexturedParameter::AlphaU, material.microfacet.alpha_u);
    material.microfacet.alpha_v = surface_scalar(scene, x, TexturedParameter::AlphaV, material.microfacet.alpha_v);
    if (scene.mask)
        material.opacity =
            SharedMath<Real>::mask_opacity(surface_scalar(scene, x, TexturedParameter::Opacity, material.opacity));
    return material;
}

// A point sampled on a light, with the material that emits there and the
// magnitude its error bound comes from (offset.h).
template <class Real>
struct LightPoint {
    typename SharedMath<Real>::LightSample sample;
    int material;
    Real magnitude;
};

// u1, u2 place the point; u_triangle picks a mesh light's triangle by area.
template <class Real>
LightPoint<Real> sample_light(const ReferenceScene<Real>& scene, const typename ReferenceScene<Real>::LightRef& light,
                              const Vec3<Real>& reference, Real u1, Real u2, Real u_triangle) {
    using M = SharedMath<Real>;
    switch (light.shape) {
        case ShapeType::Sphere: {
            const auto& s = scene.spheres[light.index];
            return {M::sample_sphere(s.center, s.radius, reference, u1, u2), s.material,
                    M::sphere_magnitude(s.center, s.radius)};
        }
        case ShapeType::Mesh: {
            std::uint32_t k = light.first_triangle + M::select_light(&scene.light_triangle_cdf[light.first_triangle],
                                                                     light.triangle_count, u_triangle);
            const auto& t = scene.light_triangles[k];
            Vec3<Real> p0 = M::triangle_vertex(t.p0), p1 = M::triangle_vertex(t.p1), p2 = M::triangle_vertex(t.p2);
            return {M::sample_triangle(p0, p1, p2, light.area, reference, u1, u2), static_cast<int>(t.material),
                    M::triangle_magnitude(p0, p1, p2)};
        }
        default: {
            const auto& q = scene.quads[light.index];
            return {M::sample_quad(q.corner, q.edge1, q.edge2, reference, u1, u2), q.material,
                    M::quad_magnitude(q.corner, q.edge1, q.edge2)};
        }
    }
}

// The solid-angle density with which next-event estimation from `reference`
// samples `point` (geometric normal `normal`) of light `index`.
template <class Real>
Real light_point_pdf(const ReferenceScene<Real>& scene, std::uint32_t index, const Vec3<Real>& reference,
                     const Vec3<Real>& point, const Vec3<Real>& normal) {
    using M = SharedMath<Real>;
    const auto& light = scene.lights[index];
    Real point_pdf = 0;
    switch (light.shape) {
        case ShapeType::Sphere: {
            const auto& s = scene.spheres[light.index];
            point_pdf = M::sphere_light_pdf(s.center, s.radius, reference, point, normal);
            break;
        }
        case ShapeType::Mesh:
            point_pdf = M::mesh_light_pdf(light.area, reference, point, normal);
            break;
        default: {
            const auto& q = scene.quads[light.index];
            point_pdf = M::quad_light_pdf(q.edge1, q.edge2, reference, point, normal);
        }
    }
    return M::light_sample_pdf(M::light_selection_pmf(scene.light_cdf.data(), index), point_pdf);
}

// light_point_pdf for the light the shape `hit` belongs to (light_key); 0
// where it is no light.
template <class Real>
Real light_pdf_at_hit(const ReferenceScene<Real>& scene, const ShapeHit<Real>& hit, const Vec3<Real>& reference,
                      const Vec3<Real>& point, const Vec3<Real>& normal) {
    using M = SharedMath<Real>;
    bool is_triangle = hit.shape == ShapeType::Mesh;
    auto index = static_cast<std::uint32_t>(hit.index);
    std::uint32_t key = M::light_key(is_triangle, index, is_triangle ? scene.triangles[index].mesh : 0u);
    for (std::uint32_t i = 0; i < scene.lights.size(); ++i) {  // a light's index is its mesh's for a mesh light
        const auto& light = scene.lights[i];
        if (light.kind == LightKind::Shape && light.shape == hit.shape &&
            static_cast<std::uint32_t>(light.index) == key)
            return light_point_pdf(scene, i, reference, point, normal);
    }
    return Real(0);
}

// The density with which next-event estimation picks the environment's
// direction d (the light table's last light): its selection probability
// times the map's density, or the uniform sphere's for the constant one (the
// kernels' environment_light_pdf).
template <class Real>
Real environment_light_pdf(const ReferenceScene<Real>& scene, const Vec3<Real>& d) {
    using M = SharedMath<Real>;
    auto environment = static_cast<std::uint32_t>(scene.lights.size() - 1);
    Real direction_pdf = scene.environment_map
                             ? M::environment_pdf(scene.environment_layout, scene.environment_data.data(), d)
                             : M::uniform_sphere_pdf();
    return M::light_sample_pdf(M::light_selection_pmf(scene.light_cdf.data(), environment), direction_pdf);
}

// The environment's radiance from direction d: the map's, or the constant background.
template <class Real>
Vec3<Real> environment_radiance_from(const ReferenceScene<Real>& scene, const Vec3<Real>& d) {
    using M = SharedMath<Real>;
    return scene.environment_map ? M::environment_radiance(scene.environment_layout, scene.environment_data.data(), d)
                                 : scene.background;
}

// The environment's radiance a path of throughput `throughput` counts where
// it leaves the scene along d after a specular vertex (or the camera) or a
// bounce of density `bsdf_pdf` (the kernels' environment_emission).
template <class Real>
Vec3<Real> environment_emission(const ReferenceScene<Real>& scene, const Vec3<Real>& d, bool after_specular,
                                Real bsdf_pdf, const Vec3<Real>& throughput) {
    using M = SharedMath<Real>;
    bool has_environment = !scene.lights.empty() && scene.lights.back().kind == LightKind::Environment;
    if (!has_environment) return Vec3<Real>(Real(0));
    Real light_pdf = scene.mis ? environment_light_pdf(scene, d) : Real(0);
    Real weight = M::emission_weight(after_specular, bsdf_pdf, light_pdf, scene.nee, scene.mis);
    return M::environment_seen(throughput, environment_radiance_from(scene, d), weight);
}

// Whether `material` transmits through a lobe of finite density (next-event
// estimation samples lights on both sides).
inline bool transmits(MaterialType material) { return material == MaterialType::RoughDielectric; }

// Whether `material` is a diffuse base under a dielectric coat.
inline bool is_plastic(MaterialType material) {
    return material == MaterialType::Plastic || material == MaterialType::RoughPlastic;
}

// Whether `material` has a lobe of finite density, where next-event estimation
// samples a light (the plastic's diffuse lobe beside its delta lobe).
inline bool is_non_specular(MaterialType material) {
    return material == MaterialType::Diffuse || material == MaterialType::RoughConductor || transmits(material) ||
           is_plastic(material);
}

// Whether `material` chooses one of its lobes (reflection or transmission, the coat or the base) with a random number.
inline bool chooses_lobe(MaterialType material) {
    return material == MaterialType::Glass || material == MaterialType::RoughDielectric ||
           material == MaterialType::ThinDielectric || is_plastic(material);
}

// The path's throughput times f, and the density of BSDF sampling, for the
// direction wi at a non-specular material (the kernels' vertex_bsdf_value),
// seen from wo with shading normal ns, on the `front` of the surface or its back.
template <class Real>
struct BsdfValue {
    Vec3<Real> throughput_f;
    Real pdf;
};

// The frame of a rough material's microfacets about the normal of
// `isotropic`, the frame it builds from the normal alone (shared/materials/microfacet.h):
// that frame itself unless the scene has anisotropic roughness (the kernels'
// WP_HAS_ANISOTROPIC_ROUGHNESS).
template <class Real>
typename SharedMath<Real>::Frame microfacet_frame(const ReferenceScene<Real>& scene,
                                                  const typename ReferenceScene<Real>::SurfaceMaterial& material,
                                                  const typename SharedMath<Real>::Frame& isotropic) {
    return scene.anisotropic ? SharedMath<Real>::microfacet_frame(material.microfacet, isotropic, material.dp_du)
                             : isotropic;
}

template <class Real>
BsdfValue<Real> nested_bsdf_value(const ReferenceScene<Real>& scene,
                                  const typename ReferenceScene<Real>::SurfaceMaterial& material, bool front,
                                  const Vec3<Real>& ns, const Vec3<Real>& wo, const Vec3<Real>& wi,
                                  const Vec3<Real>& throughput) {
    using M = SharedMath<Real>;
    if (material.type == MaterialType::RoughDielectric) {
        const typename M::Frame frame = microfacet_frame(scene, material, M::roughdielectric_frame(ns, front));
        return {throughput * M::roughdielectric_eval(material.microfacet, material.ior, front, frame, wo, wi,
                                                     WP_TRANSPORT_RADIANCE),
                M::roughdielectric_pdf(material.microfacet, material.ior, front, frame, wo, wi)};
    }
    if (material.type == MaterialType::Plastic) {  // the diffuse lobe's
        return {throughput * M::plastic_eval(material.plastic, ns, wo, wi),
                M::plastic_pdf(material.plastic, ns, wo, wi)};
    }
    if (material.type == MaterialType::RoughPlastic) {
        const Real* table = scene.roughplastic_transmittance.data();
        return {throughput * M::roughplastic_eval(material.roughplastic, table, ns, wo, wi),
                M::roughplastic_pdf(material.roughplastic, table, ns, wo, wi)};
    }
    if (material.type == MaterialType::RoughConductor) {
        const typename M::Frame frame = microfacet_frame(scene, material, M::frame_from_normal(ns));
        return {throughput * M::roughconductor_eval(material.microfacet, material.eta, material.k,
                                                    material.specular_reflectance, frame, wo, wi),
                M::roughconductor_pdf(material.microfacet, frame, wo, wi)};
    }
    return {M::diffuse_eval(throughput * material.albedo, ns, wi), M::diffuse_pdf(ns, wi, scene.uniform_hemisphere)};
}

// The material's, times a normal map's terminator term (shared/normal_map.h;
// 1 without one), and f and the density times a mask's opacity (shared/materials/mask.h).
template <class Real>
BsdfValue<Real> bsdf_value(const ReferenceScene<Real>& scene,
                           const typename ReferenceScene<Real>::SurfaceMaterial& material, bool front,
                           const Vec3<Real>& ns, const Vec3<Real>& wo, const Vec3<Real>& wi,
                           const Vec3<Real>& throughput) {
    BsdfValue<Real> b = nested_bsdf_value(scene, material, front, ns, wo, wi, throughput);
    if (scene.perturbs_normals)
        b.throughput_f = b.throughput_f * SharedMath<Real>::normal_map_terminator(material.terminator_alpha2,
                                                                                  material.unperturbed_normal, wi);
    if (scene.mask) {
        b.throughput_f = b.throughput_f * material.opacity;
        b.pdf = b.pdf * material.opacity;
    }
    return b;
}

// Next-event estimation at a point x (with error bound x_error) of a
// non-specular `material` with geometric and shading normals nf and ns
// turned to wo, reached from wo on the `front` of the surface or its back,
// on a path of throughput `throughput`: one
// light chosen by the power CDF, one point on it, one shadow ray. Returns
// the radiance the sample adds.
template <class Real>
Vec3<Real> sample_direct_light(const ReferenceScene<Real>& scene, const Vec3<Real>& x, Real x_error,
                               const Vec3<Real>& nf, const Vec3<Real>& ns, bool front, const Vec3<Real>& wo,
                               const Vec3<Real>& throughput,
                               const typename ReferenceScene<Real>::SurfaceMaterial& material,
                               const SampleRng<Real>& rng, std::uint32_t bounce, RayCounts& counts) {
    using M = SharedMath<Real>;
    auto light_count = static_cast<std::uint32_t>(scene.lights.size());
    std::uint32_t index = M::select_light(scene.light_cdf.data(), light_count, rng(bounce, DIM_LIGHT_SELECT));
    typename M::CameraPair point = rng.pair(bounce, DIM_LIGHT_U);
    Real selection_pmf = M::light_selection_pmf(scene.light_cdf.data(), index);
    typename M::DirectLight direct;
    const auto& light = scene.lights[index];
    if (light.kind == LightKind::Directional) {  // a delta light: no MIS, its density the selection probability
        BsdfValue<Real> bsdf = bsdf_value(scene, material, front, ns, wo, light.to_light, throughput);
        direct =
            M::distant_direct_light(x, x_error, nf, ns, transmits(material.type), light.to_light, bsdf.throughput_f,
                                    bsdf.pdf, selection_pmf, light.emitted, false, scene.shading_normals);
    } else if (light.kind == LightKind::Point) {                        // a delta light too
        Vec3<Real> wi = M::v3_normalize(M::v3_sub(light.position, x));  // as the kernels compute it
        BsdfValue<Real> bsdf = bsdf_value(scene, material, front, ns, wo, wi, throughput);
        Real falloff = M::spot_falloff(light.axis, -wi, light.cos_cutoff, light.cos_beam, light.cutoff_angle,
                                       light.inv_transition_width);
        direct =
            M::point_direct_light(x, x_error, nf, ns, transmits(material.type), wi, bsdf.throughput_f, selection_pmf,
                                  light.position, M::v3_scale(light.emitted, falloff), scene.shading_normals);
    } else if (light.kind == LightKind::Environment && scene.environment_map) {
        typename M::EnvironmentSample sky =
            M::environment_sample(scene.environment_layout, scene.environment_data.data(), point.u, point.v);
        BsdfValue<Real> bsdf = bsdf_value(scene, material, front, ns, wo, sky.direction, throughput);
        direct = M::distant_direct_light(x, x_error, nf, ns, transmits(material.type), sky.direction, bsdf.throughput_f,
                                         bsdf.pdf, M::light_sample_pdf(selection_pmf, sky.pdf), sky.radiance, scene.mis,
                                         scene.shading_normals);
    } else if (light.kind == LightKind::Environment) {
        Vec3<Real> wi = M::sample_uniform_sphere(point.u, point.v);
        BsdfValue<Real> bsdf = bsdf_value(scene, material, front, ns, wo, wi, throughput);
        direct = M::distant_direct_light(x, x_error, nf, ns, transmits(material.type), wi, bsdf.throughput_f, bsdf.pdf,
                                         M::light_sample_pdf(selection_pmf, M::uniform_sphere_pdf()), scene.background,
                                         scene.mis, scene.shading_normals);
    } else {
        LightPoint<Real> p = sample_light(scene, light, x, point.u, point.v, rng(bounce, DIM_LIGHT_TRIANGLE));
        const auto& emitter = scene.materials[p.material];
        Vec3<Real> wi = M::direct_light_direction(p.sample, x);
        BsdfValue<Real> bsdf = bsdf_value(scene, material, front, ns, wo, wi, throughput);
        direct = M::direct_light(x, x_error, nf, ns, transmits(material.type), wi, bsdf.throughput_f, bsdf.pdf,
                                 p.sample, p.magnitude, selection_pmf, emitter.emission, emitter.two_sided, scene.mis,
                                 scene.shading_normals);
    }
    if (!direct.carries) return Vec3<Real>(Real(0));
    ++counts.shadow;
    const auto& shadow = direct.shadow;
    if (occluded(scene, Ray<Real>{shadow.origin, shadow.direction}, shadow.distance)) return Vec3<Real>(Real(0));
    return direct.contribution;
}

// The random numbers of a camera path's BSDF sample at `bounce`, drawn for
// the material that uses them (a non-specular direction, a glass lobe, a
// mask's choice: `masked`, in a scene with masks), 0 else.
template <class Real>
typename SharedMath<Real>::BsdfRandom camera_bsdf_random(const SampleRng<Real>& rng, std::uint32_t bounce,
                                                         MaterialType material, bool masked) {
    typename SharedMath<Real>::BsdfRandom random{Real(0), Real(0), Real(0)};
    if (chooses_lobe(material) || masked) random.lobe = rng(bounce, DIM_BSDF_LOBE);
    if (is_non_specular(material)) {
        typename SharedMath<Real>::CameraPair direction = rng.pair(bounce, DIM_BSDF_U);
        random.u = direction.u;
        random.v = direction.v;
    }
    return random;
}

// Samples the material at a surface point reached along direction d, on the
// `front` of the surface (the side its geometric normal points to) or its
// back, with the geometric and shading normals nf and ns turned to face d,
// for a path that carries `transport` (WP_TRANSPORT_*).
template <class Real>
typename SharedMath<Real>::BsdfSample nested_scatter(const ReferenceScene<Real>& scene,
                                                     const typename ReferenceScene<Real>::SurfaceMaterial& material,
                                                     const Vec3<Real>& d, bool front, const Vec3<Real>& nf,
                                                     const Vec3<Real>& ns,
                                                     const typename SharedMath<Real>::BsdfRandom& random,
                                                     std::uint32_t transport) {
    using M = SharedMath<Real>;
    switch (material.type) {
        case MaterialType::Mirror:
            return M::mirror_sample(material.reflectance, -d, nf, ns, scene.shading_normals);
        case MaterialType::Glass:
            return M::glass_sample(material.ior, front, -d, nf, ns, random.lobe, transport, scene.shading_normals);
        case MaterialType::Conductor:
            return M::conductor_sample(material.eta, material.k, material.specular_reflectance, -d, nf, ns,
                                       scene.shading_normals);
        case MaterialType::RoughDielectric:
            return M::roughdielectric_sample(material.microfacet, material.ior, front, nf,
                                             microfacet_frame(scene, material, M::roughdielectric_frame(ns, front)), -d,
                                             random, transport, scene.shading_normals);
        case MaterialType::ThinDielectric:
            return M::thindielectric_sample(material.ior, -d, nf, ns, random.lobe, scene.shading_normals);
        case MaterialType::RoughConductor:
            return M::roughconductor_sample(material.microfacet, material.eta, material.k,
                                            material.specular_reflectance, nf,
                                            microfacet_frame(scene, material, M::frame_from_normal(ns)), -d, random.u,
                                            random.v, scene.shading_normals);
        case MaterialType::Plastic:
            return M::plastic_sample(material.plastic, nf, ns, -d, random, scene.shading_normals);
        case MaterialType::RoughPlastic:
            return M::roughplastic_sample(material.roughplastic, scene.roughplastic_transmittance.data(), nf, ns, -d,
                                          random, scene.shading_normals);
        default:  // diffuse
            return M::diffuse_sample(material.albedo, nf, ns, random.u, random.v, scene.uniform_hemisphere,
                                     scene.shading_normals);
    }
}

// The material's sample, its weight times a normal map's terminator term
// (shared/normal_map.h; 1 without one), or a mask's pass (shared/materials/mask.h).
template <class Real>
typename SharedMath<Real>::BsdfSample scatter(const ReferenceScene<Real>& scene,
                                              const typename ReferenceScene<Real>::SurfaceMaterial& material,
                                              const Vec3<Real>& d, bool front, const Vec3<Real>& nf,
                                              const Vec3<Real>& ns, typename SharedMath<Real>::BsdfRandom random,
                                              std::uint32_t transport) {
    using M = SharedMath<Real>;
    const bool passes = scene.mask && M::mask_passes(material.opacity, random.lobe);
    if (scene.mask) random.lobe = M::mask_nested_lobe(material.opacity, random.lobe);
    typename M::BsdfSample s = nested_scatter(scene, material, d, front, nf, ns, random, transport);
    if (scene.perturbs_normals)
        s.weight =
            s.weight * M::normal_map_terminator(material.terminator_alpha2, material.unperturbed_normal, s.direction);
    if (scene.mask) s = M::mask_sample(material.opacity, passes, s, d, nf);
    return s;
}

// Where an SPPM camera path first met a non-specular surface (after any
// mirror, glass or plastic coat): the visible point photons add to
// (docs/architecture.md, "Photon mapping"), with what evaluates its f.
template <class Real>
struct VisiblePoint {
    Vec3<Real> point{0}, nf{0}, ns{0};  // the normals on the camera's side
    Vec3<Real> weight{0};               // the path's (the kernels' visible_point_weight)
    std::uint32_t depth = WP_NO_VISIBLE_POINT;
    Real distance = 0;  // the path's length from the camera (sppm_footprint)
    typename ReferenceScene<Real>::SurfaceMaterial material{};
    Vec3<Real> wo{0};    // back along the camera path
    bool front = false;  // the path met the side the geometric normal points to
    bool found() const { return depth != WP_NO_VISIBLE_POINT; }
};

// Whether SPPM's camera pass makes its visible point at a vertex of
// `material` whose BSDF sample is `next` (the kernels' vertex_is_visible_point):
// a non-specular one, and a plastic where the sample chose its base.
template <class Real>
bool is_visible_point(MaterialType material, const typename SharedMath<Real>::BsdfSample& next) {
    return is_non_specular(material) && !(material == MaterialType::Plastic && next.specular);
}

// The weight a visible point keeps (the kernels' visible_point_weight): the
// throughput times the albedo at a diffuse vertex, over the base's
// probability at a plastic's, else the throughput.
template <class Real>
Vec3<Real> visible_point_weight(const typename ReferenceScene<Real>::SurfaceMaterial& material, const Vec3<Real>& ns,
                                const Vec3<Real>& wo, const Vec3<Real>& throughput) {
    if (material.type == MaterialType::Diffuse) return throughput * material.albedo;
    if (material.type == MaterialType::Plastic)
        return SharedMath<Real>::plastic_base_throughput(material.plastic, ns, wo, throughput);
    return throughput;
}

// The camera path's throughput times the visible point's f for a photon
// arriving along wi (the kernels' visible_point_bsdf).
template <class Real>
Vec3<Real> visible_point_f(const ReferenceScene<Real>& scene, const VisiblePoint<Real>& vp, const Vec3<Real>& wi) {
    if (vp.material.type == MaterialType::Diffuse) return SharedMath<Real>::diffuse_eval(vp.weight, vp.ns, wi);
    return SharedMath<Real>::finite_visible_f(
        bsdf_value(scene, vp.material, vp.front, vp.ns, vp.wo, wi, vp.weight).throughput_f);
}

// Radiance carried by one path that starts with `ray`. With `visible` (the
// camera pass of SPPM) the path records its first non-specular vertex there and
// ends at the hit after it, where it adds the emission it finds: the path
// tracer's estimator of the light that reaches the camera after at most one
// diffuse vertex; the photons bring the rest.
template <class Real>
Vec3<Real> trace_path(const ReferenceScene<Real>& scene, Ray<Real> ray, const SampleRng<Real>& rng, RayCounts& counts,
                      VisiblePoint<Real>* visible = nullptr) {
    using M = SharedMath<Real>;
    using vec3 = typename M::vec3;
    vec3 throughput(Real(1));
    vec3 radiance(Real(0));
    bool specular = true;  // the previous vertex was specular, or is the camera
    Real bsdf_pdf = 0;     // of the last diffuse bounce's direction
    Real eta_scale = 1;    // eta^2 over the refractions so far (roulette_survival)
    Real travelled = 0;    // from the camera, through mirrors and glass (SPPM's footprint)
    for (int depth = 0;;) {
        ++counts.extension;
        ShapeHit<Real> hit = closest_hit(scene, ray);
        if (!hit.found()) {
            add_finite<Real>(radiance, environment_emission(scene, ray.direction, specular, bsdf_pdf, throughput),
                             NonfiniteStage::emission, counts);
            break;
        }
        travelled += hit.t;
        SurfacePoint<Real> surface = surface_at(scene, ray, hit);
        auto material = material_at(scene, surface);
        if (scene.anisotropic) material.dp_du = surface_dp_du(scene, hit, surface);
        typename M::FacingNormals facing = M::normals_facing(ray.direction, surface.normal, surface.shading);
        const bool shades = normal_mapped_vertex(scene, hit, surface, -ray.direction, facing, material) &&
                            (facing.front || !material.one_sided);  // a one-sided material's back is black
        const bool front = facing.front;
        const vec3 &nf = facing.nf, &ns = facing.ns;
        bool weighs_emission = scene.mis && !specular && M::emits(material.emission);  // the power heuristic's case
        Real light_pdf =
            weighs_emission ? light_pdf_at_hit(scene, hit, ray.origin, surface.point, surface.normal) : Real(0);
        Real weight = M::emission_weight(specular, bsdf_pdf, light_pdf, scene.nee, scene.mis);
        add_finite<Real>(radiance, M::emission_seen(material.emission, material.two_sided, front, weight, throughput),
                         NonfiniteStage::emission, counts);
        if (depth >= scene.render.max_depth || material.type == MaterialType::Emitter) break;
        if (visible && visible->found()) break;  // the hit after the visible point

        auto bounce = static_cast<std::uint32_t>(depth);
        if (!shades) break;
        if (is_non_specular(material.type) && scene.nee) {
            add_finite<Real>(radiance,
                             sample_direct_light(scene, surface.point, surface.error, nf, ns, front, -ray.direction,
                                                 throughput, material, rng, bounce, counts),
                             NonfiniteStage::direct, counts);
        }
        typename M::BsdfSample next =
            scatter(scene, material, ray.direction, front, nf, ns,
                    camera_bsdf_random(rng, bounce, material.type, scene.mask), WP_TRANSPORT_RADIANCE);
        if (visible && is_visible_point<Real>(material.type, next)) {
            *visible = {surface.point,
                        nf,
                        ns,
                        visible_point_weight<Real>(material, ns, -ray.direction, throughput),
                        bounce,
                        travelled,
                        material,
                        -ray.direction,
                        front};
            if (!M::camera_pass_bounces_from_visible_point(scene.nee, scene.mis)) break;
        }
        if (!next.valid) break;
        throughput *= next.weight;
        ray = {M::offset_ray_origin(surface.point, next.leave_side, surface.error), next.direction};
        specular = next.specular;
        bsdf_pdf = next.pdf;
        eta_scale *= next.eta_squared;

        ++depth;
        typename M::RouletteOutcome roulette =
            M::russian_roulette(throughput, eta_scale, depth >= scene.render.rr_depth, rng(bounce, DIM_ROULETTE));
        if (!roulette.survives) break;
        throughput = roulette.throughput;
        if (!SharedMath<Real>::vec3_is_finite(throughput)) {  // would carry NaN or Inf into every later term
            ++counts.nonfinite[static_cast<std::size_t>(NonfiniteStage::scatter)];
            break;
        }
    }
    return radiance;
}

// The camera ray of sample `sample` in pixel (px, py), through the point of
// the pixel its filter draws (shared/pixel_filter.h).
template <class Real>
Ray<Real> camera_ray(const ReferenceScene<Real>& scene, int px, int py, const SampleRng<Real>& rng) {
    using M = SharedMath<Real>;
    const auto& c = scene.camera;
    typename M::CameraPair film = rng.pair(0, DIM_FILM_X);
    typename M::FilmPoint point = M::pixel_filter_sample(c.filter, film.u, film.v);
    return {c.position,
            M::pixel_direction(c.frame, Real(px), Real(py), Real(c.width), Real(c.height), point.u, point.v)};
}

// Radiance of one camera sample (finite: every addition was checked); with
// `visible`, SPPM's camera pass (trace_path).
template <class Real>
Vec3<Real> trace_camera_sample(const ReferenceScene<Real>& scene, int px, int py, int sample, RayCounts& counts,
                               VisiblePoint<Real>* visible = nullptr) {
    auto pixel = static_cast<std::uint32_t>(py * scene.camera.width + px);
    SampleRng<Real> rng = sample_rng(scene, pixel, static_cast<std::uint32_t>(sample));
    return trace_path(scene, camera_ray(scene, px, py, rng), rng, counts, visible);
}

}  // namespace wp::reference
