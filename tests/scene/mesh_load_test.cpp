// Mesh shapes: every file format, each transform form, normals, degenerate
// triangles, mesh lights, rebasing, and one exact message per bad mesh.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>
#include <numbers>
#include <string>

#include "scene/scene.h"
#include "support/mesh_files.h"

namespace wp::test {
namespace {

namespace fs = std::filesystem;

// Camera at the origin, so that positions stay as the mesh and transform say.
constexpr const char* kSceneTemplate = R"({
  "camera": {"position": [0, 0, 0], "look_at": [0, 0, -1], "fov_y": 40, "width": 8, "height": 8},
  "materials": {
    "white": {"type": "diffuse", "albedo": [0.5, 0.5, 0.5]},
    "lamp": {"type": "emitter", "radiance": [4, 2, 1]},
    "two_sided_lamp": {"type": "emitter", "radiance": [4, 2, 1], "two_sided": true}
  },
  "shapes": []
})";

class MeshLoad : public ::testing::Test {
 protected:
    MeshLoad() {
        const auto* test = ::testing::UnitTest::GetInstance()->current_test_info();
        std::string name = std::string(test->test_suite_name()) + "-" + test->name();
        std::replace(name.begin(), name.end(), '/', '-');  // parameterised tests' names hold slashes
        dir_ = fs::temp_directory_path() / ("wavepath-mesh-" + name + "-" + std::to_string(::getpid()));
        fs::remove_all(dir_);
        fs::create_directories(dir_);
    }
    ~MeshLoad() override { fs::remove_all(dir_); }

    void write(const std::string& name, const std::string& bytes) const { write_file(dir_ / name, bytes); }

    // Writes the template scene with these shapes (JSON texts) and loads it.
    Scene load(std::initializer_list<const char*> shapes, const char* camera_position = "[0, 0, 0]") const {
        nlohmann::json scene = nlohmann::json::parse(kSceneTemplate);
        scene["camera"]["position"] = nlohmann::json::parse(camera_position);
        for (const char* shape : shapes) scene["shapes"].push_back(nlohmann::json::parse(shape));
        write("scene.json", scene.dump(2));
        return load_scene(scene_path());
    }
    Mesh load_one(const char* shape) const {
        Scene scene = load({shape});
        EXPECT_EQ(scene.meshes.size(), 1u);
        return scene.meshes.at(0);
    }
    std::string scene_path() const { return (dir_ / "scene.json").string(); }

    fs::path dir_;
};

double total_area(const Mesh& mesh) {
    double area = 0.0;
    for (const glm::uvec3& t : mesh.triangles) {
        const glm::dvec3& p0 = mesh.positions[t.x];
        area += 0.5 * glm::length(glm::cross(mesh.positions[t.y] - p0, mesh.positions[t.z] - p0));
    }
    return area;
}

glm::dvec3 face_normal(const Mesh& mesh, const glm::uvec3& t) {
    const glm::dvec3& p0 = mesh.positions[t.x];
    return glm::normalize(glm::cross(mesh.positions[t.y] - p0, mesh.positions[t.z] - p0));
}

// The unit square after loading: two triangles of total area 1 in z = 0,
// both counter-clockwise seen from +z, corners in [0, 1]^2.
void expect_unit_square(const Mesh& mesh) {
    ASSERT_EQ(mesh.triangles.size(), 2u);
    EXPECT_EQ(mesh.degenerate_dropped, 0u);
    EXPECT_DOUBLE_EQ(total_area(mesh), 1.0);
    for (const glm::uvec3& t : mesh.triangles) EXPECT_EQ(face_normal(mesh, t), glm::dvec3(0, 0, 1));
    for (const glm::dvec3& p : mesh.positions) {
        EXPECT_TRUE(p.x == 0.0 || p.x == 1.0) << p.x;
        EXPECT_TRUE(p.y == 0.0 || p.y == 1.0) << p.y;
        EXPECT_EQ(p.z, 0.0);
    }
}

// The position that a file corner (x, y, 0) of the square became.
glm::dvec3 loaded_corner(const Mesh& mesh, std::size_t file_index) {
    // Joining identical vertices keeps the first occurrence's order: OBJ corners stay in file order.
    EXPECT_EQ(mesh.positions.size(), 4u);
    return mesh.positions.at(file_index);
}

