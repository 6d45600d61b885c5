// The Mitsuba 3 XML reader (scene/mitsuba_xml.h; docs/scene-format.md,
// "Mitsuba XML"): each element's mapping onto the Scene, exactly, and the
// one-line errors with file and line. That the mappings render as Mitsuba
// does is tests/oracle/mitsuba_xml_oracle.py's.
#include "scene/mitsuba_xml.h"

#include <gtest/gtest.h>
#include <zlib.h>

#include <cmath>
#include <cstring>
#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>
#include <numbers>
#include <string>

#include "image/image_io.h"
#include "import/mesh_file_error.h"
#include "scene/limits.h"
#include "scene/named_media.h"
#include "scene/scene_writer.h"
#include "scene/serialized_mesh.h"
#include "support/temp_directory.h"

namespace wp::test {
namespace {
// A namespace of its own: the sanitizer build compiles test files together (unity).
namespace mitsuba_xml_test {

namespace fs = std::filesystem;

// A sensor of the given film size looking down -z from the origin.
std::string sensor(int width = 8, int height = 8, const std::string& extra = "") {
    return R"(<sensor type="perspective"><transform name="to_world"><lookat origin="0, 0, 0" target="0, 0, -1" up="0, 1, 0"/></transform>)" +
           extra + R"(<film type="hdrfilm"><integer name="width" value=")" + std::to_string(width) +
           R"("/><integer name="height" value=")" + std::to_string(height) +
           R"("/><rfilter type="box"/></film></sensor>)";
}

std::string scene_of(const std::string& body) { return "<scene version=\"3.0.0\">\n" + body + "\n</scene>\n"; }

class MitsubaXml : public ::testing::Test {
 protected:
    std::string write(const std::string& name, const std::string& text) const {
        const fs::path path = dir_.path() / name;
        fs::create_directories(path.parent_path());
        write_text(path, text);
        return path.string();
    }
    MitsubaScene read(const std::string& body, const XmlDefines& defines = {}) const {
        return read_mitsuba_scene(write("scene.xml", scene_of(body)), defines);
    }
    // The error, without "<dir>/".
    std::string error_of(const std::string& body, const XmlDefines& defines = {}) const {
        try {
            read(body, defines);
        } catch (const SceneError& error) {
            std::string message = error.what();
            const std::string prefix = dir_.path().string() + "/";
            for (std::size_t at = message.find(prefix); at != std::string::npos; at = message.find(prefix))
                message.erase(at, prefix.size());
            return message;
        }
        return "(no error)";
    }
    TempDirectory dir_{"xml"};
};

void expect_near(const glm::dvec3& a, const glm::dvec3& b, double tolerance = 1e-12) {
    EXPECT_NEAR(a.x, b.x, tolerance);
    EXPECT_NEAR(a.y, b.y, tolerance);
    EXPECT_NEAR(a.z, b.z, tolerance);
}

glm::dvec3 quad_normal(const Quad& q) { return glm::normalize(glm::cross(q.edge1, q.edge2)); }

// ---- camera, film, sampler, integrator ----

TEST_F(MitsubaXml, CameraLooksAlongToWorldsZWithItsY) {
    const Scene scene = read(R"(<sensor type="perspective">
        <float name="fov" value="60"/>
        <transform name="to_world"><lookat origin="1, 2, 3" target="1, 2, 0" up="0, 1, 0"/></transform>
        <film type="hdrfilm"><integer name="width" value="40"/><integer name="height" value="20"/></film>
    </sensor>)")
                            .scene;
    expect_near(scene.camera.position, {1, 2, 3});
    expect_near(glm::normalize(scene.camera.look_at - scene.camera.position), {0, 0, -1});
    expect_near(scene.camera.up, {0, 1, 0});
    EXPECT_EQ(scene.camera.width, 40);
    EXPECT_EQ(scene.camera.height, 20);
}

TEST_F(MitsubaXml, FovAxesAsMitsubasParseFov) {
    const double t = std::tan(glm::radians(30.0));  // fov 60, aspect 2 (40 x 20)
    const std::pair<const char*, double> cases[] = {
        {"x", 2.0 * std::atan(t / 2.0)},
        {"y", glm::radians(60.0)},
        {"diagonal", 2.0 * std::atan(t / std::sqrt(5.0))},
        {"smaller", glm::radians(60.0)},  // the height, in a wide image
        {"larger", 2.0 * std::atan(t / 2.0)},
        {"X", 2.0 * std::atan(t / 2.0)},  // Mitsuba lowers the case
    };
    for (const auto& [axis, fov_y] : cases) {
        SCOPED_TRACE(axis);
        const Scene scene = read(sensor(40, 20,
                                        R"(<float name="fov" value="60"/><string name="fov_axis" value=")" +
                                            std::string(axis) + R"("/>)"))
                                .scene;
        EXPECT_NEAR(glm::radians(scene.camera.fov_y_degrees), fov_y, 1e-12);
    }
    // A square film: smaller is x, larger is y (Mitsuba compares aspect > 1).
    EXPECT_NEAR(read(sensor(8, 8, R"(<float name="fov" value="50"/><string name="fov_axis" value="larger"/>)"))
                    .scene.camera.fov_y_degrees,
                50.0, 1e-12);
}

TEST_F(MitsubaXml, MitsubasDefaultsWithoutFilmSamplerIntegratorOrFov) {
    const MitsubaScene read_scene = read(R"(<sensor type="perspective"/>)");
    const Scene& scene = read_scene.scene;
    EXPECT_EQ(scene.camera.width, 768);
    EXPECT_EQ(scene.camera.height, 576);
    EXPECT_EQ(scene.render.spp, 4);
    EXPECT_EQ(scene.render.max_depth, kMaxDepthLimit);  // Mitsuba's -1, unbounded
    EXPECT_EQ(scene.render.rr_depth, 5);
    // 50 mm on 35 mm film, the diagonal: Mitsuba's x_fov 38.1848 at 4:3 (its print of the default camera).
    const double x_fov = 2.0 * std::atan(std::tan(glm::radians(scene.camera.fov_y_degrees) / 2.0) * 768.0 / 576.0);
    EXPECT_NEAR(glm::degrees(x_fov), 38.1848, 1e-4);
    // No film: Mitsuba's default gaussian of stddev 0.5, without a warning.
    EXPECT_EQ(scene.camera.filter.type, FilterType::Gaussian);
    EXPECT_EQ(scene.camera.filter.stddev, 0.5);
    EXPECT_TRUE(read_scene.warnings.empty());
}

TEST_F(MitsubaXml, RfiltersAsMitsubasWithTheirParameters) {
    const auto filter = [&](const std::string& rfilter) {
        return read(R"(<sensor type="perspective"><film type="hdrfilm">)" + rfilter + "</film></sensor>")
            .scene.camera.filter;
    };
    EXPECT_EQ(filter("").type, FilterType::Gaussian);  // the film's default rfilter
    EXPECT_EQ(filter(R"(<rfilter type="box"/>)").type, FilterType::Box);
    const PixelFilter tent = filter(R"(<rfilter type="tent"><float name="radius" value="1.5"/></rfilter>)");
    EXPECT_EQ(tent.type, FilterType::Tent);
    EXPECT_EQ(tent.radius, 1.5);
    const PixelFilter gaussian = filter(R"(<rfilter type="gaussian"><float name="stddev" value="0.7"/></rfilter>)");
    EXPECT_EQ(gaussian.type, FilterType::Gaussian);
    EXPECT_EQ(gaussian.stddev, 0.7);
}

TEST_F(MitsubaXml, PathIntegratorDepthsCountSegmentsThere) {
    const auto depths = [&](const std::string& integrator) {
        const Scene scene = read(integrator + sensor()).scene;
        return std::pair(scene.render.max_depth, scene.render.rr_depth);
    };
    EXPECT_EQ(depths(R"(<integrator type="path"><integer name="max_depth" value="1"/></integrator>)"), std::pair(0, 5));
    EXPECT_EQ(depths(R"(<integrator type="path"><integer name="max_depth" value="6"/>)"
                     R"(<integer name="rr_depth" value="3"/></integrator>)"),
              std::pair(5, 3));
    EXPECT_EQ(depths(R"(<integrator type="path"><integer name="max_depth" value="-1"/></integrator>)"),
              std::pair(kMaxDepthLimit, 5));
}

TEST_F(MitsubaXml, SamplerCountAndSeed) {
    const Scene scene = read(sensor(8, 8,
                                    R"(<sampler type="multijitter"><integer name="sample_count" value="64"/>)"
                                    R"(<integer name="seed" value="7"/></sampler>)"))
                            .scene;
    EXPECT_EQ(scene.render.spp, 64);
    EXPECT_EQ(scene.render.seed, 7u);
}

// ---- transforms ----

TEST_F(MitsubaXml, TransformStepsApplyInDocumentOrder) {
    const auto corner = [&](const std::string& steps) {
        const Scene scene =
            read(sensor() + R"(<shape type="rectangle"><transform name="to_world">)" + steps + "</transform></shape>")
                .scene;
        return scene.quads.at(0).corner;  // to_world of (-1, -1, 0)
    };
    expect_near(corner(R"(<translate x="1"/><scale value="2"/>)"), {0, -2, 0});
    expect_near(corner(R"(<scale value="2"/><translate x="1"/>)"), {-1, -2, 0});
    expect_near(corner(R"(<translate value="1, 2, 3"/>)"), {0, 1, 3});
    expect_near(corner(R"(<scale x="2" z="5"/>)"), {-2, -1, 0});
    expect_near(corner(R"(<rotate z="1" angle="90"/>)"), {1, -1, 0});  // counter-clockwise about +z
    expect_near(corner(R"(<matrix value="1 0 0 10  0 1 0 20  0 0 1 30  0 0 0 1"/>)"), {9, 19, 30});
    expect_near(corner(R"(<matrix value="0 -1 0  1 0 0  0 0 1"/>)"), {1, -1, 0});
    // lookat: the local z axis along target - origin, local x = up x z.
    expect_near(corner(R"(<lookat origin="0, 0, 0" target="1, 0, 0" up="0, 1, 0"/>)"), {0, -1, 1});
}

TEST_F(MitsubaXml, RotationAxisIsNotNormalizedAsInMitsuba) {
    // Mitsuba 3.9.1: ScalarTransform4d().rotate([2, 0, 0], 90) = [[4, 0, 0], [0, 0, -2], [0, 2, 0]].
    const Quad q = read(sensor() + R"(<shape type="rectangle"><transform name="to_world">)"
                                   R"(<rotate x="2" angle="90"/></transform></shape>)")
                       .scene.quads.at(0);
    expect_near(q.corner, {-4, 0, -2});
}

TEST_F(MitsubaXml, RectangleFacesToWorldsNormalOfZ) {
    const auto normal = [&](const std::string& flip, const std::string& steps) {
        return quad_normal(read(sensor() + R"(<shape type="rectangle">)" + flip + R"(<transform name="to_world">)" +
                                steps + "</transform></shape>")
                               .scene.quads.at(0));
    };
    const std::string flip = R"(<boolean name="flip_normals" value="true"/>)";
    expect_near(normal("", ""), {0, 0, 1});
    expect_near(normal(flip, ""), {0, 0, -1});
    expect_near(normal("", R"(<scale z="-1"/>)"), {0, 0, -1});  // the inverse transpose of the mirror
    expect_near(normal("", R"(<scale x="-1"/>)"), {0, 0, 1});
    expect_near(normal(flip, R"(<scale x="-1"/>)"), {0, 0, -1});
}

// Whether every triangle of a mesh around `centre` faces away from it.
int outward_triangles(const Mesh& mesh, const glm::dvec3& centre) {
    int outward = 0;
    for (const glm::uvec3& t : mesh.triangles) {
        const glm::dvec3 n =
            glm::cross(mesh.positions[t.y] - mesh.positions[t.x], mesh.positions[t.z] - mesh.positions[t.x]);
        outward += glm::dot(n, mesh.positions[t.x] - centre) > 0.0 ? 1 : 0;
    }
    return outward;
}

TEST_F(MitsubaXml, CubeFacesOutUnlessItsTransformedCornersWindTheOtherWay) {
    const auto outward = [&](const std::string& inside) {
        const Scene scene = read(sensor() + R"(<shape type="cube">)" + inside + "</shape>").scene;
        EXPECT_EQ(scene.meshes.at(0).triangles.size(), 12u);
        EXPECT_TRUE(scene.meshes.at(0).normals.empty());
        return outward_triangles(scene.meshes.at(0), {5, 0, 0});
    };
    const std::string mirror = R"(<transform name="to_world"><scale x="-1"/><translate x="5"/></transform>)";
    const std::string move = R"(<transform name="to_world"><translate x="5"/></transform>)";
    const std::string flip = R"(<boolean name="flip_normals" value="true"/>)";
    EXPECT_EQ(outward(move), 12);
    EXPECT_EQ(outward(move + flip), 0);
    EXPECT_EQ(outward(mirror), 0);  // Mitsuba's meshes: the front follows the transformed corners
    EXPECT_EQ(outward(mirror + flip), 12);
}

TEST_F(MitsubaXml, DiskIsAFineFanFacingZ) {
    const Scene scene = read(sensor() + R"(<shape type="disk"><transform name="to_world"><scale value="2"/>)"
                                        R"(</transform></shape>)")
                            .scene;
    const Mesh& disk = scene.meshes.at(0);
    EXPECT_EQ(disk.triangles.size(), std::size_t(512));
    EXPECT_NEAR(mesh_area(disk) / (4.0 * std::numbers::pi), 1.0, 3e-5);
    for (const glm::uvec3& t : disk.triangles)
        EXPECT_GT(glm::cross(disk.positions[t.y] - disk.positions[t.x], disk.positions[t.z] - disk.positions[t.x]).z,
                  0.0);
}

TEST_F(MitsubaXml, SphereFromCenterRadiusAndToWorld) {
    const Scene scene = read(sensor() + R"(
        <shape type="sphere"><point name="center" value="1, 2, 3"/><float name="radius" value="0.5"/></shape>
        <shape type="sphere"><transform name="to_world"><scale value="2"/><translate y="1"/></transform>
            <point name="center" x="1" y="0" z="0"/></shape>)")
                            .scene;
    expect_near(scene.spheres.at(0).center, {1, 2, 3});
    EXPECT_EQ(scene.spheres.at(0).radius, 0.5);
    expect_near(scene.spheres.at(1).center, {2, 1, 0});  // to_world * translate(center) * scale(radius)
    EXPECT_EQ(scene.spheres.at(1).radius, 2.0);
    EXPECT_EQ(error_of(sensor() + R"(
        <shape type="sphere"><transform name="to_world"><scale x="2"/></transform></shape>)"),
              "scene.xml:3: shape \"sphere\": transform \"to_world\": a sphere's may not scale unevenly or shear");
}

// ---- materials and emitters ----

TEST_F(MitsubaXml, BsdfsAsMaterials) {
    const Scene scene = read(sensor() + R"(
        <bsdf type="diffuse" id="red"><rgb name="reflectance" value="0.5, 0.1, 0.1"/></bsdf>
        <shape type="sphere"><bsdf type="twosided"><ref id="red"/></bsdf></shape>
        <shape type="sphere"/>
        <shape type="sphere"><bsdf type="dielectric"><string name="int_ior" value="Diamond"/>
            <float name="ext_ior" value="1.5"/></bsdf></shape>
        <shape type="sphere"><bsdf type="dielectric"/></shape>
        <shape type="sphere"><emitter type="area"><rgb name="radiance" value="3"/></emitter></shape>
        <shape type="sphere"><bsdf type="dielectric"/><emitter type="area"><rgb name="radiance" value="2"/></emitter></shape>
        <shape type="sphere"><bsdf type="diffuse"><spectrum name="reflectance" value="0.25"/></bsdf></shape>
        <emitter type="constant"><rgb name="radiance" value="0.1, 0.2, 0.3"/></emitter>)")
                            .scene;
    const auto material = [&](int sphere) {
        return scene.materials.at(std::size_t(scene.spheres.at(std::size_t(sphere)).material));
    };
    EXPECT_EQ(material(0).type, MaterialType::Diffuse);
    expect_near(material(0).albedo, {0.5, 0.1, 0.1});
    expect_near(material(1).albedo, glm::dvec3(0.5));  // Mitsuba's default BSDF
    EXPECT_EQ(material(2).type, MaterialType::Glass);
    EXPECT_NEAR(material(2).ior, 2.419 / 1.5, 1e-12);
    EXPECT_NEAR(material(3).ior, 1.5046 / 1.000277, 1e-12);  // bk7 in air
    expect_near(material(4).albedo, glm::dvec3(0.0));        // the default BSDF of an emitter is black
    expect_near(material(4).emission, glm::dvec3(3.0));
    EXPECT_FALSE(material(4).two_sided);
    EXPECT_EQ(material(5).type, MaterialType::Emitter);  // a dielectric that emits: the emission only
    expect_near(material(6).albedo, glm::dvec3(0.25));
    expect_near(scene.background, {0.1, 0.2, 0.3});
}

// Mitsuba's reflecting BSDFs are black from the back unless inside a
// twosided (Material::one_sided): a diffuse, a roughconductor and the default
// BSDF alone are one-sided, a twosided's and a dielectric are not, and an
// adapter's is its nested BSDF's.
TEST_F(MitsubaXml, ReflectingBsdfsOutsideTwosidedAreOneSided) {
    const Scene scene = read(sensor() + R"(
        <shape type="sphere"><bsdf type="diffuse"/></shape>
        <shape type="sphere"><bsdf type="twosided"><bsdf type="diffuse"/></bsdf></shape>
        <shape type="sphere"><bsdf type="roughconductor"/></shape>
        <shape type="sphere"/>
        <shape type="sphere"><bsdf type="dielectric"/></shape>
        <shape type="sphere"><bsdf type="mask"><bsdf type="plastic"/></bsdf></shape>
        <shape type="sphere"><bsdf type="twosided"><bsdf type="mask"><bsdf type="plastic"/></bsdf></bsdf></shape>)")
                            .scene;
    const auto one_sided = [&](int sphere) {
        return scene.materials.at(std::size_t(scene.spheres.at(std::size_t(sphere)).material)).one_sided;
    };
    EXPECT_TRUE(one_sided(0));
    EXPECT_FALSE(one_sided(1));
    EXPECT_TRUE(one_sided(2));
    EXPECT_TRUE(one_sided(3));  // Mitsuba's default BSDF is a diffuse
    EXPECT_FALSE(one_sided(4));
    EXPECT_TRUE(one_sided(5));
    EXPECT_FALSE(one_sided(6));
    EXPECT_TRUE(scene.features().one_sided);
}

// <spectrum> lists and emitted spectra as Mitsuba 3.9.1's RGB variants read
// them (scene/spectrum.h): the values it printed for the same XML (traverse
// after load_string in scalar_rgb), to its float precision: a reflectance
// weighted by D65, a conductor's eta and k likewise but not clamped to 1, an
// emitted radiance as it is.
TEST_F(MitsubaXml, SpectraAreTheColoursMitsubaGivesThem) {
    const Scene scene = read(sensor() + R"(
        <shape type="sphere"><bsdf type="diffuse">
            <spectrum name="reflectance" value="400:0.1, 500:0.5, 600:0.9, 700:0.3"/></bsdf></shape>
        <shape type="sphere"><bsdf type="roughconductor">
            <spectrum name="eta" value="400:0.1, 500:0.5, 600:0.9, 700:0.3"/>
            <spectrum name="k" value="400:1, 500:2, 600:3, 700:4"/></bsdf></shape>
        <shape type="sphere"><emitter type="area">
            <spectrum name="radiance" value="400:1, 500:5, 600:9, 700:3"/></emitter></shape>)")
                            .scene;
    const auto material = [&](int sphere) {
        return scene.materials.at(std::size_t(scene.spheres.at(std::size_t(sphere)).material));
    };
    const double tolerance = 2e-6 * 10.0;  // Mitsuba's float sums, to its printed digits
    expect_near(material(0).albedo, {0.854797, 0.68754, 0.265015}, tolerance);
    expect_near(material(1).eta, {0.854797, 0.68754, 0.265015}, tolerance);
    expect_near(material(1).k, {3.40779, 2.42912, 1.40304}, tolerance);
    expect_near(material(2).emission, {9.99234, 6.597, 2.29444}, 10.0 * tolerance);
}

// Mitsuba's directional emitter: `direction` is the way the light travels
// (normalized), or to_world's +z; irradiance defaults to 1.
TEST_F(MitsubaXml, DirectionalEmittersAsDirectionalLights) {
    Scene scene = read(sensor() + R"(
        <emitter type="directional"><vector name="direction" value="0, -2, 0"/>
            <rgb name="irradiance" value="3, 2, 1"/></emitter>
        <emitter type="directional"><transform name="to_world"><rotate x="1" angle="90"/></transform></emitter>
        <emitter type="directional"/>)")
                      .scene;
    ASSERT_EQ(scene.directional_lights.size(), 3u);
    expect_near(scene.directional_lights[0].direction, {0, -1, 0});
    expect_near(scene.directional_lights[0].irradiance, {3, 2, 1});
    expect_near(scene.directional_lights[1].direction, {0, -1, 0});  // +z turned 90 degrees about x
    expect_near(scene.directional_lights[1].irradiance, glm::dvec3(1.0));
    expect_near(scene.directional_lights[2].direction, {0, 0, 1});
    finish_scene(scene);
    EXPECT_TRUE(scene.features().directional_lights);
}

// Mitsuba's point (at `position` or to_world's origin) and spot (at
// to_world's origin, pointing along its +z; cutoff_angle 20 and beam_width
// 3/4 of it by default) as point lights; `wavepath convert` writes them and
// the JSON reads back the same lights (in the camera's frame).
TEST_F(MitsubaXml, PointAndSpotEmittersAsPointLights) {
    const MitsubaScene read_scene = read(sensor() + R"(
        <emitter type="point"><point name="position" value="1, 2, 3"/><rgb name="intensity" value="3, 2, 1"/></emitter>
        <emitter type="point"><transform name="to_world"><translate x="-1"/></transform></emitter>
        <emitter type="spot"><transform name="to_world"><lookat origin="0, 2, 0" target="0, 0, 1" up="0, 1, 0"/>
            </transform><float name="cutoff_angle" value="40"/><float name="beam_width" value="10"/></emitter>
        <emitter type="spot"><transform name="to_world"><rotate x="1" angle="90"/><translate y="3"/></transform>
            <rgb name="intensity" value="5"/></emitter>)");
    const Scene& scene = read_scene.scene;
    ASSERT_EQ(scene.point_lights.size(), 4u);
    expect_near(scene.point_lights[0].position, {1, 2, 3});
    expect_near(scene.point_lights[0].intensity, {3, 2, 1});
    EXPECT_FALSE(scene.point_lights[0].cone.has_value());
    expect_near(scene.point_lights[1].position, {-1, 0, 0});
    expect_near(scene.point_lights[1].intensity, glm::dvec3(1.0));
    const PointLight& aimed = scene.point_lights[2];
    ASSERT_TRUE(aimed.cone.has_value());
    expect_near(aimed.position, {0, 2, 0});
    expect_near(aimed.cone->axis, glm::normalize(glm::dvec3(0, -2, 1)));
    EXPECT_EQ(aimed.cone->cutoff_angle, 40.0);
    EXPECT_EQ(aimed.cone->beam_width, 10.0);
    const PointLight& turned = scene.point_lights[3];
    ASSERT_TRUE(turned.cone.has_value());
    expect_near(turned.position, {0, 3, 0});
    expect_near(turned.cone->axis, {0, -1, 0});  // +z turned 90 degrees about x
    EXPECT_EQ(turned.cone->cutoff_angle, 20.0);
    EXPECT_EQ(turned.cone->beam_width, 15.0);
    expect_near(turned.intensity, glm::dvec3(5.0));
    fs::create_directories(dir_.path() / "out");
    const fs::path json = dir_.path() / "out/converted.json";
    write_text(json, scene_json(read_scene, json).json.dump());
    const Scene from_json = load_scene(json.string());
    ASSERT_EQ(from_json.point_lights.size(), 4u);
    for (std::size_t i = 0; i < 4; ++i) {
        const PointLight &a = from_json.point_lights[i], &b = scene.point_lights[i];
        expect_near(a.position + from_json.world_offset, b.position);
        EXPECT_EQ(a.intensity, b.intensity);
        ASSERT_EQ(a.cone.has_value(), b.cone.has_value());
        if (!a.cone) continue;
        expect_near(a.cone->axis, b.cone->axis);
        EXPECT_EQ(a.cone->cutoff_angle, b.cone->cutoff_angle);
        EXPECT_EQ(a.cone->beam_width, b.cone->beam_width);
    }
    EXPECT_TRUE(from_json.features().point_lights);
}

// Mitsuba's envmap: its file found beside the scene, `scale` and a
// `to_world` that rotates; `wavepath convert` writes it (the file named from
// the JSON's folder, to_world as a matrix) and the JSON reads back the same
// map. A second environment, or a to_world that scales, is refused.
TEST_F(MitsubaXml, EnvmapEmitterAsEnvironmentMap) {
    write_image(Image{2, 3, std::vector<float>(18, 0.5f)}, (dir_.path() / "sky.exr").string());
    const std::string envmap = R"(
        <emitter type="envmap"><string name="filename" value="sky.exr"/><float name="scale" value="2"/>
            <transform name="to_world"><rotate y="1" angle="90"/></transform></emitter>)";
    const MitsubaScene read_scene = read(sensor() + envmap);
    const Scene& scene = read_scene.scene;
    ASSERT_TRUE(scene.environment_map.has_value());
    EXPECT_EQ(scene.environment_map->width, 2);
    EXPECT_EQ(scene.environment_map->height, 3);
    EXPECT_EQ(scene.environment_map->scale, 2.0);
    expect_near(scene.environment_map->to_world * glm::dvec3(1, 0, 0), {0, 0, -1});
    fs::create_directories(dir_.path() / "out");
    const fs::path json = dir_.path() / "out/converted.json";
    write_text(json, scene_json(read_scene, json).json.dump());
    const Scene from_json = load_scene(json.string());
    ASSERT_TRUE(from_json.environment_map.has_value());
    EXPECT_EQ(from_json.environment_map->texels, scene.environment_map->texels);
    EXPECT_EQ(from_json.environment_map->scale, 2.0);
    EXPECT_EQ(from_json.environment_map->to_world, scene.environment_map->to_world);
    EXPECT_TRUE(from_json.features().environment_map);
    EXPECT_THROW(read(sensor() + envmap + R"(<emitter type="constant"/>)"), SceneError);
    EXPECT_THROW(read(sensor() + R"(<emitter type="envmap"><string name="filename" value="sky.exr"/>
            <transform name="to_world"><scale value="2"/></transform></emitter>)"),
                 SceneError);
}

