// Every validation rule of the scene format, each checked for its exact
// one-line message "<source>: <json path>: <problem>".
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>

#include "scene/named_media.h"
#include "scene/scene.h"

namespace {

// A valid scene; every case below breaks exactly one thing in it.
constexpr const char* kValidScene = R"({
  "camera": {"position": [0, 1, 5], "look_at": [0, 1, 0], "fov_y": 40, "width": 32, "height": 24},
  "render": {"spp": 4},
  "materials": {
    "white": {"type": "diffuse", "albedo": [0.5, 0.5, 0.5]},
    "lamp": {"type": "emitter", "radiance": [4, 4, 4]}
  },
  "shapes": [
    {"type": "sphere", "center": [0, 1, 0], "radius": 1, "material": "white"},
    {"type": "plane", "point": [0, 0, 0], "normal": [0, 1, 0], "material": "white"},
    {"type": "quad", "corner": [-1, 3, -1], "edge1": [2, 0, 0], "edge2": [0, 0, 2], "material": "lamp"}
  ]
})";

std::string error_of(const std::string& text) {
    try {
        wp::parse_scene(text, "test.json");
    } catch (const wp::SceneError& error) {
        return error.what();
    }
    return "(no error)";
}

TEST(SceneErrors, TheBaseSceneIsValid) { EXPECT_EQ(error_of(kValidScene), "(no error)"); }

// A JSON merge patch (RFC 7386) for kValidScene: objects merge, null removes
// a key, arrays are replaced whole. `message` omits the "test.json: " prefix.
struct PatchCase {
    const char* name;
    const char* patch;
    const char* message;
};

#define SPHERE_AT_ORIGIN R"("type": "sphere", "center": [0, 0, 0], "radius": 1)"
#define FLOOR_PLANE R"("type": "plane", "point": [0, 0, 0])"
#define UNIT_QUAD R"("type": "quad", "corner": [0, 2, 0])"

