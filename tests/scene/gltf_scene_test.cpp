// glTF 2.0 files as scenes (scene/gltf_scene.h; docs/scene-format.md, "glTF
// scenes"): the glTF scenes of scenes/test/gltf/ make the same Scene as the
// JSON written by hand beside each (so they render the same image), each
// material rule of the mapping, and the one-line errors.
#include "scene/gltf_scene.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "image/image_io.h"
#include "scene/limits.h"
#include "scene/scene_writer.h"
#include "support/temp_directory.h"

namespace wp::test {
namespace {
// A namespace of its own: the sanitizer build compiles test files together (unity).
namespace gltf_scene_test {

namespace fs = std::filesystem;

const fs::path kScenes = fs::path(WAVEPATH_SOURCE_DIR) / "scenes/test/gltf";

void expect_near(const glm::dvec3& a, const glm::dvec3& b, double tolerance) {
    EXPECT_NEAR(a.x, b.x, tolerance);
    EXPECT_NEAR(a.y, b.y, tolerance);
    EXPECT_NEAR(a.z, b.z, tolerance);
}

void expect_same_material(const Material& a, const Material& b) {
    SCOPED_TRACE(a.name);
    EXPECT_EQ(a.name, b.name);
    EXPECT_EQ(a.type, b.type);
    EXPECT_EQ(a.albedo, b.albedo);
    EXPECT_EQ(a.emission, b.emission);
    EXPECT_EQ(a.two_sided, b.two_sided);
    EXPECT_EQ(a.ior, b.ior);
    EXPECT_EQ(a.eta, b.eta);
    EXPECT_EQ(a.k, b.k);
    EXPECT_EQ(a.specular_reflectance, b.specular_reflectance);
    EXPECT_EQ(a.distribution, b.distribution);
    EXPECT_EQ(a.alpha_u, b.alpha_u);
    EXPECT_EQ(a.alpha_v, b.alpha_v);
    EXPECT_EQ(a.nonlinear, b.nonlinear);
    EXPECT_EQ(a.textures, b.textures);
}

// Everything the renderers read; the camera's angles (which go through
// assimp's float horizontal field of view) and, after a camera placed
// within `tolerance`, the camera-relative positions within `tolerance`.
void expect_same_scene(const Scene& gltf, const Scene& json, double tolerance) {
    EXPECT_EQ(gltf.camera.width, json.camera.width);
    EXPECT_EQ(gltf.camera.height, json.camera.height);
    EXPECT_NEAR(gltf.camera.fov_y_degrees, json.camera.fov_y_degrees, 1e-5);
    expect_near(gltf.camera.position, json.camera.position, tolerance);
    expect_near(gltf.camera.look_at, json.camera.look_at, tolerance);
    expect_near(gltf.camera.up, json.camera.up, 1e-12);
    expect_near(gltf.world_offset, json.world_offset, tolerance);
    EXPECT_EQ(gltf.background, json.background);
    ASSERT_EQ(gltf.directional_lights.size(), json.directional_lights.size());
    for (std::size_t l = 0; l < gltf.directional_lights.size(); ++l) {
        EXPECT_EQ(gltf.directional_lights[l].direction, json.directional_lights[l].direction);
        EXPECT_EQ(gltf.directional_lights[l].irradiance, json.directional_lights[l].irradiance);
    }
    ASSERT_EQ(gltf.point_lights.size(), json.point_lights.size());
    for (std::size_t l = 0; l < gltf.point_lights.size(); ++l) {
        const PointLight &a = gltf.point_lights[l], &b = json.point_lights[l];
        expect_near(a.position, b.position, tolerance);
        EXPECT_EQ(a.intensity, b.intensity);
        ASSERT_EQ(a.cone.has_value(), b.cone.has_value());
        if (!a.cone) continue;
        expect_near(a.cone->axis, b.cone->axis, 1e-12);
        EXPECT_NEAR(a.cone->cutoff_angle, b.cone->cutoff_angle, 1e-12);
        EXPECT_NEAR(a.cone->beam_width, b.cone->beam_width, 1e-12);
    }
    ASSERT_EQ(gltf.meshes.size(), json.meshes.size());
    for (std::size_t m = 0; m < gltf.meshes.size(); ++m) {
        SCOPED_TRACE("mesh " + std::to_string(m));
        const Mesh &a = gltf.meshes[m], &b = json.meshes[m];
        EXPECT_EQ(a.triangles, b.triangles);
        ASSERT_EQ(a.positions.size(), b.positions.size());
        for (std::size_t v = 0; v < a.positions.size(); ++v) expect_near(a.positions[v], b.positions[v], tolerance);
        EXPECT_EQ(a.normals, b.normals);
        expect_same_material(gltf.materials[std::size_t(a.material)], json.materials[std::size_t(b.material)]);
    }
    EXPECT_EQ(gltf.textures.size(), json.textures.size());
    ASSERT_EQ(gltf.lights.size(), json.lights.size());
    for (std::size_t l = 0; l < gltf.lights.size(); ++l) {
        EXPECT_EQ(gltf.lights[l].kind, json.lights[l].kind);
        EXPECT_NEAR(gltf.lights[l].power, json.lights[l].power, 1e-12 * json.lights[l].power);
    }
}

TEST(GltfScene, MaterialsCameraAndSunMakeTheSceneOfTheirHandWrittenJson) {
    std::vector<std::string> notes;
    const Scene gltf = load_gltf_scene((kScenes / "materials.gltf").string(), {}, &notes);
    const Scene json = load_scene((kScenes / "materials.json").string());
    expect_same_scene(gltf, json, 0.0);
    EXPECT_EQ(notes, std::vector<std::string>{});
    // The mapping's four rules are all there: diffuse, roughconductor, roughplastic, emitting diffuse.
    ASSERT_EQ(gltf.materials.size(), 4u);
    EXPECT_EQ(gltf.materials[1].type, MaterialType::RoughConductor);
    EXPECT_EQ(gltf.materials[2].type, MaterialType::RoughPlastic);
    EXPECT_EQ(gltf.materials[3].emission, glm::dvec3(4, 4, 2));  // emissiveFactor times KHR_materials_emissive_strength
}

TEST(GltfScene, NoCameraAndNoLightTakeTheDocumentedDefaultsWithANoteEach) {
    const std::string path = (kScenes / "no_camera_no_light.gltf").string();
    std::vector<std::string> notes;
    const Scene gltf = load_gltf_scene(path, {}, &notes);
    const Scene json = load_scene((kScenes / "no_camera_no_light.json").string());
    expect_same_scene(gltf, json, 1e-12);
    EXPECT_EQ(notes,
              (std::vector<std::string>{
                  path + ": no camera: looking at the meshes' bounding box from +z and above (fov_y 40, 640 x 480)",
                  path + ": no light: a constant white environment of radiance 1 lights the scene"}));
}

TEST(GltfScene, ExtensionsChooseTheReader) {
    EXPECT_TRUE(is_gltf_scene_path("a/b.gltf"));
    EXPECT_TRUE(is_gltf_scene_path("B.GLB"));
    EXPECT_FALSE(is_gltf_scene_path("b.gltf.json"));
    EXPECT_FALSE(is_gltf_scene_path("b.xml"));
}

// The binary container (make_gltf.py writes materials.glb of the same
// document, its buffer the BIN chunk) reads as its JSON does, the extensions
// wavepath-import reads from the JSON chunk (KHR_materials_emissive_strength) included.
TEST(GltfScene, GlbReadsAsItsGltf) {
    const Scene from_glb = load_gltf_scene((kScenes / "materials.glb").string());
    const Scene from_gltf = load_gltf_scene((kScenes / "materials.gltf").string());
    expect_same_scene(from_glb, from_gltf, 0.0);
    EXPECT_EQ(from_glb.materials.at(3).emission, glm::dvec3(4, 4, 2));
}

// One triangle of the given material, with texture coordinates (0, 0), (1,
// 0), (0, 0.25) and, where `image` is not empty, that image as texture 0;
// its camera and light defaulted.
std::string one_triangle(const std::string& material, const std::string& image = "") {
    const std::string textures =
        image.empty() ? "" : R"("textures": [{"source": 0}], "images": [{"uri": ")" + image + R"("}],)";
    return R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
 "nodes": [{"name": "Triangle", "mesh": 0}],
 "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "TEXCOORD_0": 1}, "material": 0, "mode": 4}]}],
 "materials": [)" +
           material + "], " + textures + R"(
 "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]},
               {"bufferView": 1, "componentType": 5126, "count": 3, "type": "VEC2"}],
 "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36}, {"buffer": 0, "byteOffset": 36, "byteLength": 24}],
 "buffers": [{"byteLength": 60, "uri": "data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAAAAAAAAAAAAAAAIA/AAAAAAAAAAAAAIA+"}]})";
}

