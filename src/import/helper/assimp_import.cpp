#include "import/helper/assimp_import.h"

#include <assimp/GltfMaterial.h>
#include <assimp/importerdesc.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <algorithm>
#include <array>
#include <assimp/DefaultLogger.hpp>
#include <assimp/Importer.hpp>
#include <assimp/LogStream.hpp>
#include <assimp/ProgressHandler.hpp>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <exception>
#include <fstream>
#include <iterator>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "import/helper/obj_reader.h"
#include "import/mesh_file_error.h"
#include "import/mesh_invariants.h"

namespace wp {
namespace {

// ---- assimp's log ----

// assimp reports some problems only in its log and then carries on with a
// guess: an OFF index out of range is clamped, a polygon without an ear is
// fanned. This collects the error lines logged while it lives (DefaultLogger
// is global: imports must not run on several threads at once).
class AssimpErrorCapture : private Assimp::LogStream {
 public:
    AssimpErrorCapture() : created_logger_(Assimp::DefaultLogger::isNullLogger()) {
        if (created_logger_) Assimp::DefaultLogger::create(nullptr, Assimp::Logger::NORMAL, 0);
        Assimp::DefaultLogger::get()->attachStream(this, Assimp::Logger::Err);
    }
    ~AssimpErrorCapture() override {
        Assimp::DefaultLogger::get()->detachStream(this, Assimp::Logger::Err);  // ownership comes back
        if (created_logger_) Assimp::DefaultLogger::kill();
    }
    AssimpErrorCapture(const AssimpErrorCapture&) = delete;
    AssimpErrorCapture& operator=(const AssimpErrorCapture&) = delete;

    // The first logged error containing `text`, without assimp's prefix; empty if none.
    std::string find(std::string_view text) const {
        for (const std::string& line : errors_) {
            if (line.find(text) != std::string::npos) return line;
        }
        return {};
    }

 private:
    void write(const char* message) override {
        std::string line(message);
        static constexpr std::string_view kPrefix = "Error, T0: ";
        if (line.rfind(kPrefix, 0) == 0) line.erase(0, kPrefix.size());
        while (!line.empty() && (line.back() == '\n' || line.back() == '\r')) line.pop_back();
        errors_.push_back(line);
    }

    bool created_logger_;
    std::vector<std::string> errors_;
};

// assimp's messages may span lines; ours are one line.
std::string one_line(std::string text) {
    std::replace(text.begin(), text.end(), '\n', ' ');
    std::replace(text.begin(), text.end(), '\r', ' ');
    while (!text.empty() && text.back() == ' ') text.pop_back();
    return text;
}

// ---- the reader ----

// assimp's names for the readers of the formats docs/scene-format.md lists
// (OBJ: wavepath's own, import/helper/obj_reader.h).
constexpr std::string_view kDocumentedReaders[] = {TinyObjReader::kName, "Stanford Polygon Library (PLY) Importer",
                                                   "OFF Importer", "Stereolithography (STL) Importer",
                                                   "glTF2 Importer"};

// Why the reader assimp chose for the file may not read it; empty if it may
// or none is chosen yet. assimp's ReadFile records its choice (by the
// extension, else by each reader's signature check) as "importerIndex".
std::string reader_refusal(const Assimp::Importer& importer) {
    const int index = importer.GetPropertyInteger("importerIndex", -1);
    const aiImporterDesc* reader = index < 0 ? nullptr : importer.GetImporterInfo(std::size_t(index));
    if (reader == nullptr || std::find(std::begin(kDocumentedReaders), std::end(kDocumentedReaders), reader->mName) !=
                                 std::end(kDocumentedReaders))
        return {};
    return "format not supported: assimp chose its reader \"" + std::string(reader->mName) +
           "\"; wavepath reads OBJ, PLY, OFF, STL and glTF 2.0";
}

// Whether the reader assimp chose is the one named.
bool read_by(const Assimp::Importer& importer, std::string_view reader_name) {
    const int index = importer.GetPropertyInteger("importerIndex", -1);
    const aiImporterDesc* reader = index < 0 ? nullptr : importer.GetImporterInfo(std::size_t(index));
    return reader != nullptr && reader->mName == reader_name;
}

// Stops the import before a reader of another format reads the file:
// assimp reports the read's first progress (0 of the file's size) after
// choosing the reader and before calling it. A throw here makes ReadFile
// return null.
class ReaderGate : public Assimp::ProgressHandler {
 public:
    explicit ReaderGate(const Assimp::Importer& importer) : importer_(importer) {}

