// The scene converted once to the reference renderer's scalar type, so that
// all path arithmetic runs in Real, as the kernels' runs in float.
#pragma once

#include <cstdint>
#include <memory>
#include <stdexcept>
#include <type_traits>
#include <vector>

#include "accel/bvh_layout.h"
#include "accel/embree_intersector.h"
#include "core/shared_math.h"
#include "scene/environment_layout.h"
#include "scene/mesh_lights.h"
#include "scene/microfacet_code.h"
#include "scene/pixel_filter.h"
#include "scene/plastic_constants.h"
#include "scene/scene.h"
#include "scene/texture_layout.h"

namespace wp::reference {

template <class Real>
using Vec3 = typename SharedMath<Real>::vec3;

template <class Real>
struct ReferenceScene {
    using M = SharedMath<Real>;
    using vec3 = typename M::vec3;

    struct SphereShape {
        vec3 center;
        Real radius;
        int material;
    };
    struct PlaneShape {
        vec3 point;
        vec3 normal;  // unit
        int material;
    };
    struct QuadShape {
        vec3 corner, edge1, edge2;
        int material;
    };
    struct SurfaceMaterial {
        MaterialType type;
        vec3 albedo;                        // diffuse
        vec3 reflectance;                   // mirror
        vec3 emission;                      // diffuse (optional) and emitter
        Real ior;                           // glass
        bool two_sided;                     // emission on both sides
        vec3 eta, k, specular_reflectance;  // conductor and roughconductor
        typename M::Microfacet microfacet;  // roughconductor
        typename M::PlasticParams plastic;  // plastic
        // roughplastic, its table of t in roughplastic_transmittance
        typename M::RoughPlasticParams roughplastic;
        Real bump_scale;  // a bumpmap's scale (Material::bump_scale)
        Real opacity;     // a mask's opacity (Material::opacity; 1 without a mask)
        bool one_sided;   // black from the back (Material::one_sided)
        // At a normalmap's or bumpmap's hit (path_tracer.h's
        // normal_mapped_vertex): its terminator term's alpha^2 (0: none) and
        // the unperturbed shading normal it measures from (shared/normal_map.h).
        Real terminator_alpha2 = 0;
        vec3 unperturbed_normal{0};
        // The surface's dp/du at the hit, where the scene is `anisotropic`:
        // an anisotropic material's alpha_u lies along it (microfacet_frame).
        vec3 dp_du{0};
    };
    struct LightRef {
        LightKind kind;   // a shape's, a directional or point light, or the environment (then the last)
        ShapeType shape;  // a shape's: Sphere, Quad or Mesh
        int index;        // into spheres, quads or the scene's meshes
        std::uint32_t first_triangle, triangle_count;  // a mesh: its triangles in light_triangles
        Real area;                                     // a mesh: its area
        vec3 to_light;                                 // a directional light: the unit direction towards it
        vec3 emitted;   // a directional light's irradiance, a point light's intensity (a spot's on its axis)
        vec3 position;  // a point light's
        // A point light's falloff (spot_falloff_terms), rounded as the device's.
        vec3 axis;
        Real cos_cutoff, cos_beam, cutoff_angle, inv_transition_width;
    };
    // Pinhole camera; its frame is built in double and then rounded, as the
    // kernels' host does (opencl/scene_upload.cpp).
    struct PinholeCamera {
        vec3 position;
        typename M::CameraFrame frame;
        int width, height;
        typename M::PixelFilter filter;
    };