// `gltf` (one_triangle's) with a second node in its scene and `top_level` keys (each followed by a comma).
std::string with_node(std::string gltf, const std::string& node, const std::string& top_level) {
    const std::string nodes = R"("nodes": [{"name": "Triangle", "mesh": 0}])";
    gltf.replace(gltf.find(nodes), nodes.size(), R"("nodes": [{"name": "Triangle", "mesh": 0}, )" + node + "]");
    const std::string scenes = R"("scenes": [{"nodes": [0]}],)";
    gltf.replace(gltf.find(scenes), scenes.size(), R"("scenes": [{"nodes": [0, 1]}], )" + top_level);
    return gltf;
}

// An image embedded in the file (a .glb's buffer view, a data: uri) is read
// as the image file it holds: the same texels as that file beside the glTF.
// `wavepath convert` writes it beside the JSON (GltfCli).
TEST(GltfScene, AnEmbeddedImageReadsAsTheFileItHolds) {
    const MitsubaScene beside = read_gltf_scene((kScenes / "textured.gltf").string());
    ASSERT_EQ(beside.scene.textures.size(), 1u);
    EXPECT_EQ(beside.scene.textures[0].file, "../textures/tiles.png");
    EXPECT_TRUE(beside.embedded_images.empty());
    for (const char* name : {"textured.glb", "textured_data_uri.gltf"}) {
        SCOPED_TRACE(name);
        const MitsubaScene embedded = read_gltf_scene((kScenes / name).string());
        expect_same_scene(embedded.scene, beside.scene, 0.0);
        ASSERT_EQ(embedded.scene.textures.size(), 1u);
        const Texture &a = embedded.scene.textures[0], &b = beside.scene.textures[0];
        EXPECT_EQ(a.file, "*0");
        EXPECT_TRUE(a.path.empty());
        EXPECT_EQ(a.width, b.width);
        EXPECT_EQ(a.height, b.height);
        EXPECT_EQ(a.texels, b.texels);
        ASSERT_EQ(embedded.embedded_images.size(), 1u);
        EXPECT_EQ(embedded.embedded_images[0].texture, 0u);
        EXPECT_EQ(embedded.embedded_images[0].format, "png");
        EXPECT_EQ(embedded.embedded_images[0].bytes.substr(0, 4), "\x89PNG");
    }
}