void expect_near(const glm::dvec3& actual, const glm::dvec3& expected, double tolerance = 1e-12) {
    EXPECT_NEAR(actual.x, expected.x, tolerance);
    EXPECT_NEAR(actual.y, expected.y, tolerance);
    EXPECT_NEAR(actual.z, expected.z, tolerance);
}

// ---- formats ----

struct FormatCase {
    const char* name;
    const char* file;
    std::string (*contents)();
    bool has_normals;
};

const FormatCase kFormats[] = {
    {"Obj", "square.obj", [] { return std::string(kSquareObj); }, false},
    {"PlyAscii", "square.ply", [] { return std::string(kSquarePlyAscii); }, true},
    {"PlyBinary", "square.ply", square_ply_binary, false},
    {"Off", "square.off", [] { return std::string(kSquareOff); }, false},
    {"StlAscii", "square.stl", [] { return std::string(kSquareStlAscii); }, true},  // facet normals
    {"StlBinary", "square.stl", square_stl_binary, true},
};

class MeshFormat : public MeshLoad, public ::testing::WithParamInterface<FormatCase> {};

TEST_P(MeshFormat, LoadsTheUnitSquare) {
    const FormatCase& c = GetParam();
    write(c.file, c.contents());
    const std::string shape = std::string(R"({"type": "mesh", "material": "white", "file": ")") + c.file + "\"}";
    Mesh mesh = load_one(shape.c_str());
    EXPECT_EQ(mesh.file, c.file);
    expect_unit_square(mesh);
    if (c.has_normals) {
        ASSERT_EQ(mesh.normals.size(), mesh.positions.size());
        for (const glm::dvec3& n : mesh.normals) EXPECT_EQ(n, glm::dvec3(0, 0, 1));
    } else {
        EXPECT_TRUE(mesh.normals.empty());
    }
}

INSTANTIATE_TEST_SUITE_P(Formats, MeshFormat, ::testing::ValuesIn(kFormats),
                         [](const auto& info) { return std::string(info.param.name); });

TEST_F(MeshLoad, MaterialIsResolvedByName) {
    write("square.obj", kSquareObj);
    Scene scene = load({R"({"type": "mesh", "file": "square.obj", "material": "white"})"});
    EXPECT_EQ(scene.materials.at(scene.meshes.at(0).material).name, "white");
}

TEST_F(MeshLoad, GltfNodeGraphIsMergedWithNodeTransforms) {
    write("squares.gltf", two_squares_gltf());
    Mesh mesh = load_one(R"({"type": "mesh", "file": "squares.gltf", "material": "white"})");
    ASSERT_EQ(mesh.triangles.size(), 4u);
    EXPECT_DOUBLE_EQ(total_area(mesh), 2.0);
    double min_x = 1e9, max_x = -1e9;
    for (const glm::dvec3& p : mesh.positions) min_x = std::min(min_x, p.x), max_x = std::max(max_x, p.x);
    EXPECT_EQ(min_x, 0.0);
    EXPECT_EQ(max_x, 3.0);  // the "right" node's translation by 2
    for (const glm::uvec3& t : mesh.triangles) EXPECT_EQ(face_normal(mesh, t), glm::dvec3(0, 0, 1));
}

TEST_F(MeshLoad, ObjectsSelectNamedNodes) {
    write("squares.gltf", two_squares_gltf());
    Mesh mesh = load_one(R"({"type": "mesh", "file": "squares.gltf", "material": "white", "objects": ["right"]})");
    ASSERT_EQ(mesh.triangles.size(), 2u);
    for (const glm::uvec3& t : mesh.triangles) EXPECT_GE(mesh.positions[t.x].x, 2.0);

    write("parts.obj", "o a\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\no b\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\nf 4 5 6 7\n");
    EXPECT_EQ(load_one(R"({"type": "mesh", "file": "parts.obj", "material": "white"})").triangles.size(), 3u);
    EXPECT_EQ(
        load_one(R"({"type": "mesh", "file": "parts.obj", "material": "white", "objects": ["b"]})").triangles.size(),
        2u);
    EXPECT_EQ(load_one(R"({"type": "mesh", "file": "parts.obj", "material": "white", "objects": ["b", "a"]})")
                  .triangles.size(),
              3u);
}

