#include "import/helper/obj_reader.h"

#include <assimp/importerdesc.h>
#include <assimp/scene.h>
#include <tiny_obj_loader.h>

#include <algorithm>
#include <assimp/Importer.hpp>
#include <charconv>
#include <cmath>
#include <cstddef>
#include <fstream>
#include <iterator>
#include <memory>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "import/mesh_file_error.h"

namespace wp {
namespace {
namespace obj_reader {

constexpr aiImporterDesc kDescription = {
    TinyObjReader::kName, "", "", "", aiImporterFlags_SupportTextFlavour, 0, 0, 0, 0, "obj"};

// Faces [first, last) of one shape that share a material: one aiMesh, as
// assimp's reader starts a new mesh where "usemtl" changes the material.
struct FaceRun {
    std::size_t first_face, last_face;
    std::size_t first_index;  // into the shape's indices
};

std::vector<FaceRun> material_runs(const tinyobj::mesh_t& mesh) {
    std::vector<FaceRun> runs;
    std::size_t index = 0;
    for (std::size_t face = 0; face < mesh.num_face_vertices.size(); ++face) {
        if (runs.empty() || mesh.material_ids[face] != mesh.material_ids[face - 1]) runs.push_back({face, face, index});
        runs.back().last_face = face + 1;
        index += mesh.num_face_vertices[face];
    }
    return runs;
}

// Where a corner's attribute index is valid: below `count` (tinyobjloader
// resolves negative, relative indices and leaves the rest unchecked).
bool in_range(int index, std::size_t count) { return index >= 0 && std::size_t(index) < count; }

aiVector3D triple(const std::vector<tinyobj::real_t>& values, int index) {
    return {values[3 * std::size_t(index)], values[3 * std::size_t(index) + 1], values[3 * std::size_t(index) + 2]};
}

// One run as assimp's reader builds it: a vertex per corner, in the faces'
// order; normals where any corner names one (the others zero) and uvs
// likewise, both dropped if an index is out of range.
aiMesh* run_mesh(const tinyobj::attrib_t& attrib, const tinyobj::mesh_t& shape, const FaceRun& run) {
    auto mesh = std::make_unique<aiMesh>();
    std::size_t corners = 0;
    bool any_normal = false, any_uv = false;
    for (std::size_t face = run.first_face; face < run.last_face; ++face) corners += shape.num_face_vertices[face];
    for (std::size_t c = 0; c < corners; ++c) {
        any_normal |= shape.indices[run.first_index + c].normal_index >= 0;
        any_uv |= shape.indices[run.first_index + c].texcoord_index >= 0;
    }
    mesh->mNumVertices = static_cast<unsigned>(corners);
    mesh->mVertices = new aiVector3D[corners];
    bool normals_valid = any_normal && !attrib.normals.empty();
    bool uvs_valid = any_uv && !attrib.texcoords.empty();
    if (normals_valid) mesh->mNormals = new aiVector3D[corners];
    if (uvs_valid) {
        mesh->mNumUVComponents[0] = 2;
        mesh->mTextureCoords[0] = new aiVector3D[corners];
    }
    const std::size_t vertex_count = attrib.vertices.size() / 3, normal_count = attrib.normals.size() / 3,
                      uv_count = attrib.texcoords.size() / 2;
    for (std::size_t c = 0; c < corners; ++c) {
        const tinyobj::index_t& corner = shape.indices[run.first_index + c];
        if (!in_range(corner.vertex_index, vertex_count))
            throw MeshFileError("a face's vertex index is out of range (" + std::to_string(vertex_count) +
                                " vertices)");
        mesh->mVertices[c] = triple(attrib.vertices, corner.vertex_index);
        if (normals_valid && corner.normal_index >= 0) {
            normals_valid = in_range(corner.normal_index, normal_count);
            if (normals_valid) mesh->mNormals[c] = triple(attrib.normals, corner.normal_index);
        }
        if (uvs_valid && corner.texcoord_index >= 0) {
            uvs_valid = in_range(corner.texcoord_index, uv_count);
            const std::size_t uv = 2 * std::size_t(corner.texcoord_index);
            if (uvs_valid) mesh->mTextureCoords[0][c] = {attrib.texcoords[uv], attrib.texcoords[uv + 1], 0.0f};
        }
    }
    if (any_normal && !normals_valid) {
        delete[] mesh->mNormals;
        mesh->mNormals = nullptr;
    }
    if (any_uv && !uvs_valid) {
        delete[] mesh->mTextureCoords[0];
        mesh->mTextureCoords[0] = nullptr;
        mesh->mNumUVComponents[0] = 0;
    }

    mesh->mNumFaces = static_cast<unsigned>(run.last_face - run.first_face);
    mesh->mFaces = new aiFace[mesh->mNumFaces];
    unsigned next = 0;
    for (std::size_t face = run.first_face; face < run.last_face; ++face) {
        aiFace& out = mesh->mFaces[face - run.first_face];
        out.mNumIndices = shape.num_face_vertices[face];
        out.mIndices = new unsigned[out.mNumIndices];
        for (unsigned i = 0; i < out.mNumIndices; ++i) out.mIndices[i] = next++;
        mesh->mPrimitiveTypes |= out.mNumIndices > 3 ? aiPrimitiveType_POLYGON : aiPrimitiveType_TRIANGLE;
    }
    mesh->mMaterialIndex = 0;
    return mesh.release();
}

void check_shape(const tinyobj::shape_t& shape) {
    if (!shape.lines.indices.empty() || !shape.points.indices.empty())
        throw MeshFileError("a line or a point ('l', 'p') cannot be triangulated");
    std::size_t indices = 0;
    for (unsigned char count : shape.mesh.num_face_vertices) indices += count;
    // tinyobjloader counts a face's vertices in a byte.
    if (indices != shape.mesh.indices.size())
        throw MeshFileError("a face of more than 255 vertices (tinyobjloader's limit)");
}

std::string one_line(std::string text) {
    for (char& c : text) {
        if (c == '\n' || c == '\r') c = ' ';
    }
    while (!text.empty() && text.back() == ' ') text.pop_back();
    return text;
}

std::string file_text(const std::string& path) {
    std::ifstream stream(path, std::ios::binary);
    std::ostringstream text;
    text << stream.rdbuf();
    if (!stream) throw MeshFileError("cannot read: " + path);
    return std::move(text).str();
}

// tinyobjloader reads a coordinate that is not a number ("nan", "inf",
// "x") as 0; assimp's reader kept the non-finite ones for wavepath to
// refuse. So every number of a "v", "vn" or "vt" statement must be one
// (std::from_chars) and finite.
void check_numbers(std::string_view text) {
    std::size_t line_number = 0;
    while (!text.empty()) {
        ++line_number;
        const std::size_t end = std::min(text.find('\n'), text.size());
        std::string_view line = text.substr(0, end);
        line = line.substr(0, line.find('#'));
        text.remove_prefix(std::min(end + 1, text.size()));
        auto next_token = [&line] {
            const std::size_t start = std::min(line.find_first_not_of(" \t\r"), line.size());
            line.remove_prefix(start);
            const std::size_t length = std::min(line.find_first_of(" \t\r"), line.size());
            const std::string_view token = line.substr(0, length);
            line.remove_prefix(length);
            return token;
        };
        const std::string_view statement = next_token();
        if (statement != "v" && statement != "vn" && statement != "vt") continue;
        for (std::string_view token = next_token(); !token.empty(); token = next_token()) {
            std::string_view digits = token.starts_with('+') ? token.substr(1) : token;
            float value = 0.0f;
            const auto [stop, status] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
            if (status != std::errc() || stop != digits.data() + digits.size() || !std::isfinite(value))
                throw MeshFileError("line " + std::to_string(line_number) + " (\"" + std::string(statement) +
                                    "\"): " + std::string(token) + " is not a finite number");
        }
    }
}

// Where tinyobjloader looks for "mtllib" files: the file's directory.
std::string directory(const std::string& path) {
    const std::size_t slash = path.find_last_of('/');
    return slash == std::string::npos ? "." : path.substr(0, slash);
}

// assimp's reader names the root after the file and an object without "o" or "g" "defaultobject".
std::string file_name(const std::string& path) { return path.substr(path.find_last_of('/') + 1); }

}  // namespace obj_reader
}  // namespace

bool TinyObjReader::CanRead(const std::string& file, Assimp::IOSystem* io, bool) const {
    // The statements assimp's own OBJ reader looks for in the first 200 bytes.
    static const char* kTokens[] = {"mtllib", "usemtl", "v ", "vt ", "vn ", "o ", "g ", "s ", "f "};
    return SearchFileHeaderForToken(io, file, kTokens, std::size(kTokens), 200, false, true);
}

const aiImporterDesc* TinyObjReader::GetInfo() const { return &obj_reader::kDescription; }

void TinyObjReader::InternReadFile(const std::string& file, aiScene* scene, Assimp::IOSystem*) {
    const std::string text = obj_reader::file_text(file);
    obj_reader::check_numbers(text);
    tinyobj::attrib_t attrib;
    std::vector<tinyobj::shape_t> shapes;
    std::vector<tinyobj::material_t> materials;
    std::string warning, error;
    std::istringstream stream(text);
    // Materials only for their names, which start meshes as in assimp's reader; not triangulated:
    // assimp's post-processing does, as for its own reader; no vertex colours.
    tinyobj::MaterialFileReader material_reader(obj_reader::directory(file));
    if (!tinyobj::LoadObj(&attrib, &shapes, &materials, &warning, &error, &stream, &material_reader, false, false))
        throw MeshFileError("tinyobjloader cannot read it: " + obj_reader::one_line(error));
    // tinyobjloader skips faces of one or two vertices, which assimp's reader kept for wavepath to refuse.
    if (warning.find("Degenerated face") != std::string::npos)
        throw MeshFileError("a face of fewer than 3 vertices (a point or a line) cannot be triangulated");

    std::vector<aiMesh*> meshes;
    std::vector<aiNode*> objects;
    auto release = [&] {
        for (aiMesh* mesh : meshes) delete mesh;
        for (aiNode* node : objects) delete node;
    };
    try {
        for (const tinyobj::shape_t& shape : shapes) {
            obj_reader::check_shape(shape);
            auto* node = new aiNode(shape.name.empty() ? "defaultobject" : shape.name);
            objects.push_back(node);
            const std::vector<obj_reader::FaceRun> runs = obj_reader::material_runs(shape.mesh);
            node->mNumMeshes = static_cast<unsigned>(runs.size());
            node->mMeshes = new unsigned[runs.size()];
            for (std::size_t r = 0; r < runs.size(); ++r) {
                node->mMeshes[r] = static_cast<unsigned>(meshes.size());
                meshes.push_back(obj_reader::run_mesh(attrib, shape.mesh, runs[r]));
            }
        }
    } catch (...) {
        release();
        throw;
    }
    scene->mRootNode = new aiNode(obj_reader::file_name(file));
    scene->mRootNode->addChildren(static_cast<unsigned>(objects.size()), objects.data());
    scene->mNumMeshes = static_cast<unsigned>(meshes.size());
    scene->mMeshes = new aiMesh*[meshes.size()];
    std::copy(meshes.begin(), meshes.end(), scene->mMeshes);
}

void use_tiny_obj_reader(Assimp::Importer& importer) {
    // UnregisterLoader hands assimp's reader back to the caller.
    const std::unique_ptr<Assimp::BaseImporter> assimps(importer.GetImporter("obj"));
    importer.UnregisterLoader(assimps.get());
    importer.RegisterLoader(new TinyObjReader);  // the importer owns it
}

}  // namespace wp