// A camera without aspectRatio (glTF: the viewport's) makes a 640 x 480 image, with a note.
TEST(GltfScene, ACameraWithoutAspectRatioIs640By480) {
    const TempDirectory dir("aspect");
    write_text(dir.path() / "eye.gltf",
               with_node(one_triangle(R"({"name": "m"})"), R"({"name": "Eye", "camera": 0, "translation": [0, 0, 3]})",
                         R"("cameras": [{"type": "perspective", "perspective": {"yfov": 0.5, "znear": 0.1}}],)"));
    const MitsubaScene read = read_gltf_scene(dir / "eye.gltf");
    EXPECT_EQ(read.scene.camera.width, 640);
    EXPECT_EQ(read.scene.camera.height, 480);
    EXPECT_EQ(read.scene.camera.fov_y_degrees, 0.5 * 180.0 / std::numbers::pi);
    EXPECT_EQ(read.scene.camera.position, glm::dvec3(0, 0, 3));
    EXPECT_EQ(read.scene.camera.look_at, glm::dvec3(0, 0, 2));
    ASSERT_EQ(read.warnings.size(), 2u);  // and the light's
    EXPECT_EQ(read.warnings[0], (dir / "eye.gltf") + ": camera \"Eye\": no aspectRatio: 640 x 480");
}