const PatchCase kPatchCases[] = {
    // unknown keys, at every level
    {"UnknownTopLevelKey", R"({"camra": {}})",
     "camra: unknown key (expected one of: camera, render, background, lights, textures, materials, shapes)"},
    {"UnknownCameraKey", R"({"camera": {"fovy": 40}})",
     "camera.fovy: unknown key (expected one of: position, look_at, up, fov_y, width, height, filter)"},
    {"UnknownRenderKey", R"({"render": {"samples": 4}})",
     "render.samples: unknown key (expected one of: spp, max_depth, rr_depth, seed, nee, mis, hemisphere, sampler, "
     "integrator, photons, initial_radius, alpha)"},
    {"UnknownDiffuseKey", R"({"materials": {"white": {"colour": [1, 1, 1]}}})",
     "materials.white.colour: unknown key (expected one of: type, albedo, emission, two_sided, one_sided)"},
    {"UnknownMirrorKey",
     R"({"materials": {"chrome": {"type": "mirror", "reflectance": [1, 1, 1], "albedo": [1, 1, 1]}}})",
     "materials.chrome.albedo: unknown key (expected one of: type, reflectance, one_sided)"},
    {"UnknownGlassKey", R"({"materials": {"g": {"type": "glass", "ior": 1.5, "two_sided": true}}})",
     "materials.g.two_sided: unknown key (expected one of: type, ior)"},
    {"UnknownEmitterKey", R"({"materials": {"lamp": {"emission": [1, 1, 1]}}})",
     "materials.lamp.emission: unknown key (expected one of: type, radiance, two_sided)"},
    {"UnknownSphereKey", R"({"shapes": [{)" SPHERE_AT_ORIGIN R"(, "material": "white", "color": [1, 0, 0]}]})",
     "shapes[0].color: unknown key (expected one of: type, center, radius, material)"},
    {"UnknownPlaneKey", R"({"shapes": [{)" FLOOR_PLANE R"(, "normal": [0, 1, 0], "material": "white", "center": 0}]})",
     "shapes[0].center: unknown key (expected one of: type, point, normal, material)"},
    {"UnknownQuadKey",
     R"({"shapes": [{)" UNIT_QUAD
     R"(, "edge1": [1, 0, 0], "edge2": [0, 0, 1], "edge3": [1, 1, 1], "material": "lamp"}]})",
     "shapes[0].edge3: unknown key (expected one of: type, corner, edge1, edge2, material)"},
    {"OddMaterialNamesAreQuoted", R"({"materials": {"my lamp": {"type": "emitter", "radiance": [-1, 0, 0]}}})",
     R"(materials["my lamp"].radiance[0]: must be >= 0, got -1)"},

    // missing required keys
    {"MissingCamera", R"({"camera": null})", "camera: missing required key"},
    {"MissingFov", R"({"camera": {"fov_y": null}})", "camera.fov_y: missing required key"},
    {"MissingWidth", R"({"camera": {"width": null}})", "camera.width: missing required key"},
    {"MissingMaterialType", R"({"materials": {"white": {"type": null}}})",
     "materials.white.type: missing required key"},
    {"MissingAlbedo", R"({"materials": {"white": {"albedo": null}}})", "materials.white.albedo: missing required key"},
    {"MissingIor", R"({"materials": {"g": {"type": "glass"}}})", "materials.g.ior: missing required key"},
    {"MissingRadius", R"({"shapes": [{"type": "sphere", "center": [0, 0, 0], "material": "white"}]})",
     "shapes[0].radius: missing required key"},
    {"MissingShapeMaterial", R"({"shapes": [{)" SPHERE_AT_ORIGIN R"(}]})", "shapes[0].material: missing required key"},
    {"MissingShapeType", R"({"shapes": [{"center": [0, 0, 0], "radius": 1, "material": "white"}]})",
     "shapes[0].type: missing required key"},

    // wrong types
    {"CameraNotAnObject", R"({"camera": [1, 2]})", "camera: must be an object, got array"},
    {"FovAsString", R"({"camera": {"fov_y": "wide"}})", "camera.fov_y: must be a number, got string"},
    {"FovAsBoolean", R"({"camera": {"fov_y": true}})", "camera.fov_y: must be a number, got boolean"},
    {"PositionTooShort", R"({"camera": {"position": [0, 1]}})",
     "camera.position: must be an array of 3 numbers, got 2 elements"},
    {"PositionNotAnArray", R"({"camera": {"position": 5}})",
     "camera.position: must be an array of 3 numbers, got number"},
    {"PositionComponentAsString", R"({"camera": {"position": [0, "1", 5]}})",
     "camera.position[1]: must be a number, got string"},
    {"WidthNotAnInteger", R"({"camera": {"width": 32.5}})", "camera.width: must be an integer, got 32.5"},
    {"WidthAsString", R"({"camera": {"width": "32"}})", "camera.width: must be an integer, got string"},
    {"SppAsHugeFloat", R"({"render": {"spp": 1e30}})", "render.spp: must be an integer, got 1e+30"},
    {"RenderNotAnObject", R"({"render": 4})", "render: must be an object, got number"},
    {"BackgroundAsString", R"({"background": "black"})", "background: must be an array of 3 numbers, got string"},
    {"MaterialsAsArray", R"({"materials": [1]})", "materials: must be an object, got array"},
    {"MaterialAsNumber", R"({"materials": {"white": 0.5}})", "materials.white: must be an object, got number"},
    {"MaterialTypeAsNumber", R"({"materials": {"white": {"type": 1}}})",
     "materials.white.type: must be a string, got number"},
    {"TwoSidedAsString", R"({"materials": {"lamp": {"two_sided": "yes"}}})",
     "materials.lamp.two_sided: must be a boolean, got string"},
    {"ShapesAsObject", R"({"shapes": {"a": 1}})", "shapes: must be an array, got object"},
    {"ShapeAsNumber", R"({"shapes": [3]})", "shapes[0]: must be an object, got number"},
    {"ShapeMaterialAsNumber", R"({"shapes": [{)" SPHERE_AT_ORIGIN R"(, "material": 2}]})",
     "shapes[0].material: must be a string, got number"},

    // numbers too large to stay finite in derived quantities
    {"CoordinateTooLarge",
     R"({"shapes": [{"type": "sphere", "center": [1e13, 0, 0], "radius": 1, "material": "white"}]})",
     "shapes[0].center[0]: magnitude must be <= 1e+12, got 1e+13"},
    {"RadianceTooLarge", R"({"materials": {"lamp": {"radiance": [4, -2e12, 4]}}})",
     "materials.lamp.radiance[1]: magnitude must be <= 1e+12, got -2e+12"},

    // sizes
    {"NegativeRadius", R"({"shapes": [{"type": "sphere", "center": [0, 0, 0], "radius": -1, "material": "white"}]})",
     "shapes[0].radius: must be > 0, got -1"},
    {"ZeroRadius", R"({"shapes": [{"type": "sphere", "center": [0, 0, 0], "radius": 0, "material": "white"}]})",
     "shapes[0].radius: must be > 0, got 0"},
    {"ZeroFov", R"({"camera": {"fov_y": 0}})", "camera.fov_y: must be in (0, 180), got 0"},
    {"NegativeFov", R"({"camera": {"fov_y": -10}})", "camera.fov_y: must be in (0, 180), got -10"},
    {"StraightFov", R"({"camera": {"fov_y": 180}})", "camera.fov_y: must be in (0, 180), got 180"},
    {"ZeroWidth", R"({"camera": {"width": 0}})", "camera.width: must be in [1, 16384], got 0"},
    {"NegativeHeight", R"({"camera": {"height": -24}})", "camera.height: must be in [1, 16384], got -24"},
    {"HeightTooLarge", R"({"camera": {"height": 16385}})", "camera.height: must be in [1, 16384], got 16385"},
    {"TooManyPixels", R"({"camera": {"width": 16384, "height": 8193}})",
     "camera: width * height must be <= 134217728, got 16384 * 8193 = 134234112"},

    // degenerate directions
    {"ZeroNormal", R"({"shapes": [{)" FLOOR_PLANE R"(, "normal": [0, 0, 0], "material": "white"}]})",
     "shapes[0].normal: must not be zero-length"},
    {"ZeroEdge1", R"({"shapes": [{)" UNIT_QUAD R"(, "edge1": [0, 0, 0], "edge2": [0, 0, 1], "material": "lamp"}]})",
     "shapes[0].edge1: must not be zero-length"},
    {"ZeroEdge2", R"({"shapes": [{)" UNIT_QUAD R"(, "edge1": [1, 0, 0], "edge2": [0, 0, 0], "material": "lamp"}]})",
     "shapes[0].edge2: must not be zero-length"},
    {"ParallelEdges", R"({"shapes": [{)" UNIT_QUAD R"(, "edge1": [1, 0, 0], "edge2": [4, 0, 0], "material": "lamp"}]})",
     "shapes[0].edge2: must not be parallel to edge1"},
    {"AntiparallelEdges",
     R"({"shapes": [{)" UNIT_QUAD R"(, "edge1": [1, 2, 3], "edge2": [-2, -4, -6], "material": "lamp"}]})",
     "shapes[0].edge2: must not be parallel to edge1"},
    {"NearlyParallelEdges",
     R"({"shapes": [{)" UNIT_QUAD R"(, "edge1": [1, 0, 0], "edge2": [1, 1e-7, 0], "material": "lamp"}]})",
     "shapes[0].edge2: must not be parallel to edge1"},
    {"LookAtIsPosition", R"({"camera": {"look_at": [0, 1, 5]}})", "camera.look_at: must differ from camera.position"},
    {"ZeroUp", R"({"camera": {"up": [0, 0, 0]}})", "camera.up: must not be zero-length"},
    {"UpAlongViewDirection", R"({"camera": {"up": [0, 0, 2]}})",
     "camera.up: must not be parallel to the view direction (look_at - position)"},
    {"DefaultUpAlongViewDirection", R"({"camera": {"look_at": [0, -3, 5]}})",
     "camera: the default up [0, 1, 0] is parallel to the view direction (look_at - position); set up"},

    // materials and their references
    {"UndefinedMaterial", R"({"shapes": [{)" SPHERE_AT_ORIGIN R"(, "material": "red"}]})",
     R"(shapes[0].material: undefined material "red" (defined: lamp, white))"},
    {"NoMaterialsDefined", R"({"materials": null})",
     R"(shapes[0].material: undefined material "white" (defined: none))"},
    {"UnknownMaterialType", R"({"materials": {"white": {"type": "metal"}}})",
     R"(materials.white.type: unknown material type "metal" (expected one of: diffuse, mirror, glass, emitter, conductor, roughconductor, dielectric, roughdielectric, thindielectric, plastic, roughplastic, normalmap, bumpmap, mask))"},
    {"UnknownShapeType", R"({"shapes": [{"type": "box", "material": "white"}]})",
     R"(shapes[0].type: unknown shape type "box" (expected one of: sphere, plane, quad, mesh))"},
    {"NegativeAlbedo", R"({"materials": {"white": {"albedo": [0.5, -0.1, 0.5]}}})",
     "materials.white.albedo[1]: must be >= 0, got -0.1"},
    {"AlbedoAboveOne", R"({"materials": {"white": {"albedo": [1.2, 0.5, 0.5]}}})",
     "materials.white.albedo[0]: must be <= 1 (energy gain), got 1.2"},
    {"NegativeReflectance", R"({"materials": {"chrome": {"type": "mirror", "reflectance": [-0.5, 1, 1]}}})",
     "materials.chrome.reflectance[0]: must be >= 0, got -0.5"},
    {"ReflectanceAboveOne", R"({"materials": {"chrome": {"type": "mirror", "reflectance": [1, 1, 1.01]}}})",
     "materials.chrome.reflectance[2]: must be <= 1 (energy gain), got 1.01"},
    {"NegativeEmission", R"({"materials": {"white": {"emission": [0, -1, 0]}}})",
     "materials.white.emission[1]: must be >= 0, got -1"},
    {"NegativeRadiance", R"({"materials": {"lamp": {"radiance": [-4, 4, 4]}}})",
     "materials.lamp.radiance[0]: must be >= 0, got -4"},
    {"ZeroIor", R"({"materials": {"g": {"type": "glass", "ior": 0}}})", "materials.g.ior: must be > 0, got 0"},
    {"NegativeIor", R"({"materials": {"g": {"type": "glass", "ior": -1.5}}})",
     "materials.g.ior: must be > 0, got -1.5"},
    {"ZeroRoughness", R"({"materials": {"m": {"type": "roughconductor", "alpha": 0}}})",
     "materials.m.alpha: must be >= 1e-04, got 0 (a smooth surface is a conductor)"},
    {"RoughnessBelowLimit", R"({"materials": {"m": {"type": "roughconductor", "alpha_u": 0.1, "alpha_v": 5e-5}}})",
     "materials.m.alpha_v: must be >= 1e-04, got 5e-05 (a smooth surface is a conductor)"},
    {"HugeRoughness", R"({"materials": {"m": {"type": "roughconductor", "alpha": 1e300}}})",
     "materials.m.alpha: magnitude must be <= 1e+12, got 1e+300"},
    {"AlphaAndAlphaU", R"({"materials": {"m": {"type": "roughconductor", "alpha": 0.1, "alpha_u": 0.2}}})",
     "materials.m.alpha: give either alpha or alpha_u and alpha_v, not both"},
    {"AlphaUAlone", R"({"materials": {"m": {"type": "roughconductor", "alpha_u": 0.2}}})",
     "materials.m.alpha_u: needs alpha_v beside it"},
    {"UnknownDistribution", R"({"materials": {"m": {"type": "roughconductor", "distribution": "phong"}}})",
     R"(materials.m.distribution: unknown distribution "phong" (expected beckmann or ggx))"},
    {"EtaWithoutK", R"({"materials": {"m": {"type": "conductor", "eta": 1.5}}})", "materials.m.eta: needs k beside it"},
    {"NamedConductorAndEta", R"({"materials": {"m": {"type": "conductor", "material": "Au", "eta": 1, "k": 1}}})",
     "materials.m.material: give either material or eta and k, not both"},
    {"NegativeK", R"({"materials": {"m": {"type": "conductor", "eta": 1, "k": [3, -1, 3]}}})",
     "materials.m.k[1]: must be >= 0, got -1"},
    {"SpecularReflectanceAboveOne", R"({"materials": {"m": {"type": "conductor", "specular_reflectance": 1.5}}})",
     "materials.m.specular_reflectance: must be in [0, 1], got 1.5"},
    {"ZeroPlasticRoughness", R"({"materials": {"m": {"type": "roughplastic", "alpha": 0}}})",
     "materials.m.alpha: must be >= 1e-04, got 0 (a smooth surface is a plastic)"},
    {"AnisotropicRoughPlastic", R"({"materials": {"m": {"type": "roughplastic", "alpha_u": 0.1, "alpha_v": 0.2}}})",
     "materials.m.alpha_u: unknown key (expected one of: type, diffuse_reflectance, specular_reflectance, int_ior, "
     "ext_ior, nonlinear, distribution, alpha, one_sided)"},
    {"PlasticDiffuseAboveOne", R"({"materials": {"m": {"type": "plastic", "diffuse_reflectance": [0.5, 1.5, 0.5]}}})",
     "materials.m.diffuse_reflectance[1]: must be <= 1, got 1.5"},
    {"PlasticNonlinearNumber", R"({"materials": {"m": {"type": "plastic", "nonlinear": 1}}})",
     "materials.m.nonlinear: must be a boolean, got number"},
    {"NegativeBackground", R"({"background": [0, 0, -1]})", "background[2]: must be >= 0, got -1"},
    {"EmitterPlane", R"({"shapes": [{)" FLOOR_PLANE R"(, "normal": [0, 1, 0], "material": "lamp"}]})",
     R"(shapes[0].material: "lamp" emits light, but a plane cannot be a light (infinite area))"},
    {"GlowingDiffusePlane", R"({"materials": {"white": {"emission": [1, 1, 1]}}})",
     R"(shapes[1].material: "white" emits light, but a plane cannot be a light (infinite area))"},

    // render settings
    {"ZeroSpp", R"({"render": {"spp": 0}})", "render.spp: must be in [1, 1048576], got 0"},
    {"SppTooLarge", R"({"render": {"spp": 1048577}})", "render.spp: must be in [1, 1048576], got 1048577"},
    {"SppBeyondInt64", R"({"render": {"spp": 18446744073709551615}})",
     "render.spp: must be in [1, 1048576], got 18446744073709551615"},
    {"NegativeMaxDepth", R"({"render": {"max_depth": -1}})", "render.max_depth: must be in [0, 100000], got -1"},
    {"MaxDepthTooLarge", R"({"render": {"max_depth": 100001}})",
     "render.max_depth: must be in [0, 100000], got 100001"},
    {"NegativeRrDepth", R"({"render": {"rr_depth": -1}})", "render.rr_depth: must be in [0, 2147483647], got -1"},
    {"RrDepthBeyondInt", R"({"render": {"rr_depth": 2147483648}})",
     "render.rr_depth: must be in [0, 2147483647], got 2147483648"},
    {"NegativeSeed", R"({"render": {"seed": -1}})", "render.seed: must be in [0, 4294967295], got -1"},
    {"SeedBeyond32Bits", R"({"render": {"seed": 4294967296}})",
     "render.seed: must be in [0, 4294967295], got 4294967296"},
    {"NeeAsString", R"({"render": {"nee": "off"}})", "render.nee: must be a boolean, got string"},
    {"UnknownHemisphere", R"({"render": {"hemisphere": "cos"}})",
     "render.hemisphere: unknown hemisphere sampling \"cos\" (expected \"cosine\" or \"uniform\")"},
    {"HemisphereAsNumber", R"({"render": {"hemisphere": 1}})", "render.hemisphere: must be a string, got number"},
    {"UnknownSampler", R"({"render": {"sampler": "halton"}})",
     "render.sampler: unknown sampler \"halton\" (expected \"sobol\" or \"independent\")"},
};

