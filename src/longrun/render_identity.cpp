#include "longrun/render_identity.h"

#include <type_traits>

#include "core/shared_math.h"

namespace wp {

std::uint64_t fnv1a64(const void* data, std::size_t size, std::uint64_t hash) {
    const auto* bytes = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < size; ++i) {
        hash ^= bytes[i];
        hash *= 0x100000001b3ull;
    }
    return hash;
}

namespace {

// Feeds values to FNV-1a 64 by their bytes (the host's, little-endian here;
// film files are read back on the same kind of host).
class Hasher {
 public:
    template <class T>
    Hasher& add(const T& value) {
        static_assert(std::is_arithmetic_v<T> || std::is_enum_v<T>);
        hash_ = fnv1a64(&value, sizeof value, hash_);
        return *this;
    }
    Hasher& add(const glm::dvec3& v) { return add(v.x).add(v.y).add(v.z); }
    Hasher& add(const glm::uvec3& v) { return add(v.x).add(v.y).add(v.z); }
    Hasher& add(const glm::dvec2& v) { return add(v.x).add(v.y); }
    template <class T>
    Hasher& add_all(const std::vector<T>& values) {
        add(values.size());
        for (const T& v : values) add(v);
        return *this;
    }
    std::uint64_t value() const { return hash_; }

 private:
    std::uint64_t hash_ = kFnvOffset;
};

void add_material(Hasher& h, const Material& m) {
    h.add(m.type).add(m.albedo).add(m.reflectance).add(m.ior).add(m.emission).add(m.two_sided);
    // The newer materials' parameters, theirs alone: the older materials
    // hash as they did before, so their checkpoints stay valid.
    const bool plastic = m.type == MaterialType::Plastic || m.type == MaterialType::RoughPlastic;
    if (m.type == MaterialType::Conductor || m.type == MaterialType::RoughConductor) {
        h.add(m.eta).add(m.k).add(m.specular_reflectance);
    }
    if (plastic) h.add(m.specular_reflectance).add(m.nonlinear);
    if (m.rough()) {
        h.add(m.distribution).add(m.alpha_u).add(m.alpha_v);
    }
    // A textured albedo hashes its index alone, as before the other parameters could be textured.
    if (m.texture(TexturedParameter::Albedo) != kNoTexture) h.add(m.texture(TexturedParameter::Albedo));
    for (std::size_t p = 1; p < kTexturedParameters; ++p)
        if (m.textures[p] != kNoTexture) h.add(p).add(m.textures[p]);
    // The adapters' constants, where the material is one.
    if (m.texture(TexturedParameter::BumpMap) != kNoTexture) h.add(m.bump_scale);
    if (m.masked()) h.add(m.opacity);
    if (m.one_sided) h.add(m.one_sided);
}

// A texture by what it holds (its texels, not its file's name or date).
void add_texture(Hasher& h, const Texture& t) {
    h.add(t.type).add(t.width).add(t.height).add_all(t.texels).add(t.filter).add(t.wrap).add(t.color0).add(t.color1);
    for (double m : t.to_uv) h.add(m);
}

std::uint64_t scene_hash(const Scene& scene) {
    Hasher h;
    const Camera& c = scene.camera;
    h.add(c.position).add(c.look_at).add(c.up).add(c.fov_y_degrees).add(c.width).add(c.height);
    // Only a filter other than the box is hashed: films from before filters keep their hash.
    if (c.filter.type != FilterType::Box) h.add(c.filter.type).add(c.filter.radius).add(c.filter.stddev);
    h.add(scene.background);
    if (!scene.textures.empty()) {  // scenes without textures hash as before
        h.add(scene.textures.size());
        for (const Texture& t : scene.textures) add_texture(h, t);
    }
    h.add(scene.materials.size());
    for (const Material& m : scene.materials) add_material(h, m);
    h.add(scene.spheres.size());
    for (const Sphere& s : scene.spheres) h.add(s.center).add(s.radius).add(s.material);
    h.add(scene.planes.size());
    for (const Plane& p : scene.planes) h.add(p.point).add(p.normal).add(p.material);
    h.add(scene.quads.size());
    for (const Quad& q : scene.quads) h.add(q.corner).add(q.edge1).add(q.edge2).add(q.material);
    h.add(scene.meshes.size());
    for (const Mesh& m : scene.meshes) {
        h.add_all(m.positions).add_all(m.normals).add_all(m.triangles).add(m.material);
        if (!m.uvs.empty()) h.add_all(m.uvs);  // meshes without uvs hash as before
    }
    if (!scene.directional_lights.empty()) {  // only where present: films of scenes without them keep their hash
        h.add(scene.directional_lights.size());
        for (const DirectionalLight& d : scene.directional_lights) h.add(d.direction).add(d.irradiance);
    }
    if (!scene.point_lights.empty()) {  // as the directional lights
        h.add(scene.point_lights.size());
        for (const PointLight& p : scene.point_lights) {
            h.add(p.position).add(p.intensity).add(p.cone.has_value());
            if (p.cone) h.add(p.cone->axis).add(p.cone->cutoff_angle).add(p.cone->beam_width);
        }
    }
    if (const auto& map = scene.environment_map) {  // by what it holds, not its file's name; only where present
        h.add(map->width).add(map->height).add_all(map->texels).add(map->scale);
        for (int column = 0; column < 3; ++column) h.add(map->to_world[column]);
    }
    return h.value();
}

// Adaptive sampling and SPPM are hashed only when on, so that films without
// them keep the hash they had before they existed. SPPM's photons per
// iteration as they resolve, and its first radii's rule: the override (0:
// none) and the footprints a pixel's first radius spans without one
// (sppm_first_radius; the footprint itself follows from the camera, which
// the scene's hash holds). A film made under an earlier default (version 3:
// one radius for every pixel, from the scene's extent) hashes otherwise.
std::uint64_t settings_hash(const Scene& scene, const AdaptiveSampling& adaptive) {
    const RenderSettings& r = scene.render;
    Hasher h;
    h.add(r.max_depth).add(r.rr_depth).add(r.seed).add(r.nee).add(r.mis).add(r.hemisphere).add(r.sampler);
    if (adaptive.on()) h.add(adaptive.threshold).add(adaptive.min_spp);
    if (r.integrator == Integrator::Sppm)
        h.add(r.integrator)
            .add(sppm_photons(scene))
            .add(r.sppm.radius)
            .add(SharedMath<double>::sppm_first_radius(0.0, 1.0))
            .add(r.sppm.alpha);
    return h.value();
}

}  // namespace

RenderIdentity render_identity(const Scene& scene, const std::string& estimator, const AdaptiveSampling& adaptive) {
    return {scene_hash(scene), settings_hash(scene, adaptive), estimator};
}

}  // namespace wp
