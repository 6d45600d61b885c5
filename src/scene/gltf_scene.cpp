#include "scene/gltf_scene.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>
#include <glm/trigonometric.hpp>
#include <limits>
#include <map>
#include <numbers>
#include <set>
#include <stdexcept>
#include <tuple>
#include <utility>

#include "core/number_text.h"
#include "import/import_process.h"
#include "import/mesh_invariants.h"
#include "scene/json_field.h"
#include "scene/limits.h"
#include "scene/mesh_file.h"
#include "scene/texture_section.h"

namespace wp {
namespace {
namespace gltf_scene {

namespace fs = std::filesystem;

// The default camera's vertical field of view and aspect ratio (width / height).
constexpr double kDefaultFovY = 40.0;
constexpr double kDefaultAspect = 4.0 / 3.0;
// The default camera's direction from the scene's centre: the front (+z), 26.6 degrees above it.
constexpr glm::dvec3 kDefaultViewFrom{0.0, 1.0, 2.0};

glm::dmat4 to_dmat4(const std::array<float, 16>& row_major) {
    glm::dmat4 result;
    for (int row = 0; row < 4; ++row) {
        for (int column = 0; column < 4; ++column) result[column][row] = row_major[4 * row + column];
    }
    return result;
}

glm::dvec3 to_dvec3(const std::array<float, 3>& v) { return {v[0], v[1], v[2]}; }
glm::dvec3 point_to_world(const glm::dmat4& m, const std::array<float, 3>& p) {
    return glm::dvec3(m * glm::dvec4(to_dvec3(p), 1.0));
}

bool finite(const glm::dvec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }
bool in_unit_interval(double x) { return x >= 0.0 && x <= 1.0; }

std::string quoted(const std::string& name) { return "\"" + name + "\""; }

class Reader {
 public:
    Reader(const std::string& path, const MeshImportLimits& mesh_import) : path_(path), importer_(mesh_import) {
        out_.scene.source = path;
    }

    MitsubaScene read() {
        try {
            imported_ = importer_.import(path_);
        } catch (const MeshFileError& error) {
            fail(error.what());
        }
        orient_file_uvs(path_, imported_);
        node_to_world_ = node_transforms();
        material_indices_.assign(std::max<std::size_t>(imported_.materials.size(), 1), -1);
        for (std::size_t n = 0; n < imported_.nodes.size(); ++n)
            for (std::uint32_t mesh : imported_.nodes[n].meshes) add_mesh(n, mesh);
        if (out_.scene.meshes.empty()) fail("no meshes: a glTF scene needs geometry");
        read_camera();
        read_lights();
        return std::move(out_);
    }

 private:
    [[noreturn]] void fail(const std::string& problem) const { throw SceneError(path_ + ": " + problem); }

    // Each node's transform to the world, its ancestors' applied (nodes come after their parents).
    std::vector<glm::dmat4> node_transforms() const {
        std::vector<glm::dmat4> to_world(imported_.nodes.size());
        for (std::size_t n = 0; n < imported_.nodes.size(); ++n) {
            const ImportedNode& node = imported_.nodes[n];
            const glm::dmat4 parent = node.parent == ImportedNode::kNoParent ? glm::dmat4(1.0) : to_world[node.parent];
            to_world[n] = parent * to_dmat4(node.transform);
        }
        return to_world;
    }

    const glm::dmat4& node_transform(std::uint32_t node, const std::string& what) const {
        if (node == kNoNode) fail(what + ": on no node of the scene");
        return node_to_world_[node];
    }

    std::string node_name(std::size_t node) const {
        const std::string& name = imported_.nodes[node].name;
        return "node " + (name.empty() ? std::to_string(node) : quoted(name));
    }

    // ---- meshes ----