class PatchedScene : public testing::TestWithParam<PatchCase> {};

TEST_P(PatchedScene, FailsWithItsMessage) {
    nlohmann::json scene = nlohmann::json::parse(kValidScene);
    scene.merge_patch(nlohmann::json::parse(GetParam().patch));
    EXPECT_EQ(error_of(scene.dump(2)), std::string("test.json: ") + GetParam().message);
}

INSTANTIATE_TEST_SUITE_P(SceneErrors, PatchedScene, testing::ValuesIn(kPatchCases),
                         [](const testing::TestParamInfo<PatchCase>& info) { return std::string(info.param.name); });

// What a merge patch cannot express (broken syntax, overflow, null values,
// duplicate keys): the first occurrence of `from` in kValidScene becomes `to`;
// an empty `from` stands for the whole text. A syntax error's column is that
// of the last character of the offending token.
struct TextCase {
    const char* name;
    const char* from;
    const char* to;
    const char* message;
};

const TextCase kTextCases[] = {
    {"Overflow", R"("fov_y": 40)", R"("fov_y": 1e999)",
     "line 2, column 72: malformed JSON: number overflow parsing '1e999'"},
    {"NegativeOverflow", "[0, 1, 5]", "[-1e999, 1, 5]",
     "line 2, column 32: malformed JSON: number overflow parsing '-1e999'"},
    {"NullNumber", R"("fov_y": 40)", R"("fov_y": null)", "camera.fov_y: must be a number, got null"},
    {"MissingComma", R"("fov_y": 40,)", R"("fov_y": 40)",
     "line 2, column 77: malformed JSON: syntax error while parsing object - unexpected string literal; expected '}'"},
    {"TrailingComma", R"("spp": 4})", R"("spp": 4,})",
     "line 3, column 23: malformed JSON: syntax error while parsing object key - unexpected '}'; expected string "
     "literal"},
    {"Comment", "{\n", "{ // a comment\n",
     "line 1, column 3: malformed JSON: syntax error while parsing object key - invalid literal; last read: '{ /'; "
     "expected string literal"},
    {"Truncated", "", R"({"camera": {)",
     "line 1, column 13: malformed JSON: syntax error while parsing object key - unexpected end of input; expected "
     "string literal"},
    {"Empty", "", "",
     "line 1, column 1: malformed JSON: syntax error while parsing value - unexpected end of input; expected '[', "
     "'{', or a literal"},
    {"RootNotAnObject", "", "[1, 2]", "(root): must be an object, got array"},
    {"DuplicateTopLevelKey", R"("render": {"spp": 4},)", R"("render": {"spp": 4}, "render": {},)",
     "render: duplicate key"},
    {"DuplicateKeyInAnArrayElement", R"("material": "lamp"})", R"("material": "lamp", "material": "white"})",
     "shapes[2].material: duplicate key"},
};