// ---- transforms ----

TEST_F(MeshLoad, TranslateRotateScaleApplyInThatOrderAfterScale) {
    write("square.obj", kSquareObj);
    // (1, 0, 0): scaled by 2 -> (2, 0, 0), rotated 90 degrees about z -> (0, 2, 0), translated -> (10, 2, 0).
    Mesh mesh = load_one(R"({"type": "mesh", "file": "square.obj", "material": "white",
        "transform": {"translate": [10, 0, 0], "rotate": [0, 0, 1, 90], "scale": 2}})");
    expect_near(loaded_corner(mesh, 1), {10, 2, 0});
    expect_near(loaded_corner(mesh, 2), {8, 2, 0});
    EXPECT_NEAR(total_area(mesh), 4.0, 1e-12);
}

TEST_F(MeshLoad, EachTransformKeyAlone) {
    write("square.obj", kSquareObj);
    expect_near(loaded_corner(load_one(R"({"type": "mesh", "file": "square.obj", "material": "white",
                                   "transform": {"translate": [1, 2, 3]}})"),
                              2),
                {2, 3, 3});
    expect_near(loaded_corner(load_one(R"({"type": "mesh", "file": "square.obj", "material": "white",
                                   "transform": {"rotate": [1, 0, 0, 90]}})"),
                              2),
                {1, 0, 1});
    expect_near(loaded_corner(load_one(R"({"type": "mesh", "file": "square.obj", "material": "white",
                                   "transform": {"scale": [2, 3, 4]}})"),
                              2),
                {2, 3, 0});
}

TEST_F(MeshLoad, MatrixIsRowMajor) {
    write("square.obj", kSquareObj);
    // A quarter turn about z and a translation in the last column: (1, 0, 0) -> (0, 1, 0) + (5, 6, 7).
    Mesh mesh = load_one(R"({"type": "mesh", "file": "square.obj", "material": "white",
        "transform": {"matrix": [[0, -1, 0, 5], [1, 0, 0, 6], [0, 0, 1, 7], [0, 0, 0, 1]]}})");
    EXPECT_EQ(loaded_corner(mesh, 1), glm::dvec3(5, 7, 7));
    EXPECT_EQ(loaded_corner(mesh, 3), glm::dvec3(4, 6, 7));
}

TEST_F(MeshLoad, MirroringKeepsTheFrontSide) {
    write("square.obj", kSquareObj);
    Mesh mesh = load_one(R"({"type": "mesh", "file": "square.obj", "material": "white",
        "transform": {"scale": [-1, 1, 1]}})");
    ASSERT_EQ(mesh.triangles.size(), 2u);
    for (const glm::uvec3& t : mesh.triangles) EXPECT_EQ(face_normal(mesh, t), glm::dvec3(0, 0, 1));
}

TEST_F(MeshLoad, CameraRebasesMeshPositions) {
    write("square.obj", kSquareObj);
    Scene scene = load({R"({"type": "mesh", "file": "square.obj", "material": "white"})"}, "[10, 20, 30]");
    EXPECT_EQ(scene.world_offset, glm::dvec3(10, 20, 30));
    EXPECT_EQ(scene.meshes.at(0).positions.at(2), glm::dvec3(1 - 10, 1 - 20, 0 - 30));
}

// ---- normals ----

// A triangle in the plane x = y with vertex normals (1, -1, 0) / sqrt 2.
constexpr const char* kDiagonalObj = "v 0 0 0\nv 1 1 0\nv 0 0 1\nvn 0.70710678 -0.70710678 0\nf 1//1 2//1 3//1\n";

TEST_F(MeshLoad, NormalsTransformByTheInverseTransposeAndAreUnitLength) {
    write("diagonal.obj", kDiagonalObj);
    Mesh mesh = load_one(R"({"type": "mesh", "file": "diagonal.obj", "material": "white",
        "transform": {"scale": [2, 1, 1]}})");
    // The plane x = y becomes x = 2y, normal (1, -2, 0) / sqrt 5: the inverse transpose diag(1/2, 1, 1)
    // gives that; the matrix itself would give (2, -1, 0) / sqrt 5.
    ASSERT_EQ(mesh.normals.size(), 3u);
    for (const glm::dvec3& n : mesh.normals) expect_near(n, glm::dvec3(1, -2, 0) / std::sqrt(5.0));
    // Perpendicular to the transformed surface.
    for (const glm::dvec3& n : mesh.normals) EXPECT_NEAR(glm::dot(n, mesh.positions[1] - mesh.positions[0]), 0, 1e-7);
}