    // One Mesh per primitive (assimp's mesh) of each node: one material each.
    void add_mesh(std::size_t node, std::uint32_t mesh_index) {
        const ImportedMesh& local = imported_.meshes[mesh_index];
        ImportedScene one;
        one.meshes.push_back(local);
        one.nodes.push_back(ImportedNode{});
        one.nodes[0].transform = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
        one.nodes[0].meshes = {0};
        Mesh mesh;
        try {
            mesh = mesh_from_import(one, MeshFileOptions{node_to_world_[node], false, {}});
        } catch (const MeshFileError& error) {
            fail(node_name(node) + ", mesh " + std::to_string(mesh_index) + ": " + error.what());
        }
        mesh.file = fs::path(path_).filename().string();
        mesh.material = material_index(local.material);
        triangles_ += mesh.triangles.size();
        if (triangles_ > kMaxTriangles)
            fail("the meshes have more than the " + std::to_string(kMaxTriangles) + " triangles a scene may have");
        MeshOrigin origin;
        origin.local = local;
        origin.to_world = node_to_world_[node];
        out_.scene.meshes.push_back(std::move(mesh));
        out_.meshes.push_back(std::move(origin));
    }

    // ---- materials ----

    int material_index(std::uint32_t imported) {
        int& index = material_indices_[imported];
        if (index < 0) {
            const ImportedMaterial fallback;  // a file without materials: glTF's default material
            const ImportedMaterial& source =
                imported_.materials.empty() ? fallback : imported_.materials[std::size_t(imported)];
            Material material = gltf_material(source, "material " + quoted(source.name));
            material.name = unique_name(source.name.empty() ? "material" : source.name);
            index = static_cast<int>(out_.scene.materials.size());
            out_.scene.materials.push_back(std::move(material));
        }
        return index;
    }

    std::string unique_name(const std::string& base) {
        std::string name = base;
        for (int n = 2; !material_names_.insert(name).second; ++n) name = base + " " + std::to_string(n);
        return name;
    }

    static glm::dvec3 base_colour(const ImportedMaterial& m) {
        return {m.base_color[0], m.base_color[1], m.base_color[2]};
    }
    static glm::dvec3 emission(const ImportedMaterial& m) { return to_dvec3(m.emissive) * double(m.emissive_strength); }
    // Where an emissive texture modulates it, the factor alone would make the whole surface glow:
    // such a material emits nothing here (with a note).
    static bool emits(const ImportedMaterial& m) {
        return emission(m) != glm::dvec3(0.0) && !(m.unread_textures & kEmissiveTexture);
    }

    // glTF's ranges of the factors, each an error line naming its factor.
    void check_factors(const ImportedMaterial& source, const std::string& what) const {
        const glm::dvec3 base = base_colour(source), glow = emission(source);
        const double alpha = source.base_color[3];
        if (!(finite(base) && in_unit_interval(base.x) && in_unit_interval(base.y) && in_unit_interval(base.z) &&
              in_unit_interval(alpha)))
            fail(what + ": baseColorFactor " + vector_text(base) + ", alpha " + format_number(alpha) +
                 ": must be in [0, 1]");
        if (!(std::isfinite(source.alpha_cutoff) && source.alpha_cutoff >= 0.0f))
            fail(what + ": alphaCutoff " + format_number(source.alpha_cutoff) + ": must be >= 0");
        if (!in_unit_interval(source.metallic))
            fail(what + ": metallicFactor " + format_number(source.metallic) + ": must be in [0, 1]");
        if (!in_unit_interval(source.roughness))
            fail(what + ": roughnessFactor " + format_number(source.roughness) + ": must be in [0, 1]");
        if (!(finite(glow) && glm::all(glm::greaterThanEqual(glow, glm::dvec3(0.0))) &&
              std::max({glow.x, glow.y, glow.z}) <= kMaxSceneMagnitude))
            fail(what + ": emissiveFactor times KHR_materials_emissive_strength " + vector_text(glow) +
                 ": must be finite and >= 0");
        if (!in_unit_interval(source.transmission))
            fail(what + ": transmissionFactor " + format_number(source.transmission) + ": must be in [0, 1]");
        if (!(source.ior > 1.0f && source.ior <= 10.0f))
            fail(what + ": ior " + format_number(source.ior) + ": must be in (1, 10]");
    }

