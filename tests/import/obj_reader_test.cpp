// TinyObjReader (import/helper/obj_reader.h) in assimp gives the triangles
// assimp's own OBJ reader gave: after the same post-processing
// (triangulation, joined vertices), the same meshes, vertices, normals,
// uvs and faces in the same order, and the same nodes; on the bunny the
// same but for coordinates where assimp's number parser is not correctly
// rounded and tinyobjloader's is.
#include "import/helper/obj_reader.h"

#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <assimp/Importer.hpp>
#include <charconv>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

#include "support/mesh_files.h"
#include "support/temp_directory.h"

namespace wp::test {
namespace {

namespace fs = std::filesystem;

constexpr unsigned kPostProcessing = aiProcess_Triangulate | aiProcess_JoinIdenticalVertices;

// Quads (one concave), a pentagon, normals and uvs on some faces, negative
// indices, objects, a group and materials that change and change back.
constexpr const char* kVariedObj = R"(mtllib varied.mtl
v 0 0 0
v 1 0 0
v 1 1 0.2
v 0 1 0
v 0.5 0.5 1
v 2 0 0
v 2 1 0
v 0.9 0.2 0
vt 0 0
vt 1 0
vt 1 1
vt 0 1
vn 0 0 1
vn 0 1 0
o first
usemtl red
f 1/1/1 2/2/1 3/3/1 4/4/1
f 2/2/1 6/1/1 7/3/1 3/4/1
usemtl blue
f 1/1/2 2/2/2 5/3/2
usemtl red
f -8/1/1 -7/2/1 -4/3/1
g second
f 1//1 2//1 3//1 4//1 5//2
f 1 8 3 4
o third
usemtl blue
f 1/1 2/2 3/3
f 1/1 3/3 4/4
f 1 2 4 3
)";
constexpr const char* kVariedMtl = "newmtl red\nKd 1 0 0\nnewmtl blue\nKd 0 0 1\n";

const fs::path kMeshes = fs::path(WAVEPATH_SOURCE_DIR) / "scenes/meshes";

const aiScene* read(Assimp::Importer& importer, const fs::path& file) {
    const aiScene* scene = importer.ReadFile(file.string(), kPostProcessing);
    EXPECT_NE(scene, nullptr) << importer.GetErrorString();
    return scene;
}

// Compares the two scenes; coordinates of positions may differ where `position_differs` allows it.
void expect_same(const aiScene& tiny, const aiScene& assimps,
                 const std::function<bool(float tiny, float assimps)>& position_differs) {
    ASSERT_EQ(tiny.mNumMeshes, assimps.mNumMeshes);
    for (unsigned m = 0; m < tiny.mNumMeshes; ++m) {
        SCOPED_TRACE("mesh " + std::to_string(m));
        const aiMesh &a = *tiny.mMeshes[m], &b = *assimps.mMeshes[m];
        ASSERT_EQ(a.mNumVertices, b.mNumVertices);
        ASSERT_EQ(a.mNormals == nullptr, b.mNormals == nullptr);
        ASSERT_EQ(a.mTextureCoords[0] == nullptr, b.mTextureCoords[0] == nullptr);
        for (unsigned v = 0; v < a.mNumVertices; ++v) {
            for (unsigned axis = 0; axis < 3; ++axis) {
                const float x = a.mVertices[v][axis], y = b.mVertices[v][axis];
                if (std::memcmp(&x, &y, sizeof x) != 0) {
                    EXPECT_TRUE(position_differs(x, y)) << x << " " << y;
                }
                if (a.mNormals) {
                    EXPECT_EQ(a.mNormals[v][axis], b.mNormals[v][axis]);
                }
            }
            if (a.mTextureCoords[0]) {
                EXPECT_EQ(a.mTextureCoords[0][v].x, b.mTextureCoords[0][v].x);
                EXPECT_EQ(a.mTextureCoords[0][v].y, b.mTextureCoords[0][v].y);
            }
        }
        ASSERT_EQ(a.mNumFaces, b.mNumFaces);
        for (unsigned f = 0; f < a.mNumFaces; ++f) {
            ASSERT_EQ(a.mFaces[f].mNumIndices, b.mFaces[f].mNumIndices);
            for (unsigned i = 0; i < a.mFaces[f].mNumIndices; ++i)
                EXPECT_EQ(a.mFaces[f].mIndices[i], b.mFaces[f].mIndices[i]);
        }
    }
    std::function<void(const aiNode&, const aiNode&)> same_nodes = [&](const aiNode& a, const aiNode& b) {
        EXPECT_STREQ(a.mName.C_Str(), b.mName.C_Str());
        ASSERT_EQ(a.mNumMeshes, b.mNumMeshes);
        for (unsigned i = 0; i < a.mNumMeshes; ++i) EXPECT_EQ(a.mMeshes[i], b.mMeshes[i]);
        ASSERT_EQ(a.mNumChildren, b.mNumChildren);
        for (unsigned i = 0; i < a.mNumChildren; ++i) same_nodes(*a.mChildren[i], *b.mChildren[i]);
    };
    same_nodes(*tiny.mRootNode, *assimps.mRootNode);
}

void expect_as_assimps_reader(const fs::path& file, const std::function<bool(float, float)>& position_differs) {
    Assimp::Importer tiny, assimps;
    use_tiny_obj_reader(tiny);
    const aiScene* a = read(tiny, file);
    const aiScene* b = read(assimps, file);
    ASSERT_TRUE(a && b);
    expect_same(*a, *b, position_differs);
}

TEST(TinyObjReader, GivesAssimpsReadersScene) {
    const TempDirectory dir("obj");
    write_text(dir.path() / "varied.obj", kVariedObj);
    write_text(dir.path() / "varied.mtl", kVariedMtl);
    const auto never = [](float, float) { return false; };
    for (const fs::path& file : {dir.path() / "varied.obj", kMeshes / "cornell_box.obj"}) {
        SCOPED_TRACE(file.string());
        expect_as_assimps_reader(file, never);
    }
}

// The bunny's coordinates as the nearest floats (std::from_chars), which tinyobjloader reads and assimp does not.
std::vector<float> correctly_rounded_coordinates(const fs::path& obj) {
    std::ifstream stream(obj);
    std::vector<float> values;
    for (std::string line; std::getline(stream, line);) {
        if (!line.starts_with("v ")) continue;
        std::istringstream words(line.substr(2));
        for (std::string word; words >> word;) {
            float value = 0.0f;
            std::from_chars(word.data(), word.data() + word.size(), value);
            values.push_back(value);
        }
    }
    return values;
}

TEST(TinyObjReader, GivesAssimpsReadersBunnyWithCorrectlyRoundedCoordinates) {
    const fs::path bunny = kMeshes / "bunny.obj";
    const std::vector<float> nearest = correctly_rounded_coordinates(bunny);
    int differing = 0;
    // Where the two differ, tinyobjloader's is the nearest float to the file's number, assimp's one ulp off.
    expect_as_assimps_reader(bunny, [&](float tiny, float assimps) {
        ++differing;
        return std::nextafter(tiny, assimps) == assimps &&
               std::find(nearest.begin(), nearest.end(), tiny) != nearest.end();
    });
    EXPECT_GT(differing, 0);  // else the comparison above would not have been tried
}

}  // namespace
}  // namespace wp::test