TEST_F(MitsubaXml, ConductorsAndRoughDielectricsAsMaterials) {
    const Scene scene = read(sensor() + R"(
        <shape type="sphere"><bsdf type="twosided"><bsdf type="roughconductor"><string name="material" value="Cu"/>
            <string name="distribution" value="ggx"/><float name="alpha" value="0.2"/></bsdf></bsdf></shape>
        <shape type="sphere"><bsdf type="conductor"><rgb name="eta" value="1, 2, 3"/><float name="k" value="4"/>
            <rgb name="specular_reflectance" value="0.5"/></bsdf></shape>
        <shape type="sphere"><bsdf type="roughconductor"><float name="alpha_u" value="0.05"/>
            <float name="alpha_v" value="0.3"/></bsdf></shape>
        <shape type="sphere"><bsdf type="roughdielectric"><string name="int_ior" value="water"/></bsdf></shape>
        <shape type="sphere"><bsdf type="thindielectric"><float name="int_ior" value="1.6"/>
            <float name="ext_ior" value="1.2"/></bsdf></shape>)")
                            .scene;
    const auto material = [&](int sphere) {
        return scene.materials.at(std::size_t(scene.spheres.at(std::size_t(sphere)).material));
    };
    EXPECT_EQ(material(0).type, MaterialType::RoughConductor);
    expect_near(material(0).eta, named_conductor("Cu")->eta);
    expect_near(material(0).k, named_conductor("Cu")->k);
    EXPECT_EQ(material(0).distribution, Microfacet::GGX);
    EXPECT_EQ(material(0).alpha_u, 0.2);
    EXPECT_EQ(material(1).type, MaterialType::Conductor);
    expect_near(material(1).eta, {1.0, 2.0, 3.0});
    expect_near(material(1).k, glm::dvec3(4.0));
    expect_near(material(1).specular_reflectance, glm::dvec3(0.5));
    EXPECT_EQ(material(2).distribution, Microfacet::Beckmann);  // Mitsuba's defaults: beckmann, "none"
    expect_near(material(2).k, glm::dvec3(1.0));
    EXPECT_EQ(material(2).alpha_u, 0.05);
    EXPECT_EQ(material(2).alpha_v, 0.3);
    EXPECT_EQ(material(3).type, MaterialType::RoughDielectric);
    EXPECT_NEAR(material(3).ior, *named_ior("water") / *named_ior("air"), 1e-12);
    EXPECT_EQ(material(3).alpha_u, 0.1);
    EXPECT_EQ(material(4).type, MaterialType::ThinDielectric);
    EXPECT_NEAR(material(4).ior, 1.6 / 1.2, 1e-12);
    EXPECT_EQ(error_of(sensor() + R"(
        <shape type="sphere"><bsdf type="roughconductor"><float name="alpha" value="0"/></bsdf></shape>)"),
              "scene.xml:3: bsdf \"roughconductor\": alpha: must be >= 1e-04, got 0");
}