// KHR_lights_punctual's point and spot lights are wavepath's: intensity
// (candela) colour times intensity, at the node's origin; a spot along the
// node's -z, outerConeAngle its cutoff angle and innerConeAngle its beam
// width; a point light's `range` ignored (spot_light.gltf, make_gltf.py).
TEST(GltfScene, PointAndSpotLightsMakeTheSceneOfTheirHandWrittenJson) {
    std::vector<std::string> notes;
    const Scene gltf = load_gltf_scene((kScenes / "spot_light.gltf").string(), {}, &notes);
    const Scene json = load_scene((kScenes / "spot_light.json").string());
    expect_same_scene(gltf, json, 1e-12);
    ASSERT_EQ(gltf.point_lights.size(), 2u);
    ASSERT_TRUE(gltf.point_lights[0].cone.has_value());
    EXPECT_FALSE(gltf.point_lights[1].cone.has_value());
    EXPECT_EQ(notes, std::vector<std::string>{});
    EXPECT_TRUE(gltf.features().point_lights);
}

// ---- the material mapping, one glTF material at a time ----

class GltfMaterial : public ::testing::Test {
 protected:
    MitsubaScene read_scene(const std::string& material, const std::string& image = "") const {
        const fs::path path = dir_.path() / "triangle.gltf";
        write_text(path, one_triangle(material, image));
        return read_gltf_scene(path.string());
    }
    Material read(const std::string& material) const {
        const MitsubaScene scene = read_scene(material);
        EXPECT_EQ(scene.scene.materials.size(), 1u);
        return scene.scene.materials.at(0);
    }
    std::string error_of(const std::string& material) const {
        try {
            read(material);
        } catch (const SceneError& error) {
            return std::string(error.what()).substr(dir_.path().string().size() + 1);
        }
        return "(no error)";
    }
    TempDirectory dir_{"gltf"};
};

std::string pbr(const std::string& factors) { return R"({"name": "m", "pbrMetallicRoughness": {)" + factors + "}}"; }

TEST_F(GltfMaterial, MetallicFromOneHalfIsAConductorTintedByTheBaseColour) {
    const Material rough =
        read(pbr(R"("baseColorFactor": [0.5, 0.25, 1, 1], "metallicFactor": 0.5, "roughnessFactor": 0.5)"));
    EXPECT_EQ(rough.type, MaterialType::RoughConductor);
    EXPECT_EQ(rough.specular_reflectance, glm::dvec3(0.5, 0.25, 1));
    EXPECT_EQ(rough.eta, glm::dvec3(0.0));
    EXPECT_EQ(rough.k, glm::dvec3(1.0));
    EXPECT_EQ(rough.distribution, Microfacet::GGX);
    EXPECT_EQ(rough.alpha_u, 0.25);  // roughness squared
    EXPECT_EQ(rough.alpha_v, 0.25);
    EXPECT_EQ(read(pbr(R"("metallicFactor": 1, "roughnessFactor": 0)")).type, MaterialType::Conductor);
}