    bool Update(float) override { return true; }
    void UpdateFileRead(int, int) override {
        if (checked_) return;
        checked_ = true;
        refusal_ = reader_refusal(importer_);
        if (!refusal_.empty()) throw std::runtime_error(refusal_);
    }
    const std::string& refusal() const { return refusal_; }

 private:
    const Assimp::Importer& importer_;
    bool checked_ = false;
    std::string refusal_;
};

// ---- reading ----

// assimp's own message for a missing file names neither errno nor the reason.
void check_readable(const std::filesystem::path& path) {
    std::unique_ptr<std::FILE, int (*)(std::FILE*)> file(std::fopen(path.c_str(), "rb"), &std::fclose);
    if (!file) throw MeshFileError(std::string("cannot open: ") + std::strerror(errno));
    errno = 0;
    std::fgetc(file.get());
    if (std::ferror(file.get())) throw MeshFileError(std::string("cannot read: ") + std::strerror(errno));
}

glm::dvec3 to_dvec3(const aiVector3D& v) { return {v.x, v.y, v.z}; }

// Checked before assimp's post-processing, which relies on them (import/mesh_invariants.h).
void check_raw_mesh(const aiMesh& mesh) {
    for (unsigned v = 0; v < mesh.mNumVertices; ++v) check_finite_vertex(to_dvec3(mesh.mVertices[v]));
    for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
        const aiFace& face = mesh.mFaces[f];
        check_face({face.mIndices, face.mNumIndices}, mesh.mNumVertices);
    }
}

// What a reader of wavepath's threw inside assimp (TinyObjReader), if that ended the read.
void rethrow_mesh_file_error(const std::exception_ptr& exception) {
    if (!exception) return;
    try {
        std::rethrow_exception(exception);
    } catch (const MeshFileError&) {
        throw;
    } catch (...) {
    }
}

// The file's scene, triangulated with identical vertices joined, or MeshFileError.
const aiScene* import_triangles(Assimp::Importer& importer, const std::filesystem::path& path) {
    AssimpErrorCapture log;
    use_tiny_obj_reader(importer);
    auto* gate = new ReaderGate(importer);
    importer.SetProgressHandler(gate);  // the importer owns it
    const aiScene* scene = importer.ReadFile(path.string(), 0);
    if (!gate->refusal().empty()) throw MeshFileError(gate->refusal());
    if (!scene) rethrow_mesh_file_error(importer.GetException());
    if (!scene) throw MeshFileError("assimp cannot read it: " + one_line(importer.GetErrorString()));
    if (std::string refusal = reader_refusal(importer); !refusal.empty()) throw MeshFileError(refusal);
    if (std::string error = log.find("out of range"); !error.empty())
        throw MeshFileError("index out of range: " + one_line(error));
    for (unsigned m = 0; m < scene->mNumMeshes; ++m) check_raw_mesh(*scene->mMeshes[m]);

    scene = importer.ApplyPostProcessing(aiProcess_Triangulate);
    if (std::string error = log.find("triangulate"); !error.empty())
        throw MeshFileError("a polygon cannot be triangulated: " + one_line(error));
    if (scene) scene = importer.ApplyPostProcessing(aiProcess_JoinIdenticalVertices);
    if (!scene) throw MeshFileError("assimp cannot process it: " + one_line(importer.GetErrorString()));
    return scene;
}

// ---- what goes back ----

glm::vec3 to_vec3(const aiVector3D& v) { return {v.x, v.y, v.z}; }

ImportedMesh imported_mesh(const aiMesh& mesh) {
    ImportedMesh out;
    out.positions.reserve(mesh.mNumVertices);
    for (unsigned v = 0; v < mesh.mNumVertices; ++v) out.positions.push_back(to_vec3(mesh.mVertices[v]));
    out.has_normals = mesh.mNormals != nullptr;
    if (out.has_normals) {
        out.normals.reserve(mesh.mNumVertices);
        for (unsigned v = 0; v < mesh.mNumVertices; ++v) out.normals.push_back(to_vec3(mesh.mNormals[v]));
    }
    out.has_uvs = mesh.mTextureCoords[0] != nullptr;
    if (out.has_uvs) {
        out.uvs.reserve(mesh.mNumVertices);
        for (unsigned v = 0; v < mesh.mNumVertices; ++v)
            out.uvs.emplace_back(mesh.mTextureCoords[0][v].x, mesh.mTextureCoords[0][v].y);
    }
    out.material = mesh.mMaterialIndex;
    out.triangles.reserve(mesh.mNumFaces);
    for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
        const aiFace& face = mesh.mFaces[f];
        // Triangulation leaves only points and lines, which check_raw_mesh refused.
        if (face.mNumIndices != 3)
            throw MeshFileError("assimp left a face of " + std::to_string(face.mNumIndices) + " vertices");
        out.triangles.emplace_back(face.mIndices[0], face.mIndices[1], face.mIndices[2]);
    }
    return out;
}