TEST_F(MeshLoad, RotationTurnsNormals) {
    write("square.ply", kSquarePlyAscii);
    Mesh mesh = load_one(R"({"type": "mesh", "file": "square.ply", "material": "white",
        "transform": {"rotate": [1, 0, 0, 90]}})");
    ASSERT_EQ(mesh.normals.size(), 4u);
    for (const glm::dvec3& n : mesh.normals) expect_near(n, {0, -1, 0});
}

TEST_F(MeshLoad, FaceNormalsLeaveNormalsEmpty) {
    write("square.ply", kSquarePlyAscii);
    Mesh mesh = load_one(R"({"type": "mesh", "file": "square.ply", "material": "white", "face_normals": true})");
    EXPECT_TRUE(mesh.normals.empty());
    expect_unit_square(mesh);
}

TEST_F(MeshLoad, FaceNormalsAcceptAFileWithZeroNormals) {
    write("mesh.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nvn 0 0 0\nf 1//1 2//1 3//1\n");
    EXPECT_EQ(
        load_one(R"({"type": "mesh", "file": "mesh.obj", "material": "white", "face_normals": true})").triangles.size(),
        1u);
}

TEST_F(MeshLoad, NormalsOnlyWhenEveryVertexHasOne) {
    // Object a has normals, object b has none: the merged mesh has none.
    write("mixed.obj",
          "o a\nv 0 0 0\nv 1 0 0\nv 1 1 0\nvn 0 0 1\nf 1//1 2//1 3//1\no b\nv 0 0 1\nv 1 0 1\nv 1 1 1\nf 4 5 6\n");
    Mesh mesh = load_one(R"({"type": "mesh", "file": "mixed.obj", "material": "white"})");
    EXPECT_EQ(mesh.triangles.size(), 2u);
    EXPECT_TRUE(mesh.normals.empty());
}

// Texture coordinates as Mitsuba 3.9.1 reports them (si.uv): an OBJ's v
// turned upside down, a PLY's as stored.
TEST_F(MeshLoad, UvsAsMitsubaReadsThem) {
    write("uv.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nvt 0.25 0.125\nvt 1 0\nvt 0.5 0.75\nf 1/1 2/2 3/3\n");
    Mesh obj = load_one(R"({"type": "mesh", "file": "uv.obj", "material": "white"})");
    ASSERT_EQ(obj.uvs.size(), 3u);
    EXPECT_EQ(obj.uvs[0], glm::dvec2(0.25, 0.875));
    EXPECT_EQ(obj.uvs[2], glm::dvec2(0.5, 0.25));
    write("uv.ply",
          "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
          "property float u\nproperty float v\nelement face 1\nproperty list uchar int vertex_indices\n"
          "end_header\n0 0 0 0.25 0.125\n1 0 0 1 0\n1 1 0 0.5 0.75\n3 0 1 2\n");
    Mesh ply = load_one(R"({"type": "mesh", "file": "uv.ply", "material": "white"})");
    ASSERT_EQ(ply.uvs.size(), 3u);
    EXPECT_EQ(ply.uvs[0], glm::dvec2(0.25, 0.125));
    EXPECT_EQ(ply.uvs[2], glm::dvec2(0.5, 0.75));
}

TEST_F(MeshLoad, UvsOnlyWhenEveryVertexHasOne) {
    write("mixed.obj",
          "o a\nv 0 0 0\nv 1 0 0\nv 1 1 0\nvt 0 0\nf 1/1 2/1 3/1\no b\nv 0 0 1\nv 1 0 1\nv 1 1 1\nf 4 5 6\n");
    EXPECT_TRUE(load_one(R"({"type": "mesh", "file": "mixed.obj", "material": "white"})").uvs.empty());
}

// ---- degenerate triangles ----

