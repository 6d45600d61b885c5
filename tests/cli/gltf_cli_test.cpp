// glTF 2.0 files as scenes through the binary (docs/scene-format.md, "glTF
// scenes"): `wavepath render model.gltf` renders the same bytes as the JSON
// written by hand beside it and as its `wavepath convert`, notes the
// defaults it takes, and refuses -D.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <numbers>
#include <string>
#include <vector>

#include "cli/run_wavepath.h"
#include "image/image_io.h"

namespace wp::test {
namespace {
// A namespace of its own: the sanitizer build compiles test files together (unity).
namespace gltf_cli_test {

namespace fs = std::filesystem;

const fs::path kScenes = fs::path(WAVEPATH_SOURCE_DIR) / "scenes/test/gltf";

class GltfCli : public ::testing::Test {
 protected:
    CommandResult run(const std::vector<std::string>& args) { return run_wavepath(args, scratch_.path()); }
    // The image `scene` renders at 1 sample per pixel.
    std::string image_of(const std::string& scene) {
        const CommandResult result = run({"render", scene, "-o", scratch_ / "image.pfm", "--spp", "1", "-q"});
        EXPECT_EQ(result.exit_code, 0) << result.err;
        return read_text(scratch_ / "image.pfm");
    }
    TempDirectory scratch_{"scratch"}, out_{"out"};
};

TEST_F(GltfCli, RendersTheSameImageAsItsHandWrittenJsonAndItsConversion) {
    const std::string gltf = (kScenes / "materials.gltf").string();
    const std::string image = image_of(gltf);
    EXPECT_EQ(image.size(), 640u * 427u * 12u + 16u);  // "PF\n640 427\n-1.0\n" and 3 floats a pixel
    EXPECT_EQ(image_of((kScenes / "materials.json").string()), image);

    const CommandResult convert = run({"convert", gltf, "-o", out_ / "materials.json"});
    ASSERT_EQ(convert.exit_code, 0) << convert.err;
    EXPECT_EQ(convert.err, "wavepath: wrote " + (out_ / "materials.json") + " (4 meshes, 0 textures)\n");
    EXPECT_EQ(out_.entries(), (std::vector<std::string>{"materials.json", "materials_mesh0.ply", "materials_mesh1.ply",
                                                        "materials_mesh2.ply", "materials_mesh3.ply"}));
    EXPECT_EQ(image_of(out_ / "materials.json"), image);
}

// A .glb's embedded image renders as the image file beside a .gltf, and its
// conversion writes the image's bytes beside the JSON, which renders the same.
TEST_F(GltfCli, AnEmbeddedImageRendersAsItsFileAndConvertsToIt) {
    const std::string image = image_of((kScenes / "textured.gltf").string());
    const std::string glb = (kScenes / "textured.glb").string();
    EXPECT_EQ(image_of(glb), image);
    ASSERT_EQ(run({"convert", glb, "-o", out_ / "textured.json", "-q"}).exit_code, 0);
    EXPECT_EQ(out_.entries(), (std::vector<std::string>{"textured.json", "textured_image0.png", "textured_mesh0.ply"}));
    EXPECT_EQ(read_text(out_ / "textured_image0.png"), read_text(kScenes / "../textures/tiles.png"));
    EXPECT_EQ(image_of(out_ / "textured.json"), image);
}

TEST_F(GltfCli, NotesTheDefaultCameraAndLight) {
    const std::string gltf = (kScenes / "no_camera_no_light.gltf").string();
    const CommandResult result = run({"render", gltf, "-o", out_ / "image.pfm", "--spp", "1"});
    ASSERT_EQ(result.exit_code, 0) << result.err;
    EXPECT_NE(result.err.find("wavepath: note: " + gltf + ": no camera: "), std::string::npos) << result.err;
    EXPECT_NE(result.err.find("wavepath: note: " + gltf + ": no light: "), std::string::npos) << result.err;
    EXPECT_EQ(image_of(gltf), image_of((kScenes / "no_camera_no_light.json").string()));
}

// A point light gives the irradiance I cos / d^2: point_light.gltf's grey
// floor (albedo 0.5) 1 below a light of intensity 1, seen from 3 above. A
// block of 20 x 20 pixels beside the light's foot, at 4 samples each,
// against 0.5 / pi / d^3 at each pixel's centre. The estimate's only spread
// is the pixel jitter's (d varies by under 0.1% across a pixel, so the block
// mean's relative deviation stays far below 1e-4); a radiance off by any
// factor (pi, 4) fails the 2e-3 bound.
TEST_F(GltfCli, APointLightGivesItsIrradiance) {
    const std::string gltf = (kScenes / "point_light.gltf").string();
    const CommandResult result = run({"render", gltf, "-o", scratch_ / "image.pfm", "--spp", "4", "-q"});
    ASSERT_EQ(result.exit_code, 0) << result.err;
    const Image image = read_image(scratch_ / "image.pfm");
    ASSERT_EQ(image.width, 640);
    ASSERT_EQ(image.height, 640);
    const double half_width = 3.0 * std::tan(0.125);  // yfov 0.25 at the floor, 3 below the camera
    double rendered = 0.0, expected = 0.0;
    for (int y = 310; y < 330; ++y) {
        for (int x = 420; x < 440; ++x) {
            const double fx = ((x + 0.5) / 640.0 * 2.0 - 1.0) * half_width;
            const double fz = ((y + 0.5) / 640.0 * 2.0 - 1.0) * half_width;
            const double d = std::sqrt(1.0 + fx * fx + fz * fz);
            expected += 0.5 / std::numbers::pi / (d * d * d);
            rendered += image.rgb[3 * std::size_t(y * 640 + x)];
        }
    }
    EXPECT_NEAR(rendered / expected, 1.0, 2e-3);
}

// veil.gltf: a BLEND veil (a mask) over a floor, diffuse materials only, so
// the mask's pass is the scene's one delta lobe: the wavefront carries the
// paths' specular flag for it (FeatureSet::specular, as the kernels'
// WP_HAS_SPECULAR; without it the wavefront's kernels failed to launch) and
// renders the reference's bytes, as does the scene's conversion to JSON.
TEST_F(GltfCli, AMaskAmongDiffuseMaterialsRendersOnEveryBackend) {
    const std::string gltf = (kScenes / "veil.gltf").string();
    std::vector<std::string> images;
    for (const char* backend : {"wavefront", "megakernel", "reference"}) {
        const CommandResult result =
            run({"render", gltf, "-o", scratch_ / "image.pfm", "--spp", "1", "--backend", backend, "-q"});
        ASSERT_EQ(result.exit_code, 0) << backend << ": " << result.err;
        images.push_back(read_text(scratch_ / "image.pfm"));
    }
    EXPECT_EQ(images[0], images[2]);
    EXPECT_EQ(images[1], images[2]);
    // Its conversion (the mask, the point light's sphere) renders the same bytes.
    ASSERT_EQ(run({"convert", gltf, "-o", out_ / "veil.json", "-q"}).exit_code, 0);
    ASSERT_EQ(
        run({"render", out_ / "veil.json", "-o", scratch_ / "image.pfm", "--spp", "1", "--backend", "reference", "-q"})
            .exit_code,
        0);
    EXPECT_EQ(read_text(scratch_ / "image.pfm"), images[2]);
}

TEST_F(GltfCli, DefinesAreACommandLineError) {
    const std::string gltf = (kScenes / "materials.gltf").string();
    const CommandResult result = run({"render", gltf, "-D", "spp=2", "-o", out_ / "image.pfm"});
    EXPECT_EQ(result.exit_code, 2);
    EXPECT_EQ(result.err, "wavepath: error: -D: applies to Mitsuba XML scenes (.xml) only, and " + gltf + " is glTF\n");
    EXPECT_EQ(out_.entries(), std::vector<std::string>{});
}

}  // namespace gltf_cli_test
}  // namespace
}  // namespace wp::test