ImportedNode imported_node(const aiNode& node, std::uint32_t parent) {
    ImportedNode out;
    out.parent = parent;
    out.name = node.mName.C_Str();
    const aiMatrix4x4& m = node.mTransformation;
    out.transform = {m.a1, m.a2, m.a3, m.a4, m.b1, m.b2, m.b3, m.b4, m.c1, m.c2, m.c3, m.c4, m.d1, m.d2, m.d3, m.d4};
    out.meshes.assign(node.mMeshes, node.mMeshes + node.mNumMeshes);
    return out;
}

// The node graph depth first, each node before its children (in order).
std::vector<ImportedNode> imported_nodes(const aiNode* root) {
    std::vector<ImportedNode> nodes;
    std::vector<std::pair<const aiNode*, std::uint32_t>> pending;  // a node and its parent's index
    if (root) pending.emplace_back(root, ImportedNode::kNoParent);
    while (!pending.empty()) {
        const auto [node, parent] = pending.back();
        pending.pop_back();
        const auto index = static_cast<std::uint32_t>(nodes.size());
        nodes.push_back(imported_node(*node, parent));
        for (unsigned i = node->mNumChildren; i-- > 0;) pending.emplace_back(node->mChildren[i], index);
    }
    return nodes;
}

// ---- materials, cameras and lights (glTF 2.0's; other formats' too, where assimp has them) ----

std::array<float, 3> to_array(const aiVector3D& v) { return {v.x, v.y, v.z}; }
std::array<float, 3> to_array(const aiColor3D& c) { return {c.r, c.g, c.b}; }

std::string bounded_name(const aiString& name) { return std::string(name.C_Str()).substr(0, kMaxImportedName); }

ImportedMaterial imported_material(const aiMaterial& material) {
    ImportedMaterial out;
    out.name = bounded_name(material.GetName());
    // Each value stays glTF's default where the material lacks the property.
    aiColor4D base(1, 1, 1, 1);
    material.Get(AI_MATKEY_BASE_COLOR, base);
    out.base_color = {base.r, base.g, base.b, base.a};
    material.Get(AI_MATKEY_METALLIC_FACTOR, out.metallic);
    material.Get(AI_MATKEY_ROUGHNESS_FACTOR, out.roughness);
    aiColor3D emissive(0, 0, 0);
    material.Get(AI_MATKEY_COLOR_EMISSIVE, emissive);
    out.emissive = to_array(emissive);
    material.Get(AI_MATKEY_EMISSIVE_INTENSITY, out.emissive_strength);
    material.Get(AI_MATKEY_TRANSMISSION_FACTOR, out.transmission);
    material.Get(AI_MATKEY_REFRACTI, out.ior);
    aiString texture;
    if (material.GetTexture(aiTextureType_BASE_COLOR, 0, &texture) == aiReturn_SUCCESS ||
        material.GetTexture(aiTextureType_DIFFUSE, 0, &texture) == aiReturn_SUCCESS)
        out.base_color_texture = bounded_name(texture);
    if (material.GetTexture(aiTextureType_NORMALS, 0, &texture) == aiReturn_SUCCESS)
        out.normal_texture = bounded_name(texture);
    return out;
}

// The file's embedded images as stored (assimp's compressed textures: mHeight 0, mWidth bytes), in
// its order, which its materials' "*N" names follow. An uncompressed one (other formats') goes with
// no bytes, for the scene reader to refuse if a material uses it.
std::vector<ImportedImage> imported_images(const aiScene& scene) {
    std::vector<ImportedImage> images;
    for (unsigned t = 0; t < scene.mNumTextures; ++t) {
        const aiTexture& texture = *scene.mTextures[t];
        ImportedImage& image = images.emplace_back();
        if (texture.mHeight != 0 || !texture.pcData) continue;
        if (texture.mWidth > kMaxImportedImageBytes)
            throw MeshFileError("embedded image " + std::to_string(t) + " has " + std::to_string(texture.mWidth) +
                                " bytes, more than the " + std::to_string(kMaxImportedImageBytes) + " wavepath reads");
        image.format = std::string(texture.achFormatHint, strnlen(texture.achFormatHint, kMaxImageFormat));
        image.bytes.assign(reinterpret_cast<const char*>(texture.pcData), texture.mWidth);
    }
    return images;
}

// ---- the glTF extensions assimp 5.2 does not read ----