TEST_F(MitsubaXml, PlasticsAsMaterials) {
    const Scene scene = read(sensor() + R"(
        <shape type="sphere"><bsdf type="plastic"/></shape>
        <shape type="sphere"><bsdf type="twosided"><bsdf type="roughplastic">
            <rgb name="diffuse_reflectance" value="0.6, 0.2, 0.1"/><float name="specular_reflectance" value="0.8"/>
            <string name="int_ior" value="bk7"/><float name="ext_ior" value="1.2"/>
            <boolean name="nonlinear" value="true"/><string name="distribution" value="ggx"/>
            <float name="alpha" value="0.3"/></bsdf></bsdf></shape>)")
                            .scene;
    const auto material = [&](int sphere) {
        return scene.materials.at(std::size_t(scene.spheres.at(std::size_t(sphere)).material));
    };
    EXPECT_EQ(material(0).type, MaterialType::Plastic);  // Mitsuba's defaults: 0.5, 1, polypropylene in air, linear
    expect_near(material(0).albedo, glm::dvec3(0.5));
    expect_near(material(0).specular_reflectance, glm::dvec3(1.0));
    EXPECT_NEAR(material(0).ior, *named_ior("polypropylene") / *named_ior("air"), 1e-12);
    EXPECT_FALSE(material(0).nonlinear);
    EXPECT_EQ(material(1).type, MaterialType::RoughPlastic);
    expect_near(material(1).albedo, {0.6, 0.2, 0.1});
    expect_near(material(1).specular_reflectance, glm::dvec3(0.8));
    EXPECT_NEAR(material(1).ior, *named_ior("bk7") / 1.2, 1e-12);
    EXPECT_TRUE(material(1).nonlinear);
    EXPECT_EQ(material(1).distribution, Microfacet::GGX);
    EXPECT_EQ(material(1).alpha_u, 0.3);
    EXPECT_EQ(material(1).alpha_v, 0.3);
    EXPECT_EQ(error_of(sensor() + R"(
        <shape type="sphere"><bsdf type="roughplastic"><float name="alpha_u" value="0.1"/></bsdf></shape>)"),
              "scene.xml:3: bsdf \"roughplastic\": float \"alpha_u\": not supported (supported: diffuse_reflectance, "
              "specular_reflectance, int_ior, ext_ior, nonlinear, distribution, alpha)");
}