TEST_F(GltfMaterial, MetallicBelowOneHalfIsAPlasticOrDiffuseWhereFullyRough) {
    const Material coat =
        read(pbr(R"("baseColorFactor": [0.5, 0.25, 1, 1], "metallicFactor": 0.25, "roughnessFactor": 0.5)"));
    EXPECT_EQ(coat.type, MaterialType::RoughPlastic);
    EXPECT_EQ(coat.albedo, glm::dvec3(0.5, 0.25, 1));
    EXPECT_EQ(coat.ior, 1.5);
    EXPECT_EQ(coat.alpha_u, 0.25);
    EXPECT_EQ(read(pbr(R"("metallicFactor": 0, "roughnessFactor": 0)")).type, MaterialType::Plastic);
    const Material matte =
        read(pbr(R"("baseColorFactor": [0.5, 0.25, 1, 1], "metallicFactor": 0, "roughnessFactor": 1)"));
    EXPECT_EQ(matte.type, MaterialType::Diffuse);
    EXPECT_EQ(matte.albedo, glm::dvec3(0.5, 0.25, 1));
}

TEST_F(GltfMaterial, TheRoughnessIsClampedToTheLeastTheRenderersTake) {
    EXPECT_EQ(read(pbr(R"("metallicFactor": 1, "roughnessFactor": 0.001)")).alpha_u, kMinRoughness);
}

TEST_F(GltfMaterial, WithoutFactorsItIsGltfsDefaultARoughWhiteMetal) {
    const Material m = read(R"({"name": "m"})");
    EXPECT_EQ(m.type, MaterialType::RoughConductor);
    EXPECT_EQ(m.specular_reflectance, glm::dvec3(1.0));
    EXPECT_EQ(m.alpha_u, 1.0);
}

TEST_F(GltfMaterial, TransmissionIsADielectricOfItsIor) {
    const Material rough = read(
        R"({"name": "m", "pbrMetallicRoughness": {"roughnessFactor": 0.5}, "extensions": {"KHR_materials_transmission": {"transmissionFactor": 1}, "KHR_materials_ior": {"ior": 1.25}}})");
    EXPECT_EQ(rough.type, MaterialType::RoughDielectric);
    EXPECT_EQ(rough.ior, 1.25);
    EXPECT_EQ(rough.distribution, Microfacet::GGX);
    EXPECT_EQ(rough.alpha_u, 0.25);
    const Material smooth = read(
        R"({"name": "m", "pbrMetallicRoughness": {"roughnessFactor": 0}, "extensions": {"KHR_materials_transmission": {"transmissionFactor": 0.5}}})");
    EXPECT_EQ(smooth.type, MaterialType::Glass);
    EXPECT_EQ(smooth.ior, 1.5);  // KHR_materials_ior's default
}

TEST_F(GltfMaterial, EmissionIsADiffuseAreaLightOfFactorTimesStrength) {
    const Material lamp = read(
        R"({"name": "m", "pbrMetallicRoughness": {"baseColorFactor": [0.5, 0.5, 0.5, 1], "metallicFactor": 1}, "emissiveFactor": [1, 0.5, 0], "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 8}}})");
    EXPECT_EQ(lamp.type, MaterialType::Diffuse);
    EXPECT_EQ(lamp.albedo, glm::dvec3(0.5));
    EXPECT_EQ(lamp.emission, glm::dvec3(8, 4, 0));
    EXPECT_FALSE(lamp.two_sided);
}