// A glTF file's JSON: the whole of a .gltf, the first chunk of a .glb
// (after its 12-byte header, a u32 length and the type "JSON", and read
// alone: the binary chunk after it may be large); empty if it holds none.
std::string gltf_json(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    char header[20] = {};
    in.read(header, sizeof header);
    if (std::string_view(header, 4) != "glTF") {
        in.clear();
        in.seekg(0);
        return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    }
    if (in.gcount() < 20 || std::string_view(header + 16, 4) != "JSON") return {};
    std::uint32_t length = 0;
    std::memcpy(&length, header + 12, 4);
    std::string json(length, '\0');  // assimp read the file: the chunk is there
    in.read(json.data(), length);
    json.resize(std::size_t(in.gcount()));
    return json;
}

// A number at `key` of `object`'s `extension`, if there is one.
void get_extension_number(const nlohmann::json& object, const char* extension, const char* key, float& value) {
    const auto extensions = object.find("extensions");
    if (extensions == object.end() || !extensions->is_object()) return;
    const auto found = extensions->find(extension);
    if (found == extensions->end() || !found->is_object()) return;
    const auto number = found->find(key);
    if (number != found->end() && number->is_number()) value = number->get<float>();
}

// A number at `key` of `object`, if there is one.
void get_number(const nlohmann::json& object, const char* key, float& value) {
    const auto number = object.find(key);
    if (number != object.end() && number->is_number()) value = number->get<float>();
}

// A textureInfo's KHR_texture_transform (glTF: uv' = T(offset) R(rotation) S(scale) uv, R's columns
// (cos, sin) and (-sin, cos)) as the rows of Texture::to_uv; `transform` stays as it is without one.
void get_texture_transform(const nlohmann::json& material, const char* parent, const char* texture,
                           std::array<float, 6>& transform) {
    const nlohmann::json* info = &material;
    if (parent) {
        const auto found = material.find(parent);
        if (found == material.end() || !found->is_object()) return;
        info = &*found;
    }
    const auto found = info->find(texture);
    if (found == info->end() || !found->is_object()) return;
    const auto extensions = found->find("extensions");
    if (extensions == found->end() || !extensions->is_object()) return;
    const auto t = extensions->find("KHR_texture_transform");
    if (t == extensions->end() || !t->is_object()) return;
    float offset[2] = {0, 0}, scale[2] = {1, 1}, rotation = 0;
    get_number(*t, "rotation", rotation);
    for (int i = 0; i < 2; ++i) {
        if (const auto o = t->find("offset"); o != t->end() && o->is_array() && o->size() == 2 && (*o)[i].is_number())
            offset[i] = (*o)[i].get<float>();
        if (const auto s = t->find("scale"); s != t->end() && s->is_array() && s->size() == 2 && (*s)[i].is_number())
            scale[i] = (*s)[i].get<float>();
    }
    const double c = std::cos(double(rotation)), s = std::sin(double(rotation));
    transform = {float(c * scale[0]), float(-s * scale[1]), offset[0],
                 float(s * scale[0]), float(c * scale[1]),  offset[1]};
}

// What assimp 5.2 does not read from a glTF file, from its JSON: each
// material's KHR_materials_emissive_strength, KHR_materials_transmission and
// KHR_materials_ior, its alphaMode and alphaCutoff, which of the textures wavepath does not read it
// has, its textures' KHR_texture_transform, and each perspective camera's yfov and aspectRatio
// (assimp's horizontal angle is yfov x aspectRatio, and 0 without one).
// assimp keeps the file's materials and cameras in its order (and adds its
// default material after them).
void read_gltf_extras(const std::filesystem::path& path, ImportedScene& scene) {
    const nlohmann::json document = nlohmann::json::parse(gltf_json(path), nullptr, false);
    if (!document.is_object()) return;  // assimp read it: it is there
    const auto materials = document.find("materials");
    if (materials != document.end() && materials->is_array()) {
        for (std::size_t m = 0; m < std::min(materials->size(), scene.materials.size()); ++m) {
            const nlohmann::json& material = (*materials)[m];
            if (!material.is_object()) continue;
            ImportedMaterial& out = scene.materials[m];
            get_extension_number(material, "KHR_materials_emissive_strength", "emissiveStrength",
                                 out.emissive_strength);
            get_extension_number(material, "KHR_materials_transmission", "transmissionFactor", out.transmission);
            get_extension_number(material, "KHR_materials_ior", "ior", out.ior);
            const auto alpha_mode = material.find("alphaMode");
            if (alpha_mode != material.end() && *alpha_mode == "MASK") out.alpha_mode = ImportedAlphaMode::Mask;
            if (alpha_mode != material.end() && *alpha_mode == "BLEND") out.alpha_mode = ImportedAlphaMode::Blend;
            get_number(material, "alphaCutoff", out.alpha_cutoff);
            const auto pbr = material.find("pbrMetallicRoughness");
            if (pbr != material.end() && pbr->is_object() && pbr->contains("metallicRoughnessTexture"))
                out.unread_textures |= kMetallicRoughnessTexture;
            if (material.contains("emissiveTexture")) out.unread_textures |= kEmissiveTexture;
            get_texture_transform(material, "pbrMetallicRoughness", "baseColorTexture", out.base_color_transform);
            get_texture_transform(material, nullptr, "normalTexture", out.normal_transform);
        }
    }
    const auto cameras = document.find("cameras");
    if (cameras == document.end() || !cameras->is_array()) return;
    for (std::size_t c = 0; c < std::min(cameras->size(), scene.cameras.size()); ++c) {
        const nlohmann::json& camera = (*cameras)[c];
        if (!camera.is_object()) continue;
        const auto perspective = camera.find("perspective");
        scene.cameras[c].yfov = scene.cameras[c].aspect = 0.0f;                  // unless the file gives them
        if (perspective == camera.end() || !perspective->is_object()) continue;  // orthographic
        get_number(*perspective, "yfov", scene.cameras[c].yfov);
        get_number(*perspective, "aspectRatio", scene.cameras[c].aspect);
    }
}

