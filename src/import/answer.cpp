#include "import/answer.h"

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
    return mesh;
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

ImportedScene take_scene(AnswerReader& in) {
    ImportedScene scene;
    // Each item is read before the next is counted: a count the bytes do not hold allocates nothing.
    const std::uint32_t meshes = in.take_count("the mesh count");
    for (std::uint32_t m = 0; m < meshes; ++m) scene.meshes.push_back(take_mesh(in, "mesh " + std::to_string(m)));
    const std::uint32_t nodes = in.take_count("the node count");
    for (std::uint32_t n = 0; n < nodes; ++n) scene.nodes.push_back(take_node(in, n, scene.meshes.size()));
    return scene;
}

}  // namespace

std::string encode_answer(const ImportedScene& scene) {
    AnswerWriter out(AnswerKind::Scene);
    out.put_count(scene.meshes.size());
    for (const ImportedMesh& mesh : scene.meshes) put_mesh(out, mesh);
    out.put_count(scene.nodes.size());
    for (const ImportedNode& node : scene.nodes) put_node(out, node);
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
