#include "import/answer.h"

#include <algorithm>
#include <cstring>
#include <type_traits>

namespace wp {
namespace {

constexpr std::string_view kMagic = "WPIMPORT";
enum class AnswerKind : std::uint32_t { Failure = 1, Scene = 2 };

// The arrays go as they lie in memory.
static_assert(sizeof(glm::vec3) == 12 && sizeof(glm::uvec3) == 12 && sizeof(std::array<float, 16>) == 64);

class AnswerWriter {
 public:
    explicit AnswerWriter(AnswerKind kind) {
        bytes_.append(kMagic);
        put(kAnswerVersion);
        put(kind);
    }

    template <class T>
    void put(const T& value) {
        static_assert(std::is_trivially_copyable_v<T>);
        bytes_.append(reinterpret_cast<const char*>(&value), sizeof(T));
    }
    void put_count(std::size_t count) { put(static_cast<std::uint32_t>(count)); }
    template <class T>
    void put_array(const std::vector<T>& values) {
        static_assert(std::is_trivially_copyable_v<T>);
        if (!values.empty()) bytes_.append(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(T));
    }
    void put_text(std::string_view text) {
        put_count(text.size());
        bytes_.append(text);
    }

    std::string take() { return std::move(bytes_); }

 private:
    std::string bytes_;
};

class AnswerReader {
 public:
    explicit AnswerReader(std::string_view bytes) : rest_(bytes) {}

    template <class T>
    T take(const std::string& what) {
        T value;
        std::memcpy(&value, take_bytes(sizeof(T), 1, what), sizeof(T));
        return value;
    }
    std::uint32_t take_count(const std::string& what) { return take<std::uint32_t>(what); }
    template <class T>
    std::vector<T> take_array(std::uint32_t count, const std::string& what) {
        const char* bytes = take_bytes(sizeof(T), count, what);
        std::vector<T> values(count);
        if (count > 0)
            std::memcpy(values.data(), bytes, std::size_t{count} * sizeof(T));  // an empty one's data() is null
        return values;
    }
    std::string take_text(std::size_t min, std::size_t max, const std::string& what) {
        const std::uint32_t length = take_count(what + "'s length");
        if (length < min || length > max)
            fail(what + " of " + std::to_string(length) + " bytes (" + std::to_string(min) + " to " +
                 std::to_string(max) + " expected)");
        return std::string(take_bytes(1, length, what), length);
    }

    void expect_end() const {
        if (!rest_.empty()) fail(std::to_string(rest_.size()) + " bytes after the answer");
    }
    [[noreturn]] static void fail(const std::string& problem) { throw MalformedAnswer(problem); }

 private:
    // `count` items of `size` bytes, checked against what is left before the product is formed.
    const char* take_bytes(std::size_t size, std::uint32_t count, const std::string& what) {
        if (count > rest_.size() / size)
            fail("it ends within " + what + " (" + std::to_string(std::size_t{count} * size) + " bytes, " +
                 std::to_string(rest_.size()) + " left)");
        const char* bytes = rest_.data();
        rest_.remove_prefix(std::size_t{count} * size);
        return bytes;
    }