// ---- $defaults, -D, includes, references ----

TEST_F(MitsubaXml, TopLevelObjectsUsedByReference) {
    const Scene scene = read(R"(
        <sampler type="independent" id="s"><integer name="sample_count" value="9"/></sampler>
        <emitter type="area" id="glow"><rgb name="radiance" value="2"/></emitter>)" +
                             sensor(8, 8, R"(<ref id="s"/>)") + R"(
        <shape type="sphere"><ref id="glow"/></shape>)")
                            .scene;
    EXPECT_EQ(scene.render.spp, 9);
    expect_near(scene.materials.at(0).emission, glm::dvec3(2.0));
}

TEST_F(MitsubaXml, DefaultsAndDefinesSubstituteInDocumentOrder) {
    const std::string body =
        R"(<default name="spp" value="8"/><default name="s" value="2"/>)" +
        sensor(8, 8, R"(<sampler type="independent"><integer name="sample_count" value="$spp$s"/></sampler>)");
    EXPECT_EQ(read(body).scene.render.spp, 82);
    EXPECT_EQ(read(body, {{"spp", "3"}}).scene.render.spp, 32);  // -D wins over <default>
    EXPECT_EQ(error_of(body, {{"sp", "1"}}),
              "scene.xml: -D sp: the scene has no $sp (an unused definition is an "
              "error, as in Mitsuba)");
    EXPECT_EQ(
        error_of(sensor(8, 8, R"(<sampler type="independent"><integer name="sample_count" value="$n"/></sampler>)")),
        "scene.xml:2: undefined parameter $n (define it with <default> or -D n=...)");
    // "\$" is a dollar sign.
    EXPECT_EQ(read(sensor() + R"(<bsdf type="diffuse" id="a\$b"/><shape type="sphere"><ref id="a\$b"/></shape>)")
                  .scene.materials.at(0)
                  .name,
              "a$b");
}