// glTF's texture coordinates as the file has them (v = 0 at the image's top,
// as wavepath's); the image read from beside the file, decoded from sRGB.
TEST_F(GltfMaterial, BaseColorTextureIsTheAlbedoOrTheConductorsReflectance) {
    write_image(Image{2, 1, {0.5f, 0.25f, 1.0f, 0.0f, 0.0f, 0.0f}}, (dir_.path() / "t.png").string());
    const std::string textured = R"("baseColorTexture": {"index": 0}, "roughnessFactor": 1)";
    const MitsubaScene matte = read_scene(pbr(textured + R"(, "metallicFactor": 0)"), "t.png");
    ASSERT_EQ(matte.scene.textures.size(), 1u);
    const Texture& t = matte.scene.textures[0];
    EXPECT_EQ(t.file, "t.png");
    EXPECT_FALSE(t.raw);
    EXPECT_EQ(t.width, 2);
    EXPECT_NEAR(t.texels[0], 0.5f, 0.01f);  // 8-bit sRGB of 0.5 and back
    EXPECT_EQ(t.texels[3], 0.0f);
    EXPECT_EQ(matte.scene.materials[0].type, MaterialType::Diffuse);
    EXPECT_EQ(matte.scene.materials[0].texture(TexturedParameter::Albedo), 0);
    const Mesh& mesh = matte.scene.meshes.at(0);
    ASSERT_EQ(mesh.uvs.size(), 3u);
    EXPECT_EQ(mesh.uvs[1], glm::dvec2(1, 0));
    EXPECT_EQ(mesh.uvs[2], glm::dvec2(0, 0.25));

    const Material metal = read_scene(pbr(textured + R"(, "metallicFactor": 1)"), "t.png").scene.materials[0];
    EXPECT_EQ(metal.type, MaterialType::RoughConductor);
    EXPECT_EQ(metal.texture(TexturedParameter::SpecularReflectance), 0);
    EXPECT_EQ(metal.texture(TexturedParameter::Albedo), kNoTexture);
}

// A glTF file as a JSON scene's `mesh` has the same texture coordinates.
TEST_F(GltfMaterial, AJsonMeshOfTheFileHasItsTextureCoordinatesToo) {
    write_text(dir_.path() / "triangle.gltf", one_triangle(pbr("")));
    const fs::path json = dir_.path() / "scene.json";
    write_text(json, R"({"camera": {"position": [0, 0, 2], "look_at": [0, 0, 0], "fov_y": 40, "width": 4, "height": 4},
        "materials": {"white": {"type": "diffuse", "albedo": [0.5, 0.5, 0.5]}},
        "shapes": [{"type": "mesh", "file": "triangle.gltf", "material": "white"}]})");
    const Scene scene = load_scene(json.string());
    ASSERT_EQ(scene.meshes.at(0).uvs.size(), 3u);
    EXPECT_EQ(scene.meshes[0].uvs[1], glm::dvec2(1, 0));
    EXPECT_EQ(scene.meshes[0].uvs[2], glm::dvec2(0, 0.25));
}

// The normal texture is a normal map, read raw (and once more than the base
// colour's sRGB texture of the same image); not where wavepath's normal maps
// cannot go (under a mask, on a dielectric), with a note.
TEST_F(GltfMaterial, NormalTextureIsARawNormalMap) {
    write_image(Image{2, 1, {0.5f, 0.5f, 1.0f, 0.5f, 0.5f, 1.0f}}, (dir_.path() / "n.png").string());
    const MitsubaScene read =
        read_scene(pbr(R"("baseColorTexture": {"index": 0}, "metallicFactor": 0, "roughnessFactor": 0.5)")
                       .insert(1, R"("normalTexture": {"index": 0}, )"),
                   "n.png");
    const Material& m = read.scene.materials.at(0);
    EXPECT_EQ(m.type, MaterialType::RoughPlastic);
    EXPECT_EQ(m.texture(TexturedParameter::Albedo), 0);
    EXPECT_EQ(m.texture(TexturedParameter::NormalMap), 1);
    ASSERT_EQ(read.scene.textures.size(), 2u);
    EXPECT_FALSE(read.scene.textures[0].raw);
    EXPECT_TRUE(read.scene.textures[1].raw);
    EXPECT_TRUE(read.scene.features().normal_map);

    const MitsubaScene masked = read_scene(
        R"({"normalTexture": {"index": 0}, "name": "m", "alphaMode": "BLEND", "pbrMetallicRoughness": {"baseColorFactor": [1, 1, 1, 0.5]}})",
        "n.png");
    EXPECT_EQ(masked.scene.materials.at(0).texture(TexturedParameter::NormalMap), kNoTexture);
    EXPECT_EQ(masked.scene.textures.size(), 0u);
    ASSERT_EQ(masked.warnings.size(), 3u);  // the camera's and the light's too
    EXPECT_EQ(masked.warnings[0], (dir_ / "triangle.gltf") +
                                      ": material \"m\": normalTexture ignored (wavepath's normal maps take no mask)");
}