    std::string_view rest_;
};

// A mesh's flags.
constexpr std::uint32_t kHasNormals = 1u, kHasUvs = 2u;

// ---- writing ----

void put_mesh(AnswerWriter& out, const ImportedMesh& mesh) {
    out.put_count(mesh.positions.size());
    out.put_count((mesh.has_normals ? kHasNormals : 0u) | (mesh.has_uvs ? kHasUvs : 0u));
    out.put_count(mesh.triangles.size());
    out.put_array(mesh.positions);
    if (mesh.has_normals) out.put_array(mesh.normals);
    if (mesh.has_uvs) out.put_array(mesh.uvs);
    out.put_array(mesh.triangles);
    out.put(mesh.material);
}

void put_material(AnswerWriter& out, const ImportedMaterial& material) {
    out.put_text(material.name);
    out.put(material.base_color);
    out.put(material.metallic);
    out.put(material.roughness);
    out.put(material.emissive);
    out.put(material.emissive_strength);
    out.put(material.transmission);
    out.put(material.ior);
    out.put_text(material.base_color_texture);
    out.put_text(material.normal_texture);
    out.put(material.base_color_transform);
    out.put(material.normal_transform);
    out.put(material.alpha_mode);
    out.put(material.alpha_cutoff);
    out.put(material.unread_textures);
}

void put_camera(AnswerWriter& out, const ImportedCamera& camera) {
    out.put_text(camera.name);
    out.put(camera.node);
    out.put(camera.position);
    out.put(camera.look_at);
    out.put(camera.up);
    out.put(camera.yfov);
    out.put(camera.aspect);
}

void put_light(AnswerWriter& out, const ImportedLight& light) {
    out.put_text(light.name);
    out.put(light.node);
    out.put(light.type);
    out.put(light.color);
    out.put(light.position);
    out.put(light.direction);
    out.put(light.inner_cone);
    out.put(light.outer_cone);
}

void put_image(AnswerWriter& out, const ImportedImage& image) {
    out.put_text(image.format);
    out.put_text(image.bytes);
}

void put_node(AnswerWriter& out, const ImportedNode& node) {
    out.put(node.parent);
    out.put(node.transform);
    out.put_text(node.name);
    out.put_count(node.meshes.size());
    out.put_array(node.meshes);
}

// ---- reading ----

ImportedMesh take_mesh(AnswerReader& in, const std::string& what) {
    ImportedMesh mesh;
    const std::uint32_t vertices = in.take_count(what + "'s vertex count");
    const std::uint32_t flags = in.take_count(what + "'s flags");
    if (flags > (kHasNormals | kHasUvs)) AnswerReader::fail(what + "'s flags are " + std::to_string(flags));
    mesh.has_normals = (flags & kHasNormals) != 0;
    mesh.has_uvs = (flags & kHasUvs) != 0;
    const std::uint32_t triangles = in.take_count(what + "'s triangle count");
    mesh.positions = in.take_array<glm::vec3>(vertices, what + "'s positions");
    if (mesh.has_normals) mesh.normals = in.take_array<glm::vec3>(vertices, what + "'s normals");
    if (mesh.has_uvs) mesh.uvs = in.take_array<glm::vec2>(vertices, what + "'s uvs");
    mesh.triangles = in.take_array<glm::uvec3>(triangles, what + "'s triangles");
    mesh.material = in.take<std::uint32_t>(what + "'s material");
    return mesh;
}

ImportedMaterial take_material(AnswerReader& in, const std::string& what) {
    ImportedMaterial material;
    material.name = in.take_text(0, kMaxImportedName, what + "'s name");
    material.base_color = in.take<std::array<float, 4>>(what + "'s base colour");
    material.metallic = in.take<float>(what + "'s metallic factor");
    material.roughness = in.take<float>(what + "'s roughness factor");
    material.emissive = in.take<std::array<float, 3>>(what + "'s emissive factor");
    material.emissive_strength = in.take<float>(what + "'s emissive strength");
    material.transmission = in.take<float>(what + "'s transmission");
    material.ior = in.take<float>(what + "'s ior");
    material.base_color_texture = in.take_text(0, kMaxImportedName, what + "'s base colour texture");
    material.normal_texture = in.take_text(0, kMaxImportedName, what + "'s normal texture");
    material.base_color_transform = in.take<std::array<float, 6>>(what + "'s base colour transform");
    material.normal_transform = in.take<std::array<float, 6>>(what + "'s normal transform");
    const auto alpha_mode = in.take<std::uint32_t>(what + "'s alpha mode");
    if (alpha_mode > 2)
        AnswerReader::fail(what + "'s alpha mode is " + std::to_string(alpha_mode) + " (0 to 2 expected)");
    material.alpha_mode = static_cast<ImportedAlphaMode>(alpha_mode);
    material.alpha_cutoff = in.take<float>(what + "'s alpha cutoff");
    material.unread_textures = in.take<std::uint32_t>(what + "'s unread textures");
    if (material.unread_textures > kAllUnreadTextures)
        AnswerReader::fail(what + "'s unread textures are " + std::to_string(material.unread_textures) + " (0 to " +
                           std::to_string(kAllUnreadTextures) + " expected)");
    return material;
}

std::uint32_t take_node_index(AnswerReader& in, std::size_t node_count, const std::string& what) {
    const auto node = in.take<std::uint32_t>(what + "'s node");
    if (node >= node_count && node != kNoNode)
        AnswerReader::fail(what + " names node " + std::to_string(node) + " of " + std::to_string(node_count));
    return node;
}

ImportedCamera take_camera(AnswerReader& in, std::size_t node_count, const std::string& what) {
    ImportedCamera camera;
    camera.name = in.take_text(0, kMaxImportedName, what + "'s name");
    camera.node = take_node_index(in, node_count, what);
    camera.position = in.take<std::array<float, 3>>(what + "'s position");
    camera.look_at = in.take<std::array<float, 3>>(what + "'s look-at point");
    camera.up = in.take<std::array<float, 3>>(what + "'s up");
    camera.yfov = in.take<float>(what + "'s vertical field of view");
    camera.aspect = in.take<float>(what + "'s aspect ratio");
    return camera;
}

ImportedLight take_light(AnswerReader& in, std::size_t node_count, const std::string& what) {
    ImportedLight light;
    light.name = in.take_text(0, kMaxImportedName, what + "'s name");
    light.node = take_node_index(in, node_count, what);
    const auto type = in.take<std::uint32_t>(what + "'s type");
    if (type < 1 || type > 3) AnswerReader::fail(what + "'s type is " + std::to_string(type) + " (1 to 3 expected)");
    light.type = static_cast<ImportedLightType>(type);
    light.color = in.take<std::array<float, 3>>(what + "'s colour");
    light.position = in.take<std::array<float, 3>>(what + "'s position");
    light.direction = in.take<std::array<float, 3>>(what + "'s direction");
    light.inner_cone = in.take<float>(what + "'s inner cone angle");
    light.outer_cone = in.take<float>(what + "'s outer cone angle");
    return light;
}

ImportedNode take_node(AnswerReader& in, std::uint32_t index, std::size_t mesh_count) {
    const std::string what = "node " + std::to_string(index);
    ImportedNode node;
    node.parent = in.take<std::uint32_t>(what + "'s parent");
    const bool root = index == 0;
    if (root ? node.parent != ImportedNode::kNoParent : node.parent >= index)
        AnswerReader::fail(what + "'s parent is " + std::to_string(node.parent) +
                           (root ? " (the root has none)" : " (not an earlier node)"));
    node.transform = in.take<std::array<float, 16>>(what + "'s transform");
    node.name = in.take_text(0, kMaxNodeName, what + "'s name");
    node.meshes = in.take_array<std::uint32_t>(in.take_count(what + "'s mesh count"), what + "'s meshes");
    for (std::uint32_t mesh : node.meshes) {
        if (mesh >= mesh_count)
            AnswerReader::fail(what + " names mesh " + std::to_string(mesh) + " of " + std::to_string(mesh_count));
    }
    return node;
}

ImportedImage take_image(AnswerReader& in, const std::string& what) {
    ImportedImage image;
    image.format = in.take_text(0, kMaxImageFormat, what + "'s format");
    image.bytes = in.take_text(0, kMaxImportedImageBytes, what + "'s bytes");
    return image;
}

ImportedScene take_scene(AnswerReader& in) {
    ImportedScene scene;
    // Each item is read before the next is counted: a count the bytes do not hold allocates nothing.
    const std::uint32_t meshes = in.take_count("the mesh count");
    for (std::uint32_t m = 0; m < meshes; ++m) scene.meshes.push_back(take_mesh(in, "mesh " + std::to_string(m)));
    const std::uint32_t nodes = in.take_count("the node count");
    for (std::uint32_t n = 0; n < nodes; ++n) scene.nodes.push_back(take_node(in, n, scene.meshes.size()));
    const std::uint32_t materials = in.take_count("the material count");
    for (std::uint32_t m = 0; m < materials; ++m)
        scene.materials.push_back(take_material(in, "material " + std::to_string(m)));
    for (std::size_t m = 0; m < scene.meshes.size(); ++m) {
        const std::uint32_t material = scene.meshes[m].material;
        if (material >= std::max<std::size_t>(scene.materials.size(), 1))
            AnswerReader::fail("mesh " + std::to_string(m) + " names material " + std::to_string(material) + " of " +
                               std::to_string(scene.materials.size()));
    }
    const std::uint32_t cameras = in.take_count("the camera count");
    for (std::uint32_t c = 0; c < cameras; ++c)
        scene.cameras.push_back(take_camera(in, scene.nodes.size(), "camera " + std::to_string(c)));
    const std::uint32_t lights = in.take_count("the light count");
    for (std::uint32_t l = 0; l < lights; ++l)
        scene.lights.push_back(take_light(in, scene.nodes.size(), "light " + std::to_string(l)));
    const std::uint32_t images = in.take_count("the image count");
    for (std::uint32_t i = 0; i < images; ++i) scene.images.push_back(take_image(in, "image " + std::to_string(i)));
    return scene;
}

}  // namespace

std::string encode_answer(const ImportedScene& scene) {
    AnswerWriter out(AnswerKind::Scene);
    out.put_count(scene.meshes.size());
    for (const ImportedMesh& mesh : scene.meshes) put_mesh(out, mesh);
    out.put_count(scene.nodes.size());
    for (const ImportedNode& node : scene.nodes) put_node(out, node);
    out.put_count(scene.materials.size());
    for (const ImportedMaterial& material : scene.materials) put_material(out, material);
    out.put_count(scene.cameras.size());
    for (const ImportedCamera& camera : scene.cameras) put_camera(out, camera);
    out.put_count(scene.lights.size());
    for (const ImportedLight& light : scene.lights) put_light(out, light);
    out.put_count(scene.images.size());
    for (const ImportedImage& image : scene.images) put_image(out, image);
    return out.take();
}

std::string encode_answer(const ImportFailure& failure) {
    AnswerWriter out(AnswerKind::Failure);
    const std::string_view message(failure.message);
    out.put_text(message.substr(0, kMaxFailureLength));
    return out.take();
}

ImportAnswer decode_answer(std::string_view bytes) {
    AnswerReader in(bytes);
    if (!bytes.starts_with(kMagic)) AnswerReader::fail("it does not begin with \"WPIMPORT\"");
    in.take<std::array<char, kMagic.size()>>("the signature");
    const std::uint32_t version = in.take<std::uint32_t>("the version");
    if (version != kAnswerVersion)
        AnswerReader::fail("version " + std::to_string(version) + ", not " + std::to_string(kAnswerVersion));
    const auto kind = in.take<AnswerKind>("the kind");
    ImportAnswer answer;
    if (kind == AnswerKind::Failure) {
        answer = ImportFailure{in.take_text(1, kMaxFailureLength, "the failure message")};
    } else if (kind == AnswerKind::Scene) {
        answer = take_scene(in);
    } else {
        AnswerReader::fail("kind " + std::to_string(static_cast<std::uint32_t>(kind)) + ", neither 1 nor 2");
    }
    in.expect_end();
    return answer;
}

}  // namespace wp