// The index of the first node (depth first) named `name`, or kNoNode.
std::uint32_t node_named(const std::vector<ImportedNode>& nodes, const aiString& name) {
    for (std::size_t n = 0; n < nodes.size(); ++n) {
        if (nodes[n].name == name.C_Str()) return static_cast<std::uint32_t>(n);
    }
    return kNoNode;
}

ImportedCamera imported_camera(const aiCamera& camera, const std::vector<ImportedNode>& nodes) {
    ImportedCamera out;
    out.name = bounded_name(camera.mName);
    out.node = node_named(nodes, camera.mName);
    out.position = to_array(camera.mPosition);
    out.look_at = to_array(camera.mPosition + camera.mLookAt);
    out.up = to_array(camera.mUp);
    // yfov and aspect are a glTF file's own (read_gltf_extras): assimp 5.2's
    // horizontal angle for glTF is yfov x aspectRatio, where its documentation
    // says half the horizontal angle.
    return out;
}

std::vector<ImportedLight> imported_lights(const aiScene& scene, const std::vector<ImportedNode>& nodes) {
    std::vector<ImportedLight> lights;
    for (unsigned l = 0; l < scene.mNumLights; ++l) {
        const aiLight& light = *scene.mLights[l];
        ImportedLight out;
        out.name = bounded_name(light.mName);
        out.node = node_named(nodes, light.mName);
        if (light.mType == aiLightSource_DIRECTIONAL) {
            out.type = ImportedLightType::Directional;
        } else if (light.mType == aiLightSource_POINT) {
            out.type = ImportedLightType::Point;
        } else if (light.mType == aiLightSource_SPOT) {
            out.type = ImportedLightType::Spot;
        } else {
            continue;  // ambient and area lights: other formats' (a mesh file's lights are not read)
        }
        out.color = to_array(light.mColorDiffuse);
        out.position = to_array(light.mPosition);
        out.direction = to_array(light.mDirection);
        out.inner_cone = light.mAngleInnerCone;  // glTF's innerConeAngle and outerConeAngle
        out.outer_cone = light.mAngleOuterCone;
        lights.push_back(out);
    }
    return lights;
}

}  // namespace

ImportedScene import_with_assimp(const std::filesystem::path& path) {
    check_readable(path);
    Assimp::Importer importer;
    const aiScene* scene = import_triangles(importer, path);
    ImportedScene imported;
    for (unsigned m = 0; m < scene->mNumMeshes; ++m) imported.meshes.push_back(imported_mesh(*scene->mMeshes[m]));
    imported.nodes = imported_nodes(scene->mRootNode);
    for (unsigned m = 0; m < scene->mNumMaterials; ++m)
        imported.materials.push_back(imported_material(*scene->mMaterials[m]));
    for (unsigned c = 0; c < scene->mNumCameras; ++c)
        imported.cameras.push_back(imported_camera(*scene->mCameras[c], imported.nodes));
    imported.lights = imported_lights(*scene, imported.nodes);
    imported.images = imported_images(*scene);
    if (read_by(importer, "glTF2 Importer")) read_gltf_extras(path, imported);
    return imported;
}

}  // namespace wp