    // The BSDF a material becomes (docs/scene-format.md, "glTF scenes"), and
    // which parameter its base colour texture would give.
    static Material bsdf_of(const ImportedMaterial& source, TexturedParameter& coloured) {
        const double roughness = source.roughness;
        Material m;
        coloured = TexturedParameter::Albedo;
        if (emits(source)) {
            m.type = MaterialType::Diffuse;
            m.albedo = base_colour(source);
            m.emission = emission(source);
        } else if (source.transmission > 0.0f) {
            m.type = roughness == 0.0 ? MaterialType::Glass : MaterialType::RoughDielectric;
            m.ior = source.ior;
        } else if (source.metallic >= 0.5f) {
            m.type = roughness == 0.0 ? MaterialType::Conductor : MaterialType::RoughConductor;
            m.eta = glm::dvec3(0.0);
            m.k = glm::dvec3(1.0);
            m.specular_reflectance = base_colour(source);
            coloured = TexturedParameter::SpecularReflectance;
        } else if (roughness == 1.0) {
            m.type = MaterialType::Diffuse;
            m.albedo = base_colour(source);
        } else {
            m.type = roughness == 0.0 ? MaterialType::Plastic : MaterialType::RoughPlastic;
            m.albedo = base_colour(source);
            m.ior = 1.5;  // glTF's dielectric: F0 = 0.04
        }
        if (m.type == MaterialType::RoughDielectric || m.type == MaterialType::RoughConductor ||
            m.type == MaterialType::RoughPlastic) {
            m.distribution = Microfacet::GGX;  // glTF's
            m.alpha_u = m.alpha_v = std::max(roughness * roughness, kMinRoughness);
        }
        return m;
    }

    Material gltf_material(const ImportedMaterial& source, const std::string& what) {
        check_factors(source, what);
        TexturedParameter coloured;
        Material m = bsdf_of(source, coloured);
        if (!source.base_color_texture.empty()) {
            if (m.type == MaterialType::Glass || m.type == MaterialType::RoughDielectric)
                fail(what + ": baseColorTexture on a transmissive material: wavepath's dielectrics are not tinted");
            m.texture(coloured) = texture_index(source.base_color_texture, TextureChannels::Colour,
                                                source.base_color_transform, what + ": baseColorTexture");
        }
        // The base colour's alpha (the factor's times the texture's) as a `mask`'s opacity: a cut-out
        // (MASK) or its fraction of rays stopped (BLEND).
        const double alpha = source.base_color[3];
        if (source.alpha_mode != ImportedAlphaMode::Opaque && !source.base_color_texture.empty())
            m.texture(TexturedParameter::Opacity) = opacity_texture(source, what);
        else if (source.alpha_mode == ImportedAlphaMode::Mask)
            m.opacity = alpha >= source.alpha_cutoff ? 1.0 : 0.0;
        else if (source.alpha_mode == ImportedAlphaMode::Blend)
            m.opacity = alpha;
        if (!source.normal_texture.empty()) add_normal_map(source, what, m);
        note_unread_textures(source, what);
        return m;
    }

    void note_unread_textures(const ImportedMaterial& source, const std::string& what) {
        if (source.unread_textures & kMetallicRoughnessTexture)
            out_.warnings.push_back(path_ + ": " + what +
                                    ": metallicRoughnessTexture not read: metallicFactor and roughnessFactor hold "
                                    "everywhere");
        if (source.unread_textures & kEmissiveTexture)
            out_.warnings.push_back(path_ + ": " + what +
                                    ": emissiveTexture not read: the material emits nothing (wavepath's emission is "
                                    "uniform)");
    }

    // glTF's tangent space is a normalmap's (x along increasing u, y along n x x, both with the file's
    // uvs): the texture, read raw, as the material's normal map, where wavepath's adapters allow one.
    void add_normal_map(const ImportedMaterial& source, const std::string& what, Material& m) {
        const bool transmits = m.type == MaterialType::Glass || m.type == MaterialType::RoughDielectric;
        if (transmits || m.masked()) {
            out_.warnings.push_back(path_ + ": " + what + ": normalTexture ignored (wavepath's normal maps take no " +
                                    (transmits ? "dielectric" : "mask") + ")");
            return;
        }
        m.texture(TexturedParameter::NormalMap) = texture_index(source.normal_texture, TextureChannels::Raw,
                                                                source.normal_transform, what + ": normalTexture");
    }

