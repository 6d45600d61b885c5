#include "scene/scene_writer.h"

#include <algorithm>
#include <bit>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <set>
#include <stdexcept>
#include <type_traits>
#include <utility>

namespace wp {
namespace {

namespace fs = std::filesystem;

nlohmann::json vec3(const glm::dvec3& v) { return {v.x, v.y, v.z}; }

// A file as the JSON in `folder` names it: relative to the folder where one
// path leads to the other, else absolute.
std::string path_from(const fs::path& folder, const std::string& file) {
    const fs::path absolute = fs::absolute(file).lexically_normal();
    const fs::path relative = absolute.lexically_relative(folder);
    return (relative.empty() ? absolute : relative).generic_string();
}

// The materials' textures by the names the JSON gives them: the scene's, made
// unique (Mitsuba names a nested texture by its type) by a suffix " 2", " 3", ...
class TextureNames {
 public:
    explicit TextureNames(const std::vector<Texture>& textures) {
        std::set<std::string> taken;
        for (const Texture& t : textures) {
            std::string name = t.name;
            for (int n = 2; !taken.insert(name).second; ++n) name = t.name + " " + std::to_string(n);
            names_.push_back(name);
        }
    }
    const std::string& operator[](int texture) const { return names_[std::size_t(texture)]; }