TEST_F(MitsubaXml, IncludesAreRelativeToTheIncludingFile) {
    write(
        "parts/a.xml",
        scene_of(
            R"(<include filename="b.xml"/><bsdf type="diffuse" id="x"><float name="reflectance" value="0.2"/></bsdf>)"));
    write("parts/b.xml", scene_of(R"(<bsdf type="diffuse" id="y"><float name="reflectance" value="0.3"/></bsdf>)"));
    const Scene scene =
        read(R"(<include filename="parts/a.xml"/>)" + sensor() + R"(<shape type="sphere"><ref id="y"/></shape>)").scene;
    expect_near(scene.materials.at(0).albedo, glm::dvec3(0.3));
    write("parts/loop.xml", scene_of(R"(<include filename="../scene.xml"/>)"));
    EXPECT_EQ(error_of(R"(<include filename="parts/loop.xml"/>)"),
              "parts/loop.xml:2: include cycle: scene.xml includes parts/loop.xml includes scene.xml");
}

TEST_F(MitsubaXml, ReferenceProblems) {
    EXPECT_EQ(error_of(sensor() + R"(<shape type="sphere">
        <ref id="nothing"/></shape>)"),
              "scene.xml:3: <ref>: no object has id \"nothing\"");
    EXPECT_EQ(error_of(sensor() + R"(
        <bsdf type="twosided" id="a"><ref id="b"/></bsdf>
        <bsdf type="twosided" id="b"><ref id="a"/></bsdf>
        <shape type="sphere"><ref id="b"/></shape>)"),
              "scene.xml:4: bsdf: cyclic reference: \"b\" -> \"a\" -> \"b\"");
    EXPECT_EQ(error_of(sensor() + R"(
        <bsdf type="diffuse" id="a"/>
        <bsdf type="diffuse" id="a"/>)"),
              "scene.xml:4: <bsdf>: id \"a\" is also the id of the <bsdf> at scene.xml:3");
}

TEST_F(MitsubaXml, OldVersionsNamesAreUpgradedAsMitsubaDoes) {
    write("old.xml", R"(<scene version="0.6.0">
        <integrator type="path"><integer name="maxDepth" value="3"/></integrator>
        <sensor type="perspective"><float name="fov" value="30"/><string name="fovAxis" value="y"/>
            <sampler type="independent"><integer name="sampleCount" value="9"/></sampler>
            <film type="hdrfilm"><integer name="width" value="8"/><integer name="height" value="8"/><rfilter type="box"/></film></sensor>
        <shape type="sphere"><bsdf type="diffuse"><rgb name="diffuseReflectance" value="0.4"/></bsdf></shape>
    </scene>)");
    const Scene scene = read_mitsuba_scene((dir_.path() / "old.xml").string(), {}).scene;
    EXPECT_EQ(scene.render.max_depth, 2);
    EXPECT_EQ(scene.render.spp, 9);
    EXPECT_NEAR(scene.camera.fov_y_degrees, 30.0, 1e-12);
    expect_near(scene.materials.at(0).albedo, glm::dvec3(0.4));
}

