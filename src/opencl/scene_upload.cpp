#include "opencl/scene_upload.h"

#include <algorithm>
#include <chrono>
#include <sstream>

#include "accel/bvh_layout.h"
#include "core/shared_math.h"
#include "scene/environment_layout.h"
#include "scene/mesh_lights.h"
#include "scene/microfacet_code.h"
#include "scene/pixel_filter.h"
#include "scene/plastic_constants.h"
#include "scene/texture_layout.h"

namespace wp {
namespace {
using namespace device_layout;

static_assert(sizeof(SceneHeader) == 43 * 4, "SceneHeader must match its OpenCL C layout");
static_assert(sizeof(DeviceSphere) == 5 * 4, "DeviceSphere must match its OpenCL C layout");
static_assert(sizeof(DevicePlane) == 7 * 4, "DevicePlane must match its OpenCL C layout");
static_assert(sizeof(DeviceQuad) == 16 * 4, "DeviceQuad must match its OpenCL C layout");
static_assert(sizeof(DeviceMaterial) == 32 * 4, "DeviceMaterial must match its OpenCL C layout");
static_assert(sizeof(DeviceLight) == 20 * 4, "DeviceLight must match its OpenCL C layout");
static_assert(sizeof(MaterialTextures) == WP_TEXTURED_PARAMETERS * 4,
              "MaterialTextures must match its OpenCL C layout");
static_assert(WP_TEXTURED_PARAMETERS == kTexturedParameters &&
                  WP_TEXTURED_ALBEDO == static_cast<int>(TexturedParameter::Albedo) &&
                  WP_TEXTURED_SPECULAR_REFLECTANCE == static_cast<int>(TexturedParameter::SpecularReflectance) &&
                  WP_TEXTURED_ALPHA_U == static_cast<int>(TexturedParameter::AlphaU) &&
                  WP_TEXTURED_ALPHA_V == static_cast<int>(TexturedParameter::AlphaV) &&
                  WP_TEXTURED_NORMAL_MAP == static_cast<int>(TexturedParameter::NormalMap) &&
                  WP_TEXTURED_BUMP_MAP == static_cast<int>(TexturedParameter::BumpMap) &&
                  WP_TEXTURED_OPACITY == static_cast<int>(TexturedParameter::Opacity),
              "the kernels' WP_TEXTURED_* must be TexturedParameter's");
static_assert(sizeof(SharedMath<float>::TextureDescriptor) == 18 * 4,
              "TextureDescriptor must match its OpenCL C layout");
static_assert(sizeof(SharedMath<float>::TriangleUVs) == 6 * 4, "TriangleUVs must match its OpenCL C layout");
static_assert(sizeof(SharedMath<float>::MeshTriangle) == 11 * 4, "MeshTriangle must match its OpenCL C layout");
static_assert(sizeof(SharedMath<float>::BvhNode) == 64, "BvhNode must match its OpenCL C layout");

void put(float (&out)[3], const glm::dvec3& v) {
    out[0] = static_cast<float>(v.x);
    out[1] = static_cast<float>(v.y);
    out[2] = static_cast<float>(v.z);
}

void put(SceneHeader& h, const SharedMath<float>::PixelFilter& filter) {
    h.filter_type = filter.type;
    h.filter_radius = filter.radius;
    h.filter_scale = filter.scale;
    h.filter_erf_radius = filter.erf_radius;
}

std::uint32_t shape_ref(std::uint32_t type, int index) { return (type << WP_SHAPE_TYPE_SHIFT) | std::uint32_t(index); }

SceneHeader make_header(const Scene& scene) {
    SceneHeader h{};
    const Camera& c = scene.camera;
    auto frame = SharedMath<double>::camera_frame(c.position, c.look_at, c.up, c.tan_half_fov_y(), c.aspect());
    put(h.camera_right, frame.right);
    put(h.camera_up, frame.up);
    put(h.camera_forward, frame.forward);
    h.tan_half_fov_y = static_cast<float>(frame.tan_half_fov_y);
    h.aspect = static_cast<float>(frame.aspect);
    put(h.background, scene.background);
    put(h, pixel_filter_constants<float>(c.filter));
    h.width = c.width;
    h.height = c.height;
    h.spp = scene.render.spp;
    h.max_depth = scene.render.max_depth;
    h.rr_depth = scene.render.rr_depth;
    h.seed = scene.render.seed;
    h.sphere_count = scene.spheres.size();
    h.plane_count = scene.planes.size();
    h.quad_count = scene.quads.size();
    h.light_count = scene.lights.size();
    if (scene.render.integrator == Integrator::Sppm) {
        h.photons = static_cast<std::uint32_t>(sppm_photons(scene));
        h.sppm_alpha = static_cast<float>(scene.render.sppm.alpha);
        h.sppm_radius = static_cast<float>(scene.render.sppm.radius);
        h.sppm_pixel_spread = static_cast<float>(sppm_pixel_spread(scene));
    }
    return h;
}

std::uint32_t material_type(MaterialType type) {
    switch (type) {
        case MaterialType::Diffuse:
            return WP_MATERIAL_DIFFUSE;
        case MaterialType::Mirror:
            return WP_MATERIAL_MIRROR;
        case MaterialType::Glass:
            return WP_MATERIAL_GLASS;
        case MaterialType::Emitter:
            return WP_MATERIAL_EMITTER;
        case MaterialType::Conductor:
            return WP_MATERIAL_CONDUCTOR;
        case MaterialType::RoughConductor:
            return WP_MATERIAL_ROUGH_CONDUCTOR;
        case MaterialType::RoughDielectric:
            return WP_MATERIAL_ROUGH_DIELECTRIC;
        case MaterialType::ThinDielectric:
            return WP_MATERIAL_THIN_DIELECTRIC;
        case MaterialType::Plastic:
            return WP_MATERIAL_PLASTIC;
        case MaterialType::RoughPlastic:
            return WP_MATERIAL_ROUGH_PLASTIC;
    }
    return WP_MATERIAL_DIFFUSE;
}

// The items copied into a new buffer (no copy of the vector on the way: a
// mesh's triangles are the scene's largest).
template <class T>
cl::Buffer upload(const cl::Context& context, const std::vector<T>& items) {
    const T none{};
    return cl::Buffer(context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR,
                      sizeof(T) * std::max<std::size_t>(items.size(), 1),
                      const_cast<T*>(items.empty() ? &none : items.data()));
}

// The meshes' triangles and, where the kernels trace, the BVH's nodes, as the kernels read them.
void flatten_meshes(const Scene& scene, Intersector intersector, SceneLayout& layout) {
    auto start = std::chrono::steady_clock::now();
    MeshLayout<float> meshes = mesh_layout<float>(
        scene, {intersector == Intersector::Bvh, scene.features().shading_normals, scene.features().triangle_uvs()});
    layout.triangles = std::move(meshes.triangles);
    layout.triangle_normals = std::move(meshes.normals);
    layout.triangle_uvs = std::move(meshes.uvs);
    layout.bvh_nodes = std::move(meshes.nodes);
    MeshSummary& summary = layout.meshes;
    summary.meshes = scene.meshes.size();
    summary.triangles = layout.triangles.size();
    for (const Mesh& mesh : scene.meshes) summary.degenerate_dropped += mesh.degenerate_dropped;
    summary.bvh_nodes = layout.bvh_nodes.size();
    summary.bvh_depth = meshes.depth;
    summary.layout_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// The texture table, the texels and the materials' textured parameters.
void add_textures(const Scene& scene, SceneLayout& layout) {
    TextureLayout<float> textures = texture_layout<float>(scene);
    for (const auto& slots : textures.material_textures) {
        MaterialTextures m{};
        std::copy(slots.begin(), slots.end(), m.texture);
        layout.material_textures.push_back(m);
    }
    layout.textures = std::move(textures.descriptors);
    layout.texels = std::move(textures.texels);
    const std::size_t bytes = layout.textures.size() * sizeof(layout.textures[0]) +
                              layout.texels.size() * sizeof(float) +
                              layout.triangle_uvs.size() * sizeof(SharedMath<float>::TriangleUVs);
    layout.textures_summary = describe_textures(scene, bytes);
}

// The environment map's data, its size and frame in the header.
void add_environment_map(const Scene& scene, SceneLayout& layout) {
    EnvironmentLayout<float> environment = environment_layout<float>(scene);
    layout.header.environment_width = environment.map.width;
    layout.header.environment_height = environment.map.height;
    for (int i = 0; i < 9; ++i) layout.header.environment_to_world[i] = environment.map.to_world[i];
    layout.environment = std::move(environment.data);
}

}  // namespace

std::string describe_textures(const Scene& scene, std::size_t device_bytes) {
    if (scene.textures.empty()) return "";
    std::size_t bitmaps = 0, texels = 0;
    for (const Texture& t : scene.textures) {
        bitmaps += t.type == TextureType::Bitmap;
        texels += t.texels.size() / 3;
    }
    std::ostringstream out;
    out << scene.textures.size() << (scene.textures.size() == 1 ? " texture (" : " textures (") << bitmaps
        << (bitmaps == 1 ? " bitmap, " : " bitmaps, ") << scene.textures.size() - bitmaps << " checkerboard), "
        << texels << " texels, " << (device_bytes + 1023) / 1024 << " KiB of device memory";
    return out.str();
}

SceneLayout flatten_scene(const Scene& scene, Intersector intersector) {
    SceneLayout layout;
    layout.header = make_header(scene);
    flatten_meshes(scene, intersector, layout);
    for (const Sphere& s : scene.spheres) {
        DeviceSphere d{};
        put(d.center, s.center);
        d.radius = static_cast<float>(s.radius);
        d.material = s.material;
        layout.spheres.push_back(d);
    }
    for (const Plane& p : scene.planes) {
        DevicePlane d{};
        put(d.point, p.point);
        put(d.normal, p.normal);
        d.material = p.material;
        layout.planes.push_back(d);
    }
    for (const Quad& q : scene.quads) {
        DeviceQuad d{};
        put(d.corner, q.corner);
        put(d.edge1, q.edge1);
        put(d.edge2, q.edge2);
        // In float, from the float edges, exactly as a kernel would compute it.
        using M = SharedMath<float>;
        M::QuadPlane plane = M::quad_plane(glm::vec3(glm::dvec3(q.edge1)), glm::vec3(glm::dvec3(q.edge2)));
        put(d.plane_normal, glm::dvec3(plane.normal));
        put(d.plane_w, glm::dvec3(plane.w));
        d.material = q.material;
        layout.quads.push_back(d);
    }
    PlasticTables plastics = plastic_tables(scene.materials, scene.textures);
    for (double t : plastics.transmittance) layout.roughplastic_transmittance.push_back(static_cast<float>(t));
    for (std::size_t i = 0; i < scene.materials.size(); ++i) {
        const Material& m = scene.materials[i];
        const PlasticConstants& plastic = plastics.materials[i];
        DeviceMaterial d{};
        put(d.albedo, m.albedo);
        put(d.reflectance, m.reflectance);
        put(d.emission, m.emission);
        d.ior = static_cast<float>(m.ior);
        d.type = material_type(m.type);
        d.two_sided = m.two_sided ? 1u : 0u;
        put(d.eta, m.eta);
        put(d.k, m.k);
        put(d.specular_reflectance, m.specular_reflectance);
        d.distribution = microfacet_code(m);
        d.alpha_u = static_cast<float>(m.alpha_u);
        d.alpha_v = static_cast<float>(m.alpha_v);
        d.inv_eta_2 = static_cast<float>(plastic.inv_eta_2);
        d.internal_reflectance = static_cast<float>(plastic.internal_reflectance);
        d.specular_sampling_weight = static_cast<float>(plastic.specular_sampling_weight);
        d.nonlinear = m.nonlinear ? 1u : 0u;
        d.transmittance_offset = plastic.transmittance_offset;
        d.bump_scale = static_cast<float>(m.bump_scale);
        d.opacity = static_cast<float>(m.opacity);
        d.one_sided = m.one_sided ? 1u : 0u;
        layout.materials.push_back(d);
    }
    add_textures(scene, layout);
    add_environment_map(scene, layout);
    MeshLightTriangles mesh_lights = mesh_light_triangles(scene);
    for (std::size_t i = 0; i < scene.lights.size(); ++i) {
        const Light& light = scene.lights[i];
        const MeshLightTriangles::Range& range = mesh_lights.ranges[i];
        DeviceLight d{};
        if (light.kind == LightKind::Environment) {
            d.shape = shape_ref(WP_LIGHT_ENVIRONMENT, 0);
            layout.lights.push_back(d);
            continue;
        }
        if (light.kind == LightKind::Directional) {
            const DirectionalLight& directional = scene.directional_lights[std::size_t(light.index)];
            d.shape = shape_ref(WP_LIGHT_DIRECTIONAL, 0);
            put(d.to_light, -directional.direction);
            put(d.emitted, directional.irradiance);
            layout.lights.push_back(d);
            continue;
        }
        if (light.kind == LightKind::Point) {
            const PointLight& point = scene.point_lights[std::size_t(light.index)];
            const SpotFalloffTerms terms = spot_falloff_terms(point);
            d.shape = shape_ref(WP_LIGHT_POINT, 0);
            put(d.emitted, point.intensity);
            put(d.position, point.position);
            put(d.axis, terms.axis);
            d.cos_cutoff = static_cast<float>(terms.cos_cutoff);
            d.cos_beam = static_cast<float>(terms.cos_beam);
            d.cutoff_angle = static_cast<float>(terms.cutoff_angle);
            d.inv_transition_width = static_cast<float>(terms.inv_transition_width);
            layout.lights.push_back(d);
            continue;
        }
        switch (light.shape) {
            case ShapeType::Sphere:
                d.shape = shape_ref(WP_SHAPE_SPHERE, light.index);
                break;
            case ShapeType::Mesh:
                d.shape = shape_ref(WP_SHAPE_TRIANGLE, int(range.first));
                d.triangle_count = range.count;
                d.area = static_cast<float>(range.area);
                d.mesh = static_cast<std::uint32_t>(light.index);
                break;
            default:
                d.shape = shape_ref(WP_SHAPE_QUAD, light.index);
        }
        layout.lights.push_back(d);
    }
    for (std::size_t k = 0; k < mesh_lights.triangles.size(); ++k) {
        layout.light_triangles.push_back(mesh_triangle<float>(mesh_lights.triangles[k], mesh_lights.materials[k], 0));
        layout.light_triangle_cdf.push_back(static_cast<float>(mesh_lights.cdf[k]));
    }
    for (double c : scene.light_cdf) layout.light_cdf.push_back(static_cast<float>(c));
    return layout;
}

std::string MeshSummary::describe() const {
    if (meshes == 0) return "";
    std::ostringstream out;
    out << meshes << (meshes == 1 ? " mesh, " : " meshes, ") << triangles << " triangles (" << degenerate_dropped
        << " degenerate dropped); ";
    if (bvh_nodes == 0)
        out << "no BVH (the host traces), laid out in " << layout_seconds << " s";
    else
        out << "BVH of " << bvh_nodes << " nodes, depth " << bvh_depth << ", built in " << layout_seconds << " s";
    return out.str();
}

DeviceScene::DeviceScene(const cl::Context& context, const SceneLayout& layout,
                         std::span<const std::byte> host_triangles)
    : meshes_(layout.meshes), textures_(layout.textures_summary) {
    buffers_[arg::Scene::scene] = upload(context, std::vector<SceneHeader>{layout.header});
    buffers_[arg::Scene::spheres] = upload(context, layout.spheres);
    buffers_[arg::Scene::planes] = upload(context, layout.planes);
    buffers_[arg::Scene::quads] = upload(context, layout.quads);
    buffers_[arg::Scene::triangles] =
        host_triangles.empty() ? upload(context, layout.triangles)
                               : cl::Buffer(context, CL_MEM_READ_ONLY | CL_MEM_USE_HOST_PTR, host_triangles.size(),
                                            const_cast<std::byte*>(host_triangles.data()));
    buffers_[arg::Scene::triangle_normals] = upload(context, layout.triangle_normals);
    buffers_[arg::Scene::bvh_nodes] = upload(context, layout.bvh_nodes);
    buffers_[arg::Scene::materials] = upload(context, layout.materials);
    buffers_[arg::Scene::lights] = upload(context, layout.lights);
    buffers_[arg::Scene::light_cdf] = upload(context, layout.light_cdf);
    buffers_[arg::Scene::light_triangles] = upload(context, layout.light_triangles);
    buffers_[arg::Scene::light_triangle_cdf] = upload(context, layout.light_triangle_cdf);
    buffers_[arg::Scene::roughplastic_transmittance] = upload(context, layout.roughplastic_transmittance);
    buffers_[arg::Scene::material_textures] = upload(context, layout.material_textures);
    buffers_[arg::Scene::textures] = upload(context, layout.textures);
    buffers_[arg::Scene::texels] = upload(context, layout.texels);
    buffers_[arg::Scene::triangle_uvs] = upload(context, layout.triangle_uvs);
    buffers_[arg::Scene::environment_map] = upload(context, layout.environment);
}

void DeviceScene::bind(cl::Kernel& kernel) const {
    for (cl_uint index = 0; index < buffers_.size(); ++index) kernel.setArg(index, buffers_[index]);
}

}  // namespace wp