std::string apply(const TextCase& text_case) {
    std::string text = kValidScene;
    if (std::string(text_case.from).empty()) return text_case.to;
    std::size_t at = text.find(text_case.from);
    if (at == std::string::npos) ADD_FAILURE() << text_case.from << " is not in the base scene";
    return at == std::string::npos ? text : text.replace(at, std::string(text_case.from).size(), text_case.to);
}

class EditedScene : public testing::TestWithParam<TextCase> {};

TEST_P(EditedScene, FailsWithItsMessage) {
    EXPECT_EQ(error_of(apply(GetParam())), std::string("test.json: ") + GetParam().message);
}

INSTANTIATE_TEST_SUITE_P(SceneErrors, EditedScene, testing::ValuesIn(kTextCases),
                         [](const testing::TestParamInfo<TextCase>& info) { return std::string(info.param.name); });

// Unknown names of conductors and indices list the known ones (Mitsuba's, scene/named_media.h).
TEST(SceneErrors, UnknownMediaNamesListTheKnownOnes) {
    nlohmann::json scene = nlohmann::json::parse(kValidScene);
    scene["materials"]["m"] = {{"type", "roughconductor"}, {"material", "Unobtainium"}};
    EXPECT_EQ(error_of(scene.dump(2)), R"(test.json: materials.m.material: unknown conductor "Unobtainium" (known: )" +
                                           wp::named_conductor_list() + ")");
    scene["materials"]["m"] = {{"type", "glass"}, {"ior", "Glass"}};
    EXPECT_EQ(error_of(scene.dump(2)), R"(test.json: materials.m.ior: unknown index of refraction "Glass" (known: )" +
                                           wp::named_ior_list() + ")");
    scene["materials"]["m"] = {{"type", "plastic"}, {"ext_ior", "vacuum-ish"}};
    EXPECT_EQ(error_of(scene.dump(2)),
              R"(test.json: materials.m.ext_ior: unknown index of refraction "vacuum-ish" (known: )" +
                  wp::named_ior_list() + ")");
    scene["materials"]["m"] = {{"type", "glass"}, {"ior", {1.5}}};
    EXPECT_EQ(error_of(scene.dump(2)), "test.json: materials.m.ior: must be a number or a name, got array");
}