TEST_F(MitsubaXml, ErrorsNameTheFileLineAndPluginOrProperty) {
    EXPECT_EQ(error_of(sensor() + R"(
        <shape type="sphere">
            <bsdf type="principled"/>
        </shape>)"),
              "scene.xml:4: bsdf \"principled\": not supported (supported: diffuse, twosided, dielectric, conductor, "
              "roughconductor, roughdielectric, thindielectric, plastic, roughplastic, normalmap, bumpmap, mask)");
    EXPECT_EQ(error_of(sensor() + R"(
        <shape type="rectangle"><float name="width" value="2"/></shape>)"),
              "scene.xml:3: shape \"rectangle\": float \"width\": not supported (supported: to_world, flip_normals)");
    EXPECT_EQ(error_of(sensor() + R"(
        <shape type="sphere">
            <float name="radius" value="1e13"/></shape>)"),
              "scene.xml:4: shape \"sphere\": float \"radius\": magnitude must be <= 1e+12, got 1e+13");
    EXPECT_EQ(error_of(sensor() + "\n<shape type=\"sphere\">"), "scene.xml:4: malformed XML: Start-end tags mismatch");
    EXPECT_EQ(error_of(R"(<sensor type="thinlens"/>)"),
              "scene.xml:2: sensor \"thinlens\": not supported (supported: perspective)");
    EXPECT_EQ(error_of(""), "scene.xml:1: scene: no sensor (wavepath needs a perspective sensor)");
}

// ---- serialized meshes ----

// One mesh of a serialized file, version 4: header, then its zlib stream.
std::string serialized_mesh(std::uint32_t flags, const std::vector<double>& positions,
                            const std::vector<double>& normals, const std::vector<std::uint32_t>& indices) {
    std::string body(reinterpret_cast<const char*>(&flags), 4);
    body += std::string("name") + '\0';
    const std::uint64_t counts[2] = {positions.size() / 3, indices.size() / 3};
    body.append(reinterpret_cast<const char*>(counts), 16);
    const bool doubles = flags & 0x2000;
    for (const std::vector<double>* values : {&positions, &normals}) {
        for (double v : *values) {
            const float f = float(v);
            body.append(doubles ? reinterpret_cast<const char*>(&v) : reinterpret_cast<const char*>(&f),
                        doubles ? 8 : 4);
        }
    }
    body.append(reinterpret_cast<const char*>(indices.data()), indices.size() * 4);
    uLongf size = compressBound(uLong(body.size()));
    std::string compressed(size, '\0');
    EXPECT_EQ(compress(reinterpret_cast<Bytef*>(compressed.data()), &size, reinterpret_cast<const Bytef*>(body.data()),
                       uLong(body.size())),
              Z_OK);
    compressed.resize(size);
    return std::string("\x1c\x04\x04\x00", 4) + compressed;
}

std::string square_mesh() {  // double precision, with normals
    return serialized_mesh(0x2001, {-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0}, {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1},
                           {0, 1, 2, 0, 2, 3});
}

std::string two_mesh_file() {
    const std::string square = square_mesh();
    const std::string triangle = serialized_mesh(0x1000, {0, 0, 0, 0.5, 0, 0, 0, 0.25, 0}, {}, {0, 1, 2});
    std::string file = square + triangle;
    const std::uint64_t offsets[2] = {0, square.size()};
    file.append(reinterpret_cast<const char*>(offsets), 16);
    const std::uint32_t count = 2;
    file.append(reinterpret_cast<const char*>(&count), 4);
    return file;
}

TEST(SerializedMesh, ReadsEachMeshOfTheFile) {
    const std::string file = two_mesh_file();
    const ImportedMesh square = parse_serialized_mesh(file, 0);
    ASSERT_EQ(square.positions.size(), 4u);
    EXPECT_EQ(square.positions[2], glm::vec3(1, 1, 0));
    EXPECT_TRUE(square.has_normals);
    EXPECT_EQ(square.normals[3], glm::vec3(0, 0, 1));
    EXPECT_EQ(square.triangles.size(), 2u);
    const ImportedMesh triangle = parse_serialized_mesh(file, 1);
    ASSERT_EQ(triangle.positions.size(), 3u);
    EXPECT_EQ(triangle.positions[2], glm::vec3(0, 0.25f, 0));
    EXPECT_FALSE(triangle.has_normals);
}

std::string serialized_error(const std::string& bytes, std::int64_t index) {
    try {
        parse_serialized_mesh(bytes, index);
    } catch (const MeshFileError& error) {
        return error.what();
    }
    return "(no error)";
}

TEST(SerializedMesh, MalformedFilesAreOneError) {
    const std::string file = two_mesh_file();
    EXPECT_EQ(serialized_error(file, 2), "shape_index 2 is out of range (the file holds 2 meshes)");
    EXPECT_EQ(serialized_error("PK\x03\x04", 0), "not a Mitsuba serialized mesh (its first two bytes are not 0x041C)");
    EXPECT_EQ(serialized_error(std::string("\x1c\x04\x05\x00", 4), 0),
              "serialized format version 5 (Mitsuba reads 3 and 4)");
    std::string bad_zlib = file;
    bad_zlib[4] = char(bad_zlib[4] ^ 0xff);
    EXPECT_EQ(serialized_error(bad_zlib, 0), "corrupt zlib stream (incorrect header check) in the flags");
    // Every truncation of a mesh is refused (its zlib stream must end, checksum and all), none crashes
    // or allocates what the counts claim.
    const std::string square = square_mesh();
    EXPECT_EQ(serialized_error(square, 0), "(no error)");
    for (std::size_t size = 0; size < square.size(); ++size)
        EXPECT_NE(serialized_error(square.substr(0, size), 0), "(no error)") << size;
}

TEST_F(MitsubaXml, SerializedShapeUnderItsTransform) {
    write("meshes.serialized", two_mesh_file());
    const Scene scene = read(sensor() + R"(<shape type="serialized"><string name="filename" value="meshes.serialized"/>
        <integer name="shape_index" value="1"/><transform name="to_world"><translate z="-3"/></transform></shape>)")
                            .scene;
    const Mesh& mesh = scene.meshes.at(0);
    ASSERT_EQ(mesh.positions.size(), 3u);
    expect_near(mesh.positions[1], {0.5, 0, -3});
    // No normals in the file: Mitsuba's smooth ones (a flat triangle: its face normal).
    ASSERT_EQ(mesh.normals.size(), 3u);
    expect_near(mesh.normals[0], {0, 0, 1});
}

// ---- convert ----