    PinholeCamera camera;
    RenderSettings render;
    bool nee;                 // next-event estimation runs (FeatureSet::nee)
    bool mis;                 // with multiple importance sampling (FeatureSet::mis)
    bool vertex_normals;      // some mesh shades with vertex normals (FeatureSet::shading_normals)
    bool normal_map;          // some material is a normalmap (FeatureSet::normal_map)
    bool bump_map;            // some material is a bumpmap (FeatureSet::bump_map)
    bool perturbs_normals;    // either (the kernels' WP_PERTURBS_NORMALS)
    bool mask;                // some material is a mask (FeatureSet::mask)
    bool shading_normals;     // any: shading normals differ from geometric ones (the kernels' WP_USES_SHADING_NORMALS)
    bool uniform_hemisphere;  // diffuse vertices sample the uniform hemisphere (render.hemisphere)
    bool textures;            // some material parameter is textured: hits compute their uv (FeatureSet::textures)
    bool anisotropic;         // some rough material is anisotropic: hits keep dp/du (FeatureSet::anisotropic_roughness)
    vec3 background;          // the environment's radiance (a light where not black)
    bool environment_map;     // the environment is an image (FeatureSet::environment_map)
    std::vector<SurfaceMaterial> materials;
    std::vector<SphereShape> spheres;
    std::vector<PlaneShape> planes;
    std::vector<QuadShape> quads;
    std::vector<typename M::MeshTriangle> triangles;            // in the BVH's leaf order, or the scene's (Embree)
    std::vector<typename M::TriangleNormals> triangle_normals;  // parallel to triangles, if vertex_normals
    std::vector<typename M::BvhNode> bvh_nodes;                 // none where Embree traces
    std::shared_ptr<const EmbreeIntersector> embree;            // Intersector::Embree: closest_hit and occluded ask it
    std::vector<LightRef> lights;
    std::vector<Real> light_cdf;
    std::vector<typename M::MeshTriangle> light_triangles;  // mesh lights' (scene/mesh_lights.h)
    std::vector<Real> light_triangle_cdf;
    std::vector<Real> roughplastic_transmittance;    // scene/plastic_constants.h
    std::vector<typename M::Texture> texture_table;  // scene/texture_layout.h
    std::vector<Real> texels;
    // per material and TexturedParameter: its texture, or WP_NO_TEXTURE
    std::vector<std::array<std::uint32_t, kTexturedParameters>> material_textures;
    std::vector<typename M::TriangleUVs> triangle_uvs;    // parallel to triangles, if textures or anisotropic
    typename M::EnvironmentMapLayout environment_layout;  // scene/environment_layout.h, with environment_map
    std::vector<Real> environment_data;

    // Throws std::invalid_argument for Intersector::Embree in double.
    explicit ReferenceScene(const Scene& scene, Intersector intersector = Intersector::Bvh)
        : render(scene.render),
          nee(scene.features().nee),
          mis(scene.features().mis),
          vertex_normals(scene.features().shading_normals),
          normal_map(scene.features().normal_map),
          bump_map(scene.features().bump_map),
          perturbs_normals(normal_map || bump_map),
          mask(scene.features().mask),
          shading_normals(vertex_normals || perturbs_normals),
          uniform_hemisphere(scene.render.hemisphere == Hemisphere::Uniform),
          textures(scene.features().textures),
          anisotropic(scene.features().anisotropic_roughness),
          background(scene.background),
          environment_map(scene.features().environment_map) {
        camera = convert_camera(scene.camera);
        add_materials(scene);
        for (const Sphere& s : scene.spheres) spheres.push_back({vec3(s.center), Real(s.radius), s.material});
        for (const Plane& p : scene.planes) planes.push_back({vec3(p.point), vec3(p.normal), p.material});
        for (const Quad& q : scene.quads) quads.push_back({vec3(q.corner), vec3(q.edge1), vec3(q.edge2), q.material});
        add_meshes(scene, intersector);
        if (intersector == Intersector::Embree) add_embree(scene);
        add_lights(scene);
        add_textures(scene);
        EnvironmentLayout<Real> environment = wp::environment_layout<Real>(scene);
        environment_layout = environment.map;
        environment_data = std::move(environment.data);
        for (double c : scene.light_cdf) light_cdf.push_back(Real(c));
    }

 private:
    // The materials in Real, the plastics' constants and tables as the host
    // computes them in double (scene/plastic_constants.h), rounded as the
    // kernels' host rounds them (opencl/scene_upload.cpp).
    void add_materials(const Scene& scene) {
        PlasticTables plastics = plastic_tables(scene.materials, scene.textures);
        for (double t : plastics.transmittance) roughplastic_transmittance.push_back(Real(t));
        for (std::size_t i = 0; i < scene.materials.size(); ++i) {
            const Material& m = scene.materials[i];
            const PlasticConstants& c = plastics.materials[i];
            SurfaceMaterial s{};
            s.type = m.type;
            s.albedo = vec3(m.albedo);
            s.reflectance = vec3(m.reflectance);
            s.emission = vec3(m.emission);
            s.ior = Real(m.ior);
            s.two_sided = m.two_sided;
            s.eta = vec3(m.eta);
            s.k = vec3(m.k);
            s.specular_reflectance = vec3(m.specular_reflectance);
            s.microfacet = {microfacet_code(m), Real(m.alpha_u), Real(m.alpha_v)};
            s.bump_scale = Real(m.bump_scale);
            s.opacity = Real(m.opacity);
            s.one_sided = m.one_sided;
            s.plastic = {s.albedo,
                         s.specular_reflectance,
                         s.ior,
                         Real(c.inv_eta_2),
                         Real(c.internal_reflectance),  // fdr_int
                         Real(c.specular_sampling_weight),
                         m.nonlinear};
            s.roughplastic = {s.microfacet,
                              s.albedo,
                              s.specular_reflectance,
                              s.ior,
                              Real(c.inv_eta_2),
                              Real(c.specular_sampling_weight),
                              Real(c.internal_reflectance),
                              m.nonlinear,
                              c.transmittance_offset};
            materials.push_back(s);
        }
    }