// Our line/column (computed from the byte offset, so that number overflow
// has one too) agrees with the one nlohmann prints in its own parse errors.
TEST(SceneErrors, LineAndColumnAgreeWithTheParser) {
    for (const char* text : {"{\n  \"camera\": ,\n}", "{} x", "{\"a\": \"abc", "{\n\"a\": [1, 2,\n\n", "\n\n   }"}) {
        std::string ours = error_of(text);
        std::string theirs;
        try {
            ADD_FAILURE() << "parsed: " << nlohmann::json::parse(text).dump();
        } catch (const nlohmann::json::parse_error& error) {
            theirs = error.what();
        }
        std::string position = ours.substr(ours.find(": ") + 2);
        position = position.substr(0, position.find(": "));
        EXPECT_NE(theirs.find("at " + position + ":"), std::string::npos) << ours << " vs " << theirs;
    }
}

// A duplicate key 40,000 arrays deep is named by its whole path (built in
// linear time: fuzz_scene's input of this shape took 20 s under the sanitizers).
TEST(SceneErrors, DuplicateKeyDeepInNestedArrays) {
    constexpr int kDepth = 40000;
    const std::string text =
        "{\"background\": " + std::string(kDepth, '[') + "{\"a\": 1, \"a\": 2}" + std::string(kDepth, ']') + "}";
    std::string path = "background";
    for (int level = 0; level < kDepth; ++level) path += "[0]";
    EXPECT_EQ(error_of(text), "test.json: " + path + ".a: duplicate key");
}

TEST(SceneErrors, EdgesJustAboveTheParallelLimitAreAccepted) {
    nlohmann::json scene = nlohmann::json::parse(kValidScene);
    scene["shapes"][2]["edge2"] = {1.0, 1e-5, 0.0};
    EXPECT_EQ(error_of(scene.dump()), "(no error)");
}

}  // namespace