TEST_F(MeshLoad, ZeroAreaTrianglesAreDroppedAndCounted) {
    // A good triangle, a collinear one and one with a repeated corner.
    write("mesh.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 2 0 0\nf 1 2 3\nf 1 2 4\nf 1 1 3\n");
    Mesh mesh = load_one(R"({"type": "mesh", "file": "mesh.obj", "material": "white"})");
    ASSERT_EQ(mesh.triangles.size(), 1u);
    EXPECT_EQ(mesh.degenerate_dropped, 2u);
    EXPECT_DOUBLE_EQ(total_area(mesh), 0.5);
}

TEST_F(MeshLoad, AreaIsJudgedAfterTheTransform) {
    // 1e-30 * 1e-300 underflows to 0 in double: flat in world space, though not in the file.
    write("mesh.obj", "v 0 0 0\nv 1 0 0\nv 0 1e-30 0\nv 0 0 1\nf 1 2 3\nf 1 2 4\n");
    Mesh mesh = load_one(R"({"type": "mesh", "file": "mesh.obj", "material": "white",
        "transform": {"scale": [1, 1e-300, 1]}})");
    EXPECT_EQ(mesh.triangles.size(), 1u);
    EXPECT_EQ(mesh.degenerate_dropped, 1u);
}

// ---- lights ----

TEST_F(MeshLoad, EmittingMeshIsALightWithItsPower) {
    write("square.obj", kSquareObj);
    Scene scene = load({R"({"type": "quad", "corner": [0, 5, 0], "edge1": [1, 0, 0], "edge2": [0, 0, 1],
                            "material": "lamp"})",
                        R"({"type": "mesh", "file": "square.obj", "material": "white"})",
                        R"({"type": "mesh", "file": "square.obj", "material": "lamp", "transform": {"scale": 2}})",
                        R"({"type": "mesh", "file": "square.obj", "material": "two_sided_lamp"})"});
    const double luminance = 0.2126 * 4 + 0.7152 * 2 + 0.0722 * 1;
    const double unit_power = std::numbers::pi * luminance;
    ASSERT_EQ(scene.lights.size(), 3u);
    EXPECT_EQ(scene.lights[0].shape, ShapeType::Quad);
    EXPECT_EQ(scene.lights[1].shape, ShapeType::Mesh);
    EXPECT_EQ(scene.lights[1].index, 1);
    EXPECT_NEAR(scene.lights[1].power, 4 * unit_power, 1e-12);  // area 4
    EXPECT_EQ(scene.lights[2].shape, ShapeType::Mesh);
    EXPECT_EQ(scene.lights[2].index, 2);
    EXPECT_NEAR(scene.lights[2].power, 2 * unit_power, 1e-12);  // area 1, two sides
    ASSERT_EQ(scene.light_cdf.size(), 3u);
    EXPECT_NEAR(scene.light_cdf[0], 1.0 / 7.0, 1e-15);
    EXPECT_NEAR(scene.light_cdf[1], 5.0 / 7.0, 1e-15);
    EXPECT_EQ(scene.light_cdf[2], 1.0);
    FeatureSet features = scene.features();
    EXPECT_TRUE(features.meshes);
    EXPECT_TRUE(features.mesh_lights);
}

TEST_F(MeshLoad, DiffuseMeshIsNoLight) {
    write("square.obj", kSquareObj);
    Scene scene = load({R"({"type": "mesh", "file": "square.obj", "material": "white"})"});
    EXPECT_TRUE(scene.lights.empty());
    FeatureSet features = scene.features();
    EXPECT_TRUE(features.meshes);
    EXPECT_FALSE(features.mesh_lights);
    EXPECT_FALSE(load_scene(std::string(WAVEPATH_SOURCE_DIR) + "/scenes/cornell.json").features().meshes);
}

// ---- bad meshes (the rest are the corpus's: tests/corpus/bad/scenes) ----

TEST_F(MeshLoad, DirectoryIsNotAMeshFile) {
    fs::create_directory(dir_ / "meshes");
    try {
        load({R"({"type": "mesh", "file": "meshes", "material": "white"})"});
        FAIL() << "no error";
    } catch (const SceneError& error) {
        EXPECT_EQ(std::string(error.what()), scene_path() + ": shapes[0].file: meshes: cannot read: Is a directory");
    }
}