// KHR_texture_transform is the texture's to_uv: the spec's uv' = T(offset)
// R(rotation) S(scale) uv, R's GLSL columns (cos, sin) and (-sin, cos), so
// u' = cos sx u - sin sy v + ox and v' = sin sx u + cos sy v + oy. At a
// quarter turn, scale (2, 4) and offset (0.5, 0.25): u' = -4 v + 0.5,
// v' = 2 u + 0.25. A texture without one (the normal map here) is the identity.
TEST_F(GltfMaterial, TextureTransformIsTheTexturesToUv) {
    write_image(Image{1, 1, {0.5f, 0.5f, 1.0f}}, (dir_.path() / "t.png").string());
    const MitsubaScene read = read_scene(
        R"({"name": "m", "normalTexture": {"index": 0}, "pbrMetallicRoughness": {"metallicFactor": 0, "roughnessFactor": 0.5, "baseColorTexture": {"index": 0, "extensions": {"KHR_texture_transform": {"offset": [0.5, 0.25], "rotation": 1.5707963267948966, "scale": [2, 4]}}}}})",
        "t.png");
    ASSERT_EQ(read.scene.textures.size(), 2u);
    const std::array<double, 6> expected{0, -4, 0.5, 2, 0, 0.25};
    const Material& m = read.scene.materials.at(0);
    const Texture& base = read.scene.textures.at(std::size_t(m.texture(TexturedParameter::Albedo)));
    for (std::size_t i = 0; i < 6; ++i) EXPECT_NEAR(base.to_uv[i], expected[i], 1e-6) << i;
    const Texture& normal = read.scene.textures.at(std::size_t(m.texture(TexturedParameter::NormalMap)));
    EXPECT_EQ(normal.to_uv, (std::array<double, 6>{1, 0, 0, 0, 1, 0}));
}

// With a base colour texture, the mask's opacity is the texture's alpha
// times the factor's (tests/image/grey_alpha.png: alpha 10/255 and 1), as a
// texture of its own: that fraction for BLEND, cut at alphaCutoff for MASK.
// `wavepath convert` writes such a computed texture as an EXR beside the JSON.
TEST_F(GltfMaterial, TheBaseColourTexturesAlphaIsTheMasksOpacity) {
    fs::copy_file(fs::path(WAVEPATH_SOURCE_DIR) / "tests/image/grey_alpha.png", dir_.path() / "a.png");
    const auto opacity_of = [&](const std::string& mode) {
        const MitsubaScene read = read_scene(
            R"({"name": "m", )" + mode +
                R"(, "pbrMetallicRoughness": {"baseColorFactor": [1, 1, 1, 0.5], "baseColorTexture": {"index": 0}}})",
            "a.png");
        const Material& m = read.scene.materials.at(0);
        EXPECT_EQ(m.texture(TexturedParameter::SpecularReflectance), 0);  // the colour, a metal's
        EXPECT_EQ(read.scene.textures.size(), 2u);
        const Texture& opacity = read.scene.textures.at(std::size_t(m.texture(TexturedParameter::Opacity)));
        EXPECT_TRUE(opacity.raw);
        EXPECT_EQ(read.computed_textures, std::vector<std::size_t>{1});
        const SceneJson json = scene_json(read, dir_.path() / "out.json");
        EXPECT_EQ(json.computed.size(), 1u);
        EXPECT_EQ(json.json["textures"]["a.png (opacity)"]["file"], "out_texture0.exr");
        return opacity.texels;
    };
    const float low = 10.0f / 255.0f;
    EXPECT_EQ(opacity_of(R"("alphaMode": "BLEND")"),
              (std::vector<float>{0.5f * low, 0.5f * low, 0.5f * low, 0.5f, 0.5f, 0.5f}));
    EXPECT_EQ(opacity_of(R"("alphaMode": "MASK", "alphaCutoff": 0.25)"), (std::vector<float>{0, 0, 0, 1, 1, 1}));
    EXPECT_EQ(opacity_of(R"("alphaMode": "MASK", "alphaCutoff": 0.75)"), (std::vector<float>(6, 0.0f)));
}