    // The image `uri` as a bitmap texture of `channels` under its KHR_texture_transform `to_uv`, one
    // per (uri, channels, to_uv): an image file beside the glTF, or "*N", the file's embedded image N
    // (a .glb's buffer view, a data: uri).
    int texture_index(const std::string& uri, TextureChannels channels, const std::array<float, 6>& to_uv,
                      const std::string& what) {
        const TextureKey key{uri, channels, checked_transform(to_uv, what)};
        if (const auto found = textures_.find(key); found != textures_.end()) return found->second;
        Texture texture = image_texture(uri, channels, what);
        texture.to_uv = std::get<2>(key);
        return textures_[key] = add_texture(std::move(texture), uri, what);
    }

    using TextureKey = std::tuple<std::string, TextureChannels, std::array<double, 6>>;  // image, channels, to_uv

    std::array<double, 6> checked_transform(const std::array<float, 6>& to_uv, const std::string& what) const {
        if (!std::all_of(to_uv.begin(), to_uv.end(), [](float x) { return std::isfinite(x); }))
            fail(what + ": KHR_texture_transform: offset, rotation and scale must be finite");
        std::array<double, 6> transform;
        std::copy(to_uv.begin(), to_uv.end(), transform.begin());
        return transform;
    }

    // The image `uri` read as `channels`, each image decoded once per channels (later uses copy it).
    Texture image_texture(const std::string& uri, TextureChannels channels, const std::string& what) {
        const auto read = std::find_if(textures_.begin(), textures_.end(), [&](const auto& entry) {
            return std::get<0>(entry.first) == uri && std::get<1>(entry.first) == channels;
        });
        if (read != textures_.end()) return out_.scene.textures[std::size_t(read->second)];
        Texture texture;
        texture.name = uri;
        texture.file = uri;
        const ImportedImage* embedded = uri.starts_with("*") ? &embedded_image(uri, what) : nullptr;
        try {
            if (embedded)
                read_bitmap_bytes(embedded->bytes, embedded->format, channels, texture);
            else
                read_bitmap_file((fs::path(path_).parent_path() / uri).string(), channels, texture);
        } catch (const std::runtime_error& error) {
            fail(what + " " + (embedded ? "(embedded image " + uri.substr(1) + ")" : quoted(uri)) + ": " +
                 error.what());
        }
        return texture;
    }

    // Adds `texture` to the scene; `uri` is the image it holds as it is, empty for one computed from
    // an image (`wavepath convert` writes each kind as a file of its own).
    int add_texture(Texture texture, const std::string& uri, const std::string& what) {
        texels_ += texture.texels.size() / 3;
        if (texels_ > kMaxTextureTexels)
            fail(what + ": the textures have more than the " + std::to_string(kMaxTextureTexels) +
                 " texels a scene may have");
        const std::size_t index = out_.scene.textures.size();
        if (uri.empty()) {
            out_.computed_textures.push_back(index);
        } else if (uri.starts_with("*")) {
            const ImportedImage& image = embedded_image(uri, what);
            out_.embedded_images.push_back({index, image.format, image.bytes});
        }
        out_.scene.textures.push_back(std::move(texture));
        return static_cast<int>(index);
    }

    // The base colour texture's alpha times the factor's as a mask's opacity: that fraction of rays
    // stopped (BLEND), or 1 where it is at least alphaCutoff and 0 below (MASK), texel by texel.
    int opacity_texture(const ImportedMaterial& source, const std::string& what) {
        Texture opacity =
            image_texture(source.base_color_texture, TextureChannels::Alpha, what + ": baseColorTexture's alpha");
        opacity.to_uv = checked_transform(source.base_color_transform, what);
        opacity.name = source.base_color_texture + " (opacity)";
        const float factor = source.base_color[3];
        for (float& texel : opacity.texels) {
            texel *= factor;
            if (source.alpha_mode == ImportedAlphaMode::Mask) texel = texel >= source.alpha_cutoff ? 1.0f : 0.0f;
        }
        return add_texture(std::move(opacity), "", what);
    }