// ---- bad mesh keys ----

struct KeyCase {
    const char* name;
    const char* shape;
    const char* message;  // after "<scene file>: "
};

#define SQUARE R"("type": "mesh", "file": "square.obj", "material": "white")"

const KeyCase kKeyCases[] = {
    {"UnknownKey", "{" SQUARE R"(, "normals": true})",
     "shapes[0].normals: unknown key (expected one of: type, file, material, transform, face_normals, objects)"},
    {"MissingFile", R"({"type": "mesh", "material": "white"})", "shapes[0].file: missing required key"},
    {"EmptyFile", R"({"type": "mesh", "file": "", "material": "white"})", "shapes[0].file: must not be empty"},
    {"FileNotAString", R"({"type": "mesh", "file": 3, "material": "white"})",
     "shapes[0].file: must be a string, got number"},
    {"UndefinedMaterial", R"({"type": "mesh", "file": "square.obj", "material": "gold"})",
     R"(shapes[0].material: undefined material "gold" (defined: lamp, two_sided_lamp, white))"},
    {"UnknownTransformKey", "{" SQUARE R"(, "transform": {"shear": 1}})",
     "shapes[0].transform.shear: unknown key (expected one of: translate, rotate, scale, matrix)"},
    {"MatrixWithTranslate",
     "{" SQUARE R"(, "transform": {"translate": [1, 0, 0], "matrix": [[1,0,0,0],[0,1,0,0],[0,0,1,0],[0,0,0,1]]}})",
     "shapes[0].transform.matrix: cannot be combined with translate, rotate or scale"},
    {"MatrixNotAffine", "{" SQUARE R"(, "transform": {"matrix": [[1,0,0,0],[0,1,0,0],[0,0,1,0],[0,0,1,1]]}})",
     "shapes[0].transform.matrix[3]: must be [0, 0, 0, 1] (affine transforms only)"},
    {"MatrixSingular", "{" SQUARE R"(, "transform": {"matrix": [[1,0,0,0],[0,1,0,0],[0,0,0,0],[0,0,0,1]]}})",
     "shapes[0].transform.matrix: must be invertible (its 3x3 part is singular)"},
    {"MatrixThreeRows", "{" SQUARE R"(, "transform": {"matrix": [[1,0,0,0],[0,1,0,0],[0,0,1,0]]}})",
     "shapes[0].transform.matrix: must be an array of 4 rows, got 3 elements"},
    {"MatrixShortRow", "{" SQUARE R"(, "transform": {"matrix": [[1,0,0,0],[0,1,0],[0,0,1,0],[0,0,0,1]]}})",
     "shapes[0].transform.matrix[1]: must be an array of 4 numbers, got 3 elements"},
    {"ZeroScale", "{" SQUARE R"(, "transform": {"scale": 0}})", "shapes[0].transform.scale: must not be 0"},
    {"ZeroScaleComponent", "{" SQUARE R"(, "transform": {"scale": [1, 0, 1]}})",
     "shapes[0].transform.scale[1]: must not be 0"},
    {"ScaleNotANumber", "{" SQUARE R"(, "transform": {"scale": "big"}})",
     "shapes[0].transform.scale: must be a number or an array of 3 numbers, got string"},
    {"RotateWithoutAngle", "{" SQUARE R"(, "transform": {"rotate": [0, 1, 0]}})",
     "shapes[0].transform.rotate: must be an array of 4 numbers, got 3 elements"},
    {"RotateZeroAxis", "{" SQUARE R"(, "transform": {"rotate": [0, 0, 0, 90]}})",
     "shapes[0].transform.rotate: the axis (the first 3 numbers) must not be zero-length"},
    {"TranslateTooFar", "{" SQUARE R"(, "transform": {"translate": [0, 0, 1e13]}})",
     "shapes[0].transform.translate[2]: magnitude must be <= 1e+12, got 1e+13"},
    {"FaceNormalsNotABoolean", "{" SQUARE R"(, "face_normals": 1})",
     "shapes[0].face_normals: must be a boolean, got number"},
    {"NoObjects", "{" SQUARE R"(, "objects": []})",
     "shapes[0].objects: must name at least one object (leave it out to load all)"},
};