// The metallic-roughness and emissive textures are not read, each with a
// note; the factors alone would make an emissive texture's whole surface
// glow, so such a material emits nothing.
TEST_F(GltfMaterial, TexturesNotReadAreNotedAndAnEmissiveOneTurnsTheEmissionOff) {
    write_image(Image{1, 1, {1.0f, 1.0f, 1.0f}}, (dir_.path() / "e.png").string());
    const MitsubaScene read = read_scene(
        R"({"name": "m", "emissiveFactor": [1, 1, 1], "emissiveTexture": {"index": 0}, "pbrMetallicRoughness": {"metallicFactor": 0, "roughnessFactor": 0.5, "metallicRoughnessTexture": {"index": 0}}})",
        "e.png");
    const Material& m = read.scene.materials.at(0);
    EXPECT_EQ(m.type, MaterialType::RoughPlastic);
    EXPECT_EQ(m.alpha_u, 0.25);
    EXPECT_EQ(m.emission, glm::dvec3(0.0));
    ASSERT_EQ(read.warnings.size(), 4u);  // the camera's and the light's too
    const std::string file = dir_ / "triangle.gltf";
    EXPECT_EQ(read.warnings[0], file +
                                    ": material \"m\": metallicRoughnessTexture not read: metallicFactor and "
                                    "roughnessFactor hold everywhere");
    EXPECT_EQ(read.warnings[1], file +
                                    ": material \"m\": emissiveTexture not read: the material emits nothing "
                                    "(wavepath's emission is uniform)");
    EXPECT_EQ(read.warnings[3], file + ": no light: a constant white environment of radiance 1 lights the scene");
}

// The base colour's alpha is a mask's opacity: BLEND's fraction, MASK's cut-out at
// alphaCutoff (default 0.5); OPAQUE (the default) ignores it.
TEST_F(GltfMaterial, AlphaModesAreMasks) {
    const std::string quarter = R"("pbrMetallicRoughness": {"baseColorFactor": [1, 1, 1, 0.25], "roughnessFactor": 1})";
    const Material blend = read(R"({"name": "m", "alphaMode": "BLEND", )" + quarter + "}");
    EXPECT_EQ(blend.opacity, 0.25);
    EXPECT_TRUE(blend.masked());
    EXPECT_EQ(blend.type, MaterialType::RoughConductor);  // the material under the mask
    EXPECT_EQ(read(R"({"name": "m", "alphaMode": "MASK", )" + quarter + "}").opacity, 0.0);
    EXPECT_EQ(read(R"({"name": "m", "alphaMode": "MASK", "alphaCutoff": 0.25, )" + quarter + "}").opacity, 1.0);
    EXPECT_EQ(read(R"({"name": "m", )" + quarter + "}").opacity, 1.0);
    EXPECT_FALSE(read(R"({"name": "m", )" + quarter + "}").masked());
}

TEST_F(GltfMaterial, FactorsOutsideTheirRangeAreOneErrorLine) {
    EXPECT_EQ(error_of(pbr(R"("baseColorFactor": [2, 0.5, 0.5, 1])")),
              "triangle.gltf: material \"m\": baseColorFactor (2, 0.5, 0.5), alpha 1: must be in [0, 1]");
    EXPECT_EQ(error_of(pbr(R"("roughnessFactor": 1.5)")),
              "triangle.gltf: material \"m\": roughnessFactor 1.5: must be in [0, 1]");
    EXPECT_EQ(error_of(R"({"name": "m", "extensions": {"KHR_materials_ior": {"ior": 0.5}}})"),
              "triangle.gltf: material \"m\": ior 0.5: must be in (1, 10]");
}

}  // namespace gltf_scene_test
}  // namespace
}  // namespace wp::test
