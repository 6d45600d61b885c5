// glTF 2.0 files as scenes through the binary (docs/scene-format.md, "glTF
// scenes"): `wavepath render model.gltf` renders the same bytes as the JSON
// written by hand beside it and as its `wavepath convert`, notes the
// defaults it takes, and refuses -D.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "cli/run_wavepath.h"

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

TEST_F(GltfCli, NotesTheDefaultCameraAndLight) {
    const std::string gltf = (kScenes / "no_camera_no_light.gltf").string();
    const CommandResult result = run({"render", gltf, "-o", out_ / "image.pfm", "--spp", "1"});
    ASSERT_EQ(result.exit_code, 0) << result.err;
    EXPECT_NE(result.err.find("wavepath: note: " + gltf + ": no camera: "), std::string::npos) << result.err;
    EXPECT_NE(result.err.find("wavepath: note: " + gltf + ": no light: "), std::string::npos) << result.err;
    EXPECT_EQ(image_of(gltf), image_of((kScenes / "no_camera_no_light.json").string()));
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