    // The embedded image "*N" names, one wavepath can decode (its format named, its bytes sent).
    const ImportedImage& embedded_image(const std::string& uri, const std::string& what) const {
        const std::string digits = uri.substr(1);
        const bool number = !digits.empty() && digits.size() <= 9 &&
                            std::all_of(digits.begin(), digits.end(), [](char c) { return c >= '0' && c <= '9'; });
        if (!number || std::stoul(digits) >= imported_.images.size())
            fail(what + " names embedded image " + quoted(uri) + ", and the file holds " +
                 std::to_string(imported_.images.size()));
        const ImportedImage& image = imported_.images[std::stoul(digits)];
        if (image.bytes.empty())
            fail(what + " (embedded image " + digits + "): not a compressed image file (PNG, JPEG)");
        const bool format_named = !image.format.empty() &&
                                  std::all_of(image.format.begin(), image.format.end(),
                                              [](char c) { return (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9'); });
        if (!format_named)
            fail(what + " (embedded image " + digits +
                 "): its mimeType names no image format wavepath reads (image/png, image/jpeg)");
        return image;
    }

    // ---- camera ----

    void read_camera() {
        Camera& camera = out_.scene.camera;
        if (imported_.cameras.empty()) {
            default_camera();
            return;
        }
        const ImportedCamera& source = imported_.cameras.front();
        const std::string what = "camera " + quoted(source.name);
        const glm::dmat4& to_world = node_transform(source.node, what);
        // A glTF camera sits at its node's origin; assimp 5.2 copies the node's
        // translation into its position as well, which would apply it twice.
        camera.position = point_to_world(to_world, {0, 0, 0});
        camera.look_at = glm::dvec3(to_world * glm::dvec4(to_dvec3(source.look_at) - to_dvec3(source.position), 1.0));
        camera.up = glm::dmat3(to_world) * to_dvec3(source.up);
        camera.fov_y_degrees = double(source.yfov) * 180.0 / std::numbers::pi;
        if (!(camera.fov_y_degrees > 0.0 && camera.fov_y_degrees < 180.0))
            fail(what + ": yfov " + format_number(source.yfov) +
                 " radians: must be in (0, pi) (wavepath's cameras are perspective)");
        if (source.aspect > 0.0f && std::isfinite(source.aspect)) {
            set_size(source.aspect, what);
        } else {
            set_size(kDefaultAspect, what);
            out_.warnings.push_back(path_ + ": " + what + ": no aspectRatio: 640 x 480");
        }
        const glm::dvec3 view = camera.look_at - camera.position;
        if (!finite(camera.position) || !finite(view) || glm::length(view) == 0.0 ||
            glm::length(glm::cross(view, camera.up)) == 0.0)
            fail(what + ": its node's transform leaves no view direction and up");
    }

    void set_size(double aspect, const std::string& what) {
        const double height = std::round(kGltfImageWidth / aspect);
        if (!(height >= 1.0 && height <= kMaxResolution))
            fail(what + ": aspectRatio " + format_number(aspect) + " gives an image of " +
                 std::to_string(kGltfImageWidth) + " x " + format_number(height) + " pixels");
        out_.scene.camera.width = kGltfImageWidth;
        out_.scene.camera.height = static_cast<int>(height);
    }

    // Looking at the meshes' bounding box from the front (+z) and above (kDefaultViewFrom), from
    // where its bounding sphere fills the height.
    void default_camera() {
        glm::dvec3 low(std::numeric_limits<double>::infinity()), high(-std::numeric_limits<double>::infinity());
        for (const Mesh& mesh : out_.scene.meshes)
            for (const glm::dvec3& p : mesh.positions) {
                low = glm::min(low, p);
                high = glm::max(high, p);
            }
        const glm::dvec3 center = 0.5 * (low + high);
        const double radius = 0.5 * glm::length(high - low);
        Camera& camera = out_.scene.camera;
        camera.fov_y_degrees = kDefaultFovY;
        camera.look_at = center;
        camera.position = center + glm::normalize(kDefaultViewFrom) *
                                       (radius / std::sin(0.5 * kDefaultFovY * std::numbers::pi / 180.0));
        camera.up = {0.0, 1.0, 0.0};
        set_size(kDefaultAspect, "the default camera");
        out_.warnings.push_back(
            path_ + ": no camera: looking at the meshes' bounding box from +z and above (fov_y 40, 640 x 480)");
    }

    // ---- lights ----

    void read_lights() {
        for (const ImportedLight& light : imported_.lights) {
            const std::string what = "light " + quoted(light.name);
            const glm::dmat4& to_world = node_transform(light.node, what);
            const glm::dvec3 colour = to_dvec3(light.color);
            if (!(finite(colour) && glm::all(glm::greaterThanEqual(colour, glm::dvec3(0.0))) &&
                  std::max({colour.x, colour.y, colour.z}) <= kMaxSceneMagnitude))
                fail(what + ": colour times intensity " + vector_text(colour) + ": must be finite and >= 0");
            const glm::dvec3 direction = glm::dmat3(to_world) * to_dvec3(light.direction);
            if (light.type != ImportedLightType::Point && !(finite(direction) && glm::length(direction) > 0.0))
                fail(what + ": its node's transform leaves no direction");
            if (light.type == ImportedLightType::Directional) {
                out_.scene.directional_lights.push_back({glm::normalize(direction), colour});
                continue;
            }
            PointLight point;
            point.position = point_to_world(to_world, light.position);
            if (!finite(point.position) ||
                glm::any(glm::greaterThan(glm::abs(point.position), glm::dvec3(kMaxSceneMagnitude))))
                fail(what + ": its position " + vector_text(point.position) + " is out of range");
            point.intensity = colour;  // candela, as wavepath's intensity
            if (light.type == ImportedLightType::Spot) point.cone = spot_cone(light, glm::normalize(direction), what);
            out_.scene.point_lights.push_back(point);
        }
        const bool emits = std::any_of(out_.scene.materials.begin(), out_.scene.materials.end(),
                                       [](const Material& m) { return m.emits(); });
        if (out_.scene.directional_lights.empty() && out_.scene.point_lights.empty() && !emits) {
            out_.scene.background = glm::dvec3(1.0);
            out_.warnings.push_back(path_ + ": no light: a constant white environment of radiance 1 lights the scene");
        }
    }

    // A spot's cone: outerConeAngle the cutoff angle, innerConeAngle the beam
    // width (the falloff between them Mitsuba's, linear in the angle, not
    // glTF's recommended smooth one; docs/scene-format.md).
    SpotCone spot_cone(const ImportedLight& light, const glm::dvec3& axis, const std::string& what) const {
        SpotCone cone;
        cone.axis = axis;
        cone.cutoff_angle = glm::degrees(double(light.outer_cone));
        cone.beam_width = glm::degrees(double(light.inner_cone));
        if (!(cone.cutoff_angle > 0.0 && cone.cutoff_angle <= 90.0))
            fail(what + ": outerConeAngle " + format_number(light.outer_cone) + ": must be in (0, pi/2]");
        if (!(cone.beam_width >= 0.0 && cone.beam_width <= cone.cutoff_angle))
            fail(what + ": innerConeAngle " + format_number(light.inner_cone) + ": must be in [0, outerConeAngle]");
        return cone;
    }

    std::string path_;
    MeshImporter importer_;
    ImportedScene imported_;
    std::vector<glm::dmat4> node_to_world_;
    std::vector<int> material_indices_;  // per imported material: its index in the scene, -1 before its first use
    std::set<std::string> material_names_;
    std::map<TextureKey, int> textures_;
    std::size_t triangles_ = 0;
    std::size_t texels_ = 0;
    MitsubaScene out_;
};

std::string lower(std::string text) {
    std::transform(text.begin(), text.end(), text.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return text;
}

}  // namespace gltf_scene
}  // namespace

MitsubaScene read_gltf_scene(const std::string& path, const MeshImportLimits& mesh_import) {
    return gltf_scene::Reader(path, mesh_import).read();
}

Scene load_gltf_scene(const std::string& path, const MeshImportLimits& mesh_import, std::vector<std::string>* notes) {
    MitsubaScene read = read_gltf_scene(path, mesh_import);
    finish_scene(read.scene);
    if (notes) *notes = std::move(read.warnings);
    return std::move(read.scene);
}

bool is_gltf_scene_path(const std::string& path) {
    const std::string extension = gltf_scene::lower(std::filesystem::path(path).extension().string());
    return extension == ".gltf" || extension == ".glb";
}

}  // namespace wp