 private:
    std::vector<std::string> names_;
};

// A texture's JSON; `file` is the bitmap's image as the JSON names it.
nlohmann::json texture_json(const Texture& t, const std::string& file) {
    nlohmann::json j;
    if (t.type == TextureType::Bitmap) {
        j = {{"type", "bitmap"},
             {"file", file},
             {"filter_type", t.filter == TextureFilter::Nearest ? "nearest" : "bilinear"},
             {"wrap_mode", t.wrap == TextureWrap::Mirror  ? "mirror"
                           : t.wrap == TextureWrap::Clamp ? "clamp"
                                                          : "repeat"},
             {"raw", t.raw}};
    } else {
        j = {{"type", "checkerboard"}, {"color0", vec3(t.color0)}, {"color1", vec3(t.color1)}};
    }
    const std::array<double, 6>& m = t.to_uv;
    j["to_uv"] = {{m[0], m[1], m[2]}, {m[3], m[4], m[5]}};
    return j;
}

// A material's parameter: its texture's name, or its constant.
template <typename Constant>
nlohmann::json parameter_json(const Material& m, TexturedParameter p, const Constant& constant,
                              const TextureNames& textures) {
    if (m.texture(p) != kNoTexture) return {{"texture", textures[m.texture(p)]}};
    if constexpr (std::is_same_v<Constant, glm::dvec3>)
        return vec3(constant);
    else
        return constant;
}

// plastic and roughplastic, their relative index as int_ior over an ext_ior of 1.
nlohmann::json plastic_json(const Material& m, const TextureNames& textures) {
    nlohmann::json j = {{"type", m.type == MaterialType::Plastic ? "plastic" : "roughplastic"},
                        {"diffuse_reflectance", parameter_json(m, TexturedParameter::Albedo, m.albedo, textures)},
                        {"specular_reflectance",
                         parameter_json(m, TexturedParameter::SpecularReflectance, m.specular_reflectance, textures)},
                        {"int_ior", m.ior},
                        {"ext_ior", 1.0},
                        {"nonlinear", m.nonlinear}};
    if (m.type == MaterialType::RoughPlastic) {
        j["distribution"] = m.distribution == Microfacet::GGX ? "ggx" : "beckmann";
        j["alpha"] = m.alpha_u;
    }
    return j;
}

// A microfacet distribution and its roughness along each tangent.
void add_microfacet(nlohmann::json& j, const Material& m, const TextureNames& textures) {
    j["distribution"] = m.distribution == Microfacet::GGX ? "ggx" : "beckmann";
    j["alpha_u"] = parameter_json(m, TexturedParameter::AlphaU, m.alpha_u, textures);
    j["alpha_v"] = parameter_json(m, TexturedParameter::AlphaV, m.alpha_v, textures);
}

// conductor and roughconductor: the complex index per channel.
nlohmann::json conductor_json(const Material& m, const TextureNames& textures) {
    nlohmann::json j = {{"type", m.type == MaterialType::Conductor ? "conductor" : "roughconductor"},
                        {"eta", vec3(m.eta)},
                        {"k", vec3(m.k)},
                        {"specular_reflectance",
                         parameter_json(m, TexturedParameter::SpecularReflectance, m.specular_reflectance, textures)}};
    if (m.type == MaterialType::RoughConductor) add_microfacet(j, m, textures);
    return j;
}

// roughdielectric and thindielectric, their relative index as int_ior over an ext_ior of 1.
nlohmann::json dielectric_json(const Material& m, const TextureNames& textures) {
    nlohmann::json j = {{"type", m.type == MaterialType::RoughDielectric ? "roughdielectric" : "thindielectric"},
                        {"int_ior", m.ior},
                        {"ext_ior", 1.0}};
    if (m.type == MaterialType::RoughDielectric) add_microfacet(j, m, textures);
    return j;
}

// A normalmap, bumpmap or mask around the nested material's JSON, or that JSON as it is.
nlohmann::json adapted_json(const Material& m, nlohmann::json nested, const TextureNames& textures) {
    if (m.masked())
        return {{"type", "mask"},
                {"opacity", parameter_json(m, TexturedParameter::Opacity, m.opacity, textures)},
                {"bsdf", std::move(nested)}};
    if (m.texture(TexturedParameter::NormalMap) != kNoTexture)
        return {{"type", "normalmap"},
                {"normalmap", parameter_json(m, TexturedParameter::NormalMap, 0.0, textures)},
                {"bsdf", std::move(nested)}};
    if (m.texture(TexturedParameter::BumpMap) != kNoTexture)
        return {{"type", "bumpmap"},
                {"bumpmap", parameter_json(m, TexturedParameter::BumpMap, 0.0, textures)},
                {"scale", m.bump_scale},
                {"bsdf", std::move(nested)}};
    return nested;
}

nlohmann::json material_json(const Material& m, const TextureNames& textures) {
    nlohmann::json j;
    switch (m.type) {
        case MaterialType::Diffuse:
            j = {{"type", "diffuse"}, {"albedo", parameter_json(m, TexturedParameter::Albedo, m.albedo, textures)}};
            if (m.emits()) j["emission"] = vec3(m.emission);
            break;
        case MaterialType::Mirror:
            j = {{"type", "mirror"}, {"reflectance", vec3(m.reflectance)}};
            break;
        case MaterialType::Glass:
            j = {{"type", "glass"}, {"ior", m.ior}};
            break;
        case MaterialType::Emitter:
            j = {{"type", "emitter"}, {"radiance", vec3(m.emission)}};
            break;
        case MaterialType::Conductor:
        case MaterialType::RoughConductor:
            j = conductor_json(m, textures);
            break;
        case MaterialType::RoughDielectric:
        case MaterialType::ThinDielectric:
            j = dielectric_json(m, textures);
            break;
        case MaterialType::Plastic:
        case MaterialType::RoughPlastic:
            j = plastic_json(m, textures);
            break;
    }
    if (m.two_sided) j["two_sided"] = true;
    if (m.one_sided) j["one_sided"] = true;
    return adapted_json(m, std::move(j), textures);
}

nlohmann::json matrix_json(const glm::dmat4& m) {
    nlohmann::json rows = nlohmann::json::array();
    for (int row = 0; row < 4; ++row) rows.push_back({m[0][row], m[1][row], m[2][row], m[3][row]});
    return rows;
}

void append_le(std::string& out, std::uint32_t value) {
    for (int i = 0; i < 4; ++i) out += char((value >> (8 * i)) & 0xff);
}

// The envmap light, its file named from the JSON's folder and its frame as a matrix.
nlohmann::json envmap_json(const EnvironmentMap& map, const fs::path& folder) {
    nlohmann::json matrix = nlohmann::json::array();
    for (int row = 0; row < 4; ++row) {
        nlohmann::json numbers = nlohmann::json::array();
        for (int column = 0; column < 4; ++column)
            numbers.push_back(row < 3 && column < 3 ? map.to_world[column][row] : double(row == column));
        matrix.push_back(numbers);
    }
    return {{"type", "envmap"},
            {"filename", path_from(folder, map.path)},
            {"scale", map.scale},
            {"to_world", {{"matrix", matrix}}}};
}

// A point light, or a spot with its cone.
nlohmann::json point_light_json(const PointLight& light) {
    nlohmann::json j = {{"type", light.cone ? "spot" : "point"},
                        {"position", vec3(light.position)},
                        {"intensity", vec3(light.intensity)}};
    if (light.cone) {
        j["direction"] = vec3(light.cone->axis);
        j["cutoff_angle"] = light.cone->cutoff_angle;
        j["beam_width"] = light.cone->beam_width;
    }
    return j;
}

// The image file texture `t`'s JSON names (none for a checkerboard): the one it was read from, or, for an image
// embedded in the scene file or a texture computed from one, a file beside the JSON that `out` lists to write.
std::string texture_file(const MitsubaScene& read, std::size_t t, const fs::path& json_path, SceneJson& out) {
    if (read.scene.textures[t].type != TextureType::Bitmap) return {};
    const std::string stem = json_path.stem().string();
    const auto embedded = std::find_if(read.embedded_images.begin(), read.embedded_images.end(),
                                       [&](const EmbeddedImage& image) { return image.texture == t; });
    if (embedded != read.embedded_images.end()) {
        const std::string file = stem + "_image" + std::to_string(out.images.size()) + "." + embedded->format;
        out.images.push_back({json_path.parent_path() / file, &embedded->bytes});
        return file;
    }
    if (std::find(read.computed_textures.begin(), read.computed_textures.end(), t) != read.computed_textures.end()) {
        const std::string file = stem + "_texture" + std::to_string(out.computed.size()) + ".exr";
        out.computed.push_back({json_path.parent_path() / file, &read.scene.textures[t]});
        return file;
    }
    return path_from(fs::absolute(json_path).parent_path(), read.scene.textures[t].path);
}

}  // namespace

SceneJson scene_json(const MitsubaScene& read, const fs::path& json_path) {
    const Scene& scene = read.scene;
    const fs::path folder = fs::absolute(json_path).parent_path();
    SceneJson out;
    nlohmann::json& j = out.json;
    const Camera& c = scene.camera;
    j["camera"] = {{"position", vec3(c.position)}, {"look_at", vec3(c.look_at)}, {"up", vec3(c.up)},
                   {"fov_y", c.fov_y_degrees},     {"width", c.width},           {"height", c.height}};
    if (c.filter.type == FilterType::Tent) j["camera"]["filter"] = {{"type", "tent"}, {"radius", c.filter.radius}};
    if (c.filter.type == FilterType::Gaussian) {
        j["camera"]["filter"] = {{"type", "gaussian"}, {"stddev", c.filter.stddev}};
    }
    const RenderSettings& r = scene.render;
    j["render"] = {{"spp", r.spp}, {"max_depth", r.max_depth}, {"rr_depth", r.rr_depth}, {"seed", r.seed}};
    j["background"] = vec3(scene.background);
    if (!scene.directional_lights.empty() || !scene.point_lights.empty() || scene.environment_map) {
        nlohmann::json& lights = j["lights"] = nlohmann::json::array();
        for (const DirectionalLight& d : scene.directional_lights)
            lights.push_back(
                {{"type", "directional"}, {"direction", vec3(d.direction)}, {"irradiance", vec3(d.irradiance)}});
        for (const PointLight& p : scene.point_lights) lights.push_back(point_light_json(p));
        if (const auto& map = scene.environment_map) lights.push_back(envmap_json(*map, folder));
    }
    const TextureNames texture_names(scene.textures);
    if (!scene.textures.empty()) {
        nlohmann::json& textures = j["textures"] = nlohmann::json::object();
        for (std::size_t t = 0; t < scene.textures.size(); ++t)
            textures[texture_names[int(t)]] = texture_json(scene.textures[t], texture_file(read, t, json_path, out));
    }
    j["materials"] = nlohmann::json::object();
    for (const Material& m : scene.materials) j["materials"][m.name] = material_json(m, texture_names);
    nlohmann::json& shapes = j["shapes"] = nlohmann::json::array();
    const auto material = [&](int index) { return scene.materials[std::size_t(index)].name; };
    for (const Sphere& s : scene.spheres)
        shapes.push_back(
            {{"type", "sphere"}, {"center", vec3(s.center)}, {"radius", s.radius}, {"material", material(s.material)}});
    for (const Quad& q : scene.quads)
        shapes.push_back({{"type", "quad"},
                          {"corner", vec3(q.corner)},
                          {"edge1", vec3(q.edge1)},
                          {"edge2", vec3(q.edge2)},
                          {"material", material(q.material)}});
    for (std::size_t i = 0; i < scene.meshes.size(); ++i) {
        const MeshOrigin& origin = read.meshes[i];
        nlohmann::json mesh = {{"type", "mesh"}, {"material", material(scene.meshes[i].material)}};
        if (origin.as_file) {
            mesh["file"] = path_from(folder, origin.file);
        } else {
            const fs::path file = json_path.parent_path() /
                                  (json_path.stem().string() + "_mesh" + std::to_string(out.meshes.size()) + ".ply");
            out.meshes.push_back({file, &origin.local});
            mesh["file"] = file.filename().string();
        }
        if (origin.to_world != glm::dmat4(1.0)) mesh["transform"] = {{"matrix", matrix_json(origin.to_world)}};
        if (origin.face_normals) mesh["face_normals"] = true;
        shapes.push_back(mesh);
    }
    return out;
}

void write_ply(const fs::path& path, const ImportedMesh& mesh) {
    std::string bytes = "ply\nformat binary_little_endian 1.0\nelement vertex " +
                        std::to_string(mesh.positions.size()) +
                        "\nproperty float x\nproperty float y\nproperty float z\n";
    if (mesh.has_normals) bytes += "property float nx\nproperty float ny\nproperty float nz\n";
    if (mesh.has_uvs) bytes += "property float u\nproperty float v\n";
    bytes += "element face " + std::to_string(mesh.triangles.size()) +
             "\nproperty list uchar int vertex_indices\nend_header\n";
    for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
        for (int k = 0; k < 3; ++k) append_le(bytes, std::bit_cast<std::uint32_t>(mesh.positions[v][k]));
        if (mesh.has_normals)
            for (int k = 0; k < 3; ++k) append_le(bytes, std::bit_cast<std::uint32_t>(mesh.normals[v][k]));
        if (mesh.has_uvs)
            for (int k = 0; k < 2; ++k) append_le(bytes, std::bit_cast<std::uint32_t>(mesh.uvs[v][k]));
    }
    for (const glm::uvec3& t : mesh.triangles) {
        bytes += char(3);
        for (int k = 0; k < 3; ++k) append_le(bytes, t[k]);
    }
    std::ofstream file(path, std::ios::binary);
    file.write(bytes.data(), std::streamsize(bytes.size()));
    file.close();
    if (!file) throw std::runtime_error(path.string() + ": cannot write: " + std::strerror(errno));
}

}  // namespace wp