    void add_embree(const Scene& scene) {
        if constexpr (std::is_same_v<Real, float>) {
            embree = std::make_shared<const EmbreeIntersector>(scene, triangles);
        } else {
            throw std::invalid_argument("the Embree intersector traces in float only");
        }
    }

    void add_lights(const Scene& scene) {
        MeshLightTriangles mesh_lights = mesh_light_triangles(scene);
        for (std::size_t i = 0; i < scene.lights.size(); ++i) {
            const MeshLightTriangles::Range& range = mesh_lights.ranges[i];
            const Light& light = scene.lights[i];
            LightRef ref{light.kind, light.shape, light.index, range.first, range.count, Real(range.area), vec3(0),
                         vec3(0),    vec3(0),     vec3(0),     Real(0),     Real(0),     Real(0),          Real(0)};
            if (light.kind == LightKind::Directional) {
                const DirectionalLight& directional = scene.directional_lights[std::size_t(light.index)];
                ref.to_light = vec3(-directional.direction);
                ref.emitted = vec3(directional.irradiance);
            }
            if (light.kind == LightKind::Point) {
                const PointLight& point = scene.point_lights[std::size_t(light.index)];
                const SpotFalloffTerms terms = spot_falloff_terms(point);
                ref.emitted = vec3(point.intensity);
                ref.position = vec3(point.position);
                ref.axis = vec3(terms.axis);
                ref.cos_cutoff = Real(terms.cos_cutoff);
                ref.cos_beam = Real(terms.cos_beam);
                ref.cutoff_angle = Real(terms.cutoff_angle);
                ref.inv_transition_width = Real(terms.inv_transition_width);
            }
            lights.push_back(ref);
        }
        for (std::size_t k = 0; k < mesh_lights.triangles.size(); ++k) {
            light_triangles.push_back(mesh_triangle<Real>(mesh_lights.triangles[k], mesh_lights.materials[k], 0));
            light_triangle_cdf.push_back(Real(mesh_lights.cdf[k]));
        }
    }

    // The texture table as the kernels' (texture_layout), each texture's fields as shared/texture.h reads them.
    void add_textures(const Scene& scene) {
        TextureLayout<Real> layout = texture_layout<Real>(scene);
        for (const auto& d : layout.descriptors) {
            typename M::Texture t{};
            t.type = d.type, t.filter = d.filter, t.wrap = d.wrap;
            t.width = d.width, t.height = d.height, t.first_texel = d.first_texel;
            for (int i = 0; i < 6; ++i) t.to_uv[i] = d.to_uv[i];
            t.color0 = vec3(d.color0[0], d.color0[1], d.color0[2]);
            t.color1 = vec3(d.color1[0], d.color1[1], d.color1[2]);
            texture_table.push_back(t);
        }
        texels = std::move(layout.texels);
        material_textures = std::move(layout.material_textures);
    }

    // The kernels' layout with the vertices in Real: with the BVH, the same
    // tree and leaf order; where Embree traces, no tree and the scene's order.
    void add_meshes(const Scene& scene, Intersector intersector) {
        MeshLayout<Real> meshes =
            mesh_layout<Real>(scene, {intersector == Intersector::Bvh, vertex_normals, textures || anisotropic});
        triangles = std::move(meshes.triangles);
        triangle_normals = std::move(meshes.normals);
        triangle_uvs = std::move(meshes.uvs);
        bvh_nodes = std::move(meshes.nodes);
    }

    static PinholeCamera convert_camera(const Camera& c) {
        auto frame = SharedMath<double>::camera_frame(c.position, c.look_at, c.up, c.tan_half_fov_y(), c.aspect());
        typename M::CameraFrame rounded{vec3(frame.right), vec3(frame.up), vec3(frame.forward),
                                        Real(frame.tan_half_fov_y), Real(frame.aspect)};
        return {vec3(c.position), rounded, c.width, c.height, pixel_filter_constants<Real>(c.filter)};
    }
};

}  // namespace wp::reference