class BadMeshKey : public MeshLoad, public ::testing::WithParamInterface<KeyCase> {};

TEST_P(BadMeshKey, FailsWithItsMessage) {
    const KeyCase& c = GetParam();
    write("square.obj", kSquareObj);
    try {
        load({c.shape});
        FAIL() << "no error";
    } catch (const SceneError& error) {
        EXPECT_EQ(std::string(error.what()), scene_path() + ": " + c.message);
    }
}

INSTANTIATE_TEST_SUITE_P(MeshKeys, BadMeshKey, ::testing::ValuesIn(kKeyCases),
                         [](const auto& info) { return std::string(info.param.name); });

// ---- bundled meshes ----

const std::string kSceneDir = std::string(WAVEPATH_SOURCE_DIR) + "/scenes/";

// setup.sh links scenes/meshes/bunny.obj to glmark2-data's bunny.
TEST_F(MeshLoad, StanfordBunny) {
    const std::string bunny = kSceneDir + "meshes/bunny.obj";
    ASSERT_TRUE(fs::exists(bunny)) << bunny << " is missing: run scripts/setup.sh";
    const std::string shape = R"({"type": "mesh", "material": "white", "file": ")" + bunny + "\"}";
    const auto start = std::chrono::steady_clock::now();
    Mesh mesh = load_one(shape.c_str());
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    EXPECT_EQ(mesh.triangles.size() + mesh.degenerate_dropped, 69666u);
    EXPECT_EQ(mesh.triangles.size(), 69666u);
    EXPECT_EQ(mesh.positions.size(), 34835u);
    EXPECT_TRUE(mesh.normals.empty());
    for (const glm::dvec3& p : mesh.positions) EXPECT_LE(std::fabs(p.x) + std::fabs(p.y) + std::fabs(p.z), 3.0);
    std::printf("bunny: %zu triangles, %zu degenerate dropped, loaded in %.3f s\n", mesh.triangles.size(),
                mesh.degenerate_dropped, seconds);
}

// Each quad of cornell.json is two triangles of cornell_mesh.json with the
// same material and orientation (within float: assimp reads coordinates as float).
TEST(BundledMeshScenes, CornellMeshIsTheQuadCornell) {
    const Scene quads = load_scene(kSceneDir + "cornell.json");
    const Scene meshes = load_scene(kSceneDir + "cornell_mesh.json");
    std::vector<std::pair<const Mesh*, glm::uvec3>> triangles;
    for (const Mesh& mesh : meshes.meshes) {
        EXPECT_EQ(mesh.degenerate_dropped, 0u);
        EXPECT_TRUE(mesh.normals.empty());
        for (const glm::uvec3& t : mesh.triangles) triangles.emplace_back(&mesh, t);
    }
    ASSERT_EQ(triangles.size(), 2 * quads.quads.size());
    auto near = [](const glm::dvec3& a, const glm::dvec3& b) { return glm::length(a - b) < 1e-3; };
    for (const Quad& q : quads.quads) {
        const glm::dvec3 corners[2][3] = {{q.corner, q.corner + q.edge1, q.corner + q.edge1 + q.edge2},
                                          {q.corner, q.corner + q.edge1 + q.edge2, q.corner + q.edge2}};
        for (const auto& corner : corners) {
            auto same = [&](const auto& entry) {
                const auto& [mesh, t] = entry;
                return near(mesh->positions[t.x], corner[0]) && near(mesh->positions[t.y], corner[1]) &&
                       near(mesh->positions[t.z], corner[2]);
            };
            auto found = std::find_if(triangles.begin(), triangles.end(), same);
            ASSERT_NE(found, triangles.end()) << "no triangle for a quad at " << q.corner.x << ", " << q.corner.z;
            EXPECT_EQ(meshes.materials[found->first->material].name, quads.materials[q.material].name);
        }
    }
    ASSERT_EQ(meshes.lights.size(), 1u);
    EXPECT_EQ(meshes.lights[0].shape, ShapeType::Mesh);
    EXPECT_NEAR(meshes.lights[0].power, quads.lights.at(0).power, 1e-6 * quads.lights[0].power);
}

}  // namespace
}  // namespace wp::test