// A scene of every shape; converted to JSON and loaded, it is the same Scene, bit for bit.
TEST_F(MitsubaXml, ConvertedJsonLoadsAsTheSameScene) {
    write("meshes.serialized", two_mesh_file());
    write("tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 1\nf 1 2 3\nf 2 4 3\n");
    const std::string path = write("scene.xml", scene_of(sensor(8, 8, R"(<float name="fov" value="40"/>)") + R"(
        <shape type="sphere"><point name="center" value="1, 2, -5"/><float name="radius" value="0.3"/>
            <emitter type="area"><rgb name="radiance" value="4, 3, 2"/></emitter></shape>
        <shape type="rectangle"><transform name="to_world"><rotate x="1" angle="-90"/><translate y="-1"/></transform>
            <bsdf type="twosided"><bsdf type="diffuse"/></bsdf></shape>
        <shape type="cube"><transform name="to_world"><scale x="-0.5"/><translate z="-4"/></transform>
            <bsdf type="dielectric"/></shape>
        <shape type="disk"><boolean name="flip_normals" value="true"/><transform name="to_world"><translate z="-6"/></transform></shape>
        <shape type="serialized"><string name="filename" value="meshes.serialized"/><transform name="to_world"><translate z="-7"/></transform></shape>
        <shape type="obj"><string name="filename" value="tri.obj"/><transform name="to_world"><translate z="-8"/></transform></shape>
        <shape type="obj"><string name="filename" value="tri.obj"/><boolean name="face_normals" value="true"/></shape>
        <emitter type="constant"><rgb name="radiance" value="0.5"/></emitter>)"));
    const MitsubaScene mitsuba = read_mitsuba_scene(path, {});
    fs::create_directories(dir_.path() / "out");
    const fs::path json = dir_.path() / "out/converted.json";
    const SceneJson out = scene_json(mitsuba, json);
    write_text(json, out.json.dump());
    for (const MeshFileToWrite& mesh : out.meshes) write_ply(mesh.path, *mesh.mesh);
    const Scene from_json = load_scene(json.string());
    const Scene from_xml = load_mitsuba_scene(path, {});
    // The file mesh with face normals is referred to; the others are written beside the JSON.
    EXPECT_TRUE(fs::exists(dir_.path() / "out/converted_mesh3.ply"));
    EXPECT_FALSE(fs::exists(dir_.path() / "out/converted_mesh4.ply"));
    EXPECT_EQ(from_json.camera.position, from_xml.camera.position);
    EXPECT_EQ(from_json.camera.look_at, from_xml.camera.look_at);
    EXPECT_EQ(from_json.camera.up, from_xml.camera.up);
    EXPECT_EQ(from_json.camera.fov_y_degrees, from_xml.camera.fov_y_degrees);
    EXPECT_EQ(from_json.background, from_xml.background);
    EXPECT_EQ(from_json.render.max_depth, from_xml.render.max_depth);
    ASSERT_EQ(from_json.spheres.size(), 1u);
    EXPECT_EQ(from_json.spheres[0].center, from_xml.spheres[0].center);
    ASSERT_EQ(from_json.quads.size(), 1u);
    EXPECT_EQ(from_json.quads[0].corner, from_xml.quads[0].corner);
    EXPECT_EQ(from_json.quads[0].edge2, from_xml.quads[0].edge2);
    ASSERT_EQ(from_json.meshes.size(), from_xml.meshes.size());
    for (std::size_t m = 0; m < from_xml.meshes.size(); ++m) {
        SCOPED_TRACE(m);
        const Mesh &a = from_json.meshes[m], &b = from_xml.meshes[m];
        // assimp joins identical vertices: compare the triangles' corners.
        ASSERT_EQ(a.triangles.size(), b.triangles.size());
        EXPECT_EQ(a.normals.empty(), b.normals.empty());
        for (std::size_t t = 0; t < a.triangles.size(); ++t)
            for (int k = 0; k < 3; ++k) {
                EXPECT_EQ(a.positions[a.triangles[t][k]], b.positions[b.triangles[t][k]]);
                if (!a.normals.empty()) expect_near(a.normals[a.triangles[t][k]], b.normals[b.triangles[t][k]], 1e-6);
            }
        EXPECT_EQ(from_json.materials[std::size_t(a.material)].name, from_xml.materials[std::size_t(b.material)].name);
    }
    EXPECT_EQ(from_json.lights.size(), from_xml.lights.size());
}

// ---- textures ----

// A diffuse reflectance's texture, nested or by <ref> (one texture for both
// references), with to_uv's scale and translate as Mitsuba takes them (rows
// and columns x, y and w of the 4x4: checked against Mitsuba 3.9.1 printing
// the texture's transform); the texels of an 8-bit PNG decoded from sRGB.
TEST_F(MitsubaXml, TexturesOfADiffuseReflectance) {
    write_image(Image{2, 1, {0.5f, 0.25f, 1.0f, 0.0f, 0.0f, 0.0f}}, (dir_.path() / "t.png").string());
    const MitsubaScene read_scene = read(sensor() + R"(
        <texture type="bitmap" id="tiles">
            <string name="filename" value="t.png"/>
            <string name="filter_type" value="nearest"/>
            <string name="wrap_mode" value="clamp"/>
            <transform name="to_uv"><scale x="2" y="3"/><translate x="0.5" y="0.25"/></transform>
        </texture>
        <shape type="sphere"><bsdf type="diffuse"><ref name="reflectance" id="tiles"/></bsdf></shape>
        <shape type="sphere"><point name="center" x="3" y="0" z="0"/>
            <bsdf type="twosided"><bsdf type="diffuse"><ref name="reflectance" id="tiles"/></bsdf></bsdf></shape>
        <shape type="sphere"><point name="center" x="6" y="0" z="0"/>
            <bsdf type="diffuse"><texture type="checkerboard" name="reflectance">
                <rgb name="color0" value="0.1, 0.2, 0.3"/></texture></bsdf></shape>)");
    const Scene& scene = read_scene.scene;
    ASSERT_EQ(scene.textures.size(), 2u);
    const Texture& bitmap = scene.textures[0];
    EXPECT_EQ(bitmap.type, TextureType::Bitmap);
    EXPECT_EQ(bitmap.filter, TextureFilter::Nearest);
    EXPECT_EQ(bitmap.wrap, TextureWrap::Clamp);
    EXPECT_EQ(bitmap.to_uv, (std::array<double, 6>{2, 0, 0.5, 0, 3, 0.25}));
    ASSERT_EQ(bitmap.texels.size(), 6u);
    EXPECT_NEAR(bitmap.texels[0], 0.5f, 3e-3f);  // 188 / 255 decoded
    EXPECT_EQ(bitmap.texels[2], 1.0f);
    const Texture& checkerboard = scene.textures[1];
    EXPECT_EQ(checkerboard.type, TextureType::Checkerboard);
    expect_near(checkerboard.color0, {0.1, 0.2, 0.3});
    expect_near(checkerboard.color1, glm::dvec3(0.2));  // Mitsuba's default
    EXPECT_EQ(scene.materials[scene.spheres[0].material].texture(TexturedParameter::Albedo), 0);
    EXPECT_EQ(scene.materials[scene.spheres[1].material].texture(TexturedParameter::Albedo), 0);
    EXPECT_EQ(scene.materials[scene.spheres[2].material].texture(TexturedParameter::Albedo), 1);
    EXPECT_TRUE(scene.features().textures);
}

// A bumpmap: its one texture (under any name, nested or by <ref>) the
// material's height, its scale (Mitsuba's default 1), inside or around
// twosided, its nested BSDF's parameters kept; the feature bit on.
TEST_F(MitsubaXml, BumpmapsAsTheirNestedBsdfWithAHeight) {
    write_image(Image{2, 1, {0.5f, 0.25f, 1.0f, 0.0f, 0.0f, 0.0f}}, (dir_.path() / "h.png").string());
    const Scene scene = read(sensor() + R"(
        <texture type="bitmap" id="h"><string name="filename" value="h.png"/><boolean name="raw" value="true"/></texture>
        <shape type="sphere"><bsdf type="bumpmap"><ref name="anything" id="h"/><float name="scale" value="0.25"/>
            <bsdf type="roughplastic"><float name="alpha" value="0.2"/></bsdf></bsdf></shape>
        <shape type="sphere"><point name="center" x="3" y="0" z="0"/>
            <bsdf type="twosided"><bsdf type="bumpmap"><ref id="h"/><bsdf type="diffuse"/></bsdf></bsdf></shape>)")
                            .scene;
    ASSERT_EQ(scene.textures.size(), 1u);
    const Material& first = scene.materials[scene.spheres[0].material];
    EXPECT_EQ(first.type, MaterialType::RoughPlastic);
    EXPECT_EQ(first.alpha_u, 0.2);
    EXPECT_EQ(first.texture(TexturedParameter::BumpMap), 0);
    EXPECT_EQ(first.bump_scale, 0.25);
    const Material& second = scene.materials[scene.spheres[1].material];
    EXPECT_EQ(second.type, MaterialType::Diffuse);
    EXPECT_EQ(second.texture(TexturedParameter::BumpMap), 0);
    EXPECT_EQ(second.bump_scale, 1.0);
    EXPECT_TRUE(scene.features().bump_map);
    EXPECT_FALSE(scene.features().normal_map);
}

// The other textured colour parameters: a plastic's and roughplastic's
// diffuse_reflectance and specular_reflectance, a conductor's and
// roughconductor's specular_reflectance, and a roughconductor's and
// roughdielectric's roughness, each its material's slot; the constant of a
// textured parameter is 0 (unused), the others keep theirs.
TEST_F(MitsubaXml, TexturesOfPlasticsAndConductors) {
    const Scene scene = read(sensor() + R"(
        <texture type="checkerboard" id="a"/>
        <shape type="sphere"><bsdf type="plastic"><ref name="diffuse_reflectance" id="a"/>
            <rgb name="specular_reflectance" value="0.5"/></bsdf></shape>
        <shape type="sphere"><point name="center" x="3" y="0" z="0"/>
            <bsdf type="roughplastic"><texture type="checkerboard" name="specular_reflectance"/></bsdf></shape>
        <shape type="sphere"><point name="center" x="6" y="0" z="0"/>
            <bsdf type="twosided"><bsdf type="conductor"><ref name="specular_reflectance" id="a"/></bsdf></bsdf></shape>
        <shape type="sphere"><point name="center" x="9" y="0" z="0"/>
            <bsdf type="roughconductor"><ref name="specular_reflectance" id="a"/></bsdf></shape>
        <shape type="sphere"><point name="center" x="12" y="0" z="0"/>
            <bsdf type="roughdielectric"><ref name="alpha" id="a"/></bsdf></shape>
        <shape type="sphere"><point name="center" x="15" y="0" z="0"/>
            <bsdf type="roughconductor"><float name="alpha_u" value="0.3"/><ref name="alpha_v" id="a"/></bsdf></shape>)")
                            .scene;
    // the roughnesses read `a` as a number: a third texture, `a` with its colours swapped (Mitsuba's eval_1)
    ASSERT_EQ(scene.textures.size(), 3u);
    expect_near(scene.textures[2].color0, scene.textures[0].color1);
    expect_near(scene.textures[2].color1, scene.textures[0].color0);
    EXPECT_EQ(scene.textures[2].name, scene.textures[0].name);
    auto material = [&](int sphere) {
        return scene.materials[std::size_t(scene.spheres[std::size_t(sphere)].material)];
    };
    using P = TexturedParameter;
    EXPECT_EQ(material(0).type, MaterialType::Plastic);
    EXPECT_EQ(material(0).texture(P::Albedo), 0);
    EXPECT_EQ(material(0).texture(P::SpecularReflectance), kNoTexture);
    expect_near(material(0).albedo, glm::dvec3(0.0));
    expect_near(material(0).specular_reflectance, glm::dvec3(0.5));
    EXPECT_EQ(material(1).type, MaterialType::RoughPlastic);
    EXPECT_EQ(material(1).texture(P::Albedo), kNoTexture);
    EXPECT_EQ(material(1).texture(P::SpecularReflectance), 1);
    expect_near(material(1).albedo, glm::dvec3(0.5));  // Mitsuba's default
    EXPECT_EQ(material(2).type, MaterialType::Conductor);
    EXPECT_EQ(material(2).texture(P::SpecularReflectance), 0);
    EXPECT_EQ(material(3).type, MaterialType::RoughConductor);
    EXPECT_EQ(material(3).texture(P::SpecularReflectance), 0);
    EXPECT_EQ(material(3).texture(P::Albedo), kNoTexture);
    // a roughness: `alpha` both tangents', alpha_u and alpha_v one each
    EXPECT_EQ(material(4).type, MaterialType::RoughDielectric);
    EXPECT_EQ(material(4).texture(P::AlphaU), 2);
    EXPECT_EQ(material(4).texture(P::AlphaV), 2);
    EXPECT_EQ(material(5).texture(P::AlphaU), kNoTexture);
    EXPECT_EQ(material(5).alpha_u, 0.3);
    EXPECT_EQ(material(5).texture(P::AlphaV), 2);
}

// A mask around its BSDF (twosided inside or outside): a constant opacity,
// Mitsuba's default 0.5, and a texture (a checkerboard read as a number:
// its colours swapped), which makes the constant 0 (unused).
TEST_F(MitsubaXml, MasksAroundTheirBsdfs) {
    const Scene scene = read(sensor() + R"(
        <shape type="sphere"><bsdf type="mask"><float name="opacity" value="0.25"/>
            <bsdf type="twosided"><bsdf type="diffuse"/></bsdf></bsdf></shape>
        <shape type="sphere"><point name="center" x="3" y="0" z="0"/>
            <bsdf type="twosided"><bsdf type="mask"><bsdf type="roughconductor"/></bsdf></bsdf></shape>
        <shape type="sphere"><point name="center" x="6" y="0" z="0"/>
            <bsdf type="mask"><texture type="checkerboard" name="opacity">
                <float name="color0" value="1"/><float name="color1" value="0"/></texture>
            <bsdf type="dielectric"/></bsdf></shape>)")
                            .scene;
    auto material = [&](int sphere) {
        return scene.materials[std::size_t(scene.spheres[std::size_t(sphere)].material)];
    };
    EXPECT_EQ(material(0).type, MaterialType::Diffuse);
    EXPECT_EQ(material(0).opacity, 0.25);
    EXPECT_EQ(material(1).type, MaterialType::RoughConductor);
    EXPECT_EQ(material(1).opacity, 0.5);
    EXPECT_EQ(material(2).type, MaterialType::Glass);
    EXPECT_EQ(material(2).opacity, 0.0);
    ASSERT_EQ(material(2).texture(TexturedParameter::Opacity), 0);
    ASSERT_EQ(scene.textures.size(), 1u);
    expect_near(scene.textures[0].color0, glm::dvec3(0.0));
    expect_near(scene.textures[0].color1, glm::dvec3(1.0));
    EXPECT_TRUE(material(0).masked() && material(1).masked() && material(2).masked());
    EXPECT_TRUE(scene.features().mask);
}

}  // namespace mitsuba_xml_test
}  // namespace
}  // namespace wp::test
