// Mitsuba 3 XML scenes through the binary: `wavepath render SCENE.xml` with
// -D, the pixel filter's one warning, `wavepath convert` and its JSON, which
// renders the same image; failures are one line, exit 3 (2 for the command
// line) and no output (docs/scene-format.md, "Mitsuba XML").
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "cli/run_wavepath.h"

namespace wp::test {
namespace {
// A namespace of its own: the sanitizer build compiles test files together (unity).
namespace mitsuba_cli_test {

namespace fs = std::filesystem;

const fs::path kScenes = fs::path(WAVEPATH_SOURCE_DIR) / "scenes/test/mitsuba";

class MitsubaCli : public ::testing::Test {
 protected:
    CommandResult run(const std::vector<std::string>& args) { return run_wavepath(args, scratch_.path()); }
    // The XML scene and its conversion `json` render the same bytes with `flags`.
    void expect_same_image(const std::string& xml, const std::string& json, const std::vector<std::string>& flags) {
        std::vector<std::string> from_xml{"render", xml, "-o", scratch_ / "xml.pfm"};
        std::vector<std::string> from_json{"render", json, "-o", scratch_ / "json.pfm"};
        from_xml.insert(from_xml.end(), flags.begin(), flags.end());
        from_json.insert(from_json.end(), flags.begin(), flags.end());
        ASSERT_EQ(run(from_xml).exit_code, 0);
        ASSERT_EQ(run(from_json).exit_code, 0);
        EXPECT_EQ(read_text(scratch_ / "xml.pfm"), read_text(scratch_ / "json.pfm"));
    }
    TempDirectory scratch_{"scratch"}, out_{"out"};
};

TEST_F(MitsubaCli, RendersXmlWithDefines) {
    const CommandResult result = run({"render", (kScenes / "camera.xml").string(), "-D", "fov_axis=diagonal", "-D",
                                      "spp=2", "-o", out_ / "camera.pfm", "-q"});
    EXPECT_EQ(result.exit_code, 0) << result.err;
    EXPECT_EQ(result.err, "");
    EXPECT_EQ(out_.entries(), std::vector<std::string>{"camera.pfm"});
}

TEST_F(MitsubaCli, ConvertedJsonRendersTheSameImage) {
    const std::string scene = (kScenes / "cornell_box.xml").string();
    const CommandResult convert = run({"convert", scene, "-o", out_ / "box.json"});
    ASSERT_EQ(convert.exit_code, 0) << convert.err;
    EXPECT_EQ(convert.err, "wavepath: wrote " + (out_ / "box.json") + " (2 meshes, 0 textures)\n");
    // The two cubes, written beside the JSON.
    EXPECT_EQ(out_.entries(), (std::vector<std::string>{"box.json", "box_mesh0.ply", "box_mesh1.ply"}));
    expect_same_image(scene, out_ / "box.json", {"--spp", "4", "--seed", "3", "-q"});
}

// The plastics (their every parameter, scene_writer.cpp) survive the conversion to JSON.
TEST_F(MitsubaCli, ConvertedPlasticsRenderTheSameImage) {
    const std::string scene = (kScenes / "plastics.xml").string();
    ASSERT_EQ(run({"convert", scene, "-o", out_ / "plastics.json"}).exit_code, 0);
    expect_same_image(scene, out_ / "plastics.json", {"--spp", "1", "-q"});
}

// The conductors, rough and smooth, and the rough and thin dielectrics, through the JSON and back.
TEST_F(MitsubaCli, ConvertedMetalsAndGlassRenderTheSameImage) {
    const std::string scene = (kScenes / "metals_and_glass.xml").string();
    ASSERT_EQ(run({"convert", scene, "-o", out_ / "metals.json"}).exit_code, 0);
    EXPECT_EQ(read_text(out_ / "metals.json").find("null"), std::string::npos);
    expect_same_image(scene, out_ / "metals.json", {"--spp", "1", "-q"});
}

// Textures (bitmaps nested and by <ref>, raw, nearest, mirror; a checkerboard;
// their to_uv) on every parameter that takes one, and normal and bump maps
// and masks around their nested materials (a bump map's scale, a mask's
// opacity; a checkerboard roughness or opacity with its colours swapped),
// through the JSON and
// back: the images are found from the JSON's folder, which is not the XML's.
TEST_F(MitsubaCli, ConvertedTexturesRenderTheSameImage) {
    for (const auto& [name, textures] :
         {std::pair{"textures", 3}, {"textured_materials", 5}, {"normal_map", 2}, {"bump_map", 2}, {"mask", 2}}) {
        SCOPED_TRACE(name);
        const std::string scene = (kScenes / (std::string(name) + ".xml")).string();
        const std::string json = out_ / (std::string(name) + ".json");
        const CommandResult convert = run({"convert", scene, "-o", json});
        ASSERT_EQ(convert.exit_code, 0) << convert.err;
        EXPECT_NE(convert.err.find(" " + std::to_string(textures) + " textures)"), std::string::npos) << convert.err;
        expect_same_image(scene, json, {"--spp", "1", "-q"});
    }
}

// The pixel filter travels into the JSON: an image with edges renders the same from either.
TEST_F(MitsubaCli, ConvertedJsonKeepsThePixelFilter) {
    const std::string scene = (kScenes / "filters.xml").string();
    for (const std::string filter : {"tent", "gaussian"}) {
        const CommandResult convert = run({"convert", scene, "-D", "filter=" + filter, "-o", out_ / "filters.json"});
        ASSERT_EQ(convert.exit_code, 0) << convert.err;
        EXPECT_NE(read_text(out_ / "filters.json").find("\"" + filter + "\""), std::string::npos);
        ASSERT_EQ(run({"render", scene, "-D", "filter=" + filter, "-o", scratch_ / "xml.pfm", "-q"}).exit_code, 0);
        ASSERT_EQ(run({"render", out_ / "filters.json", "-o", scratch_ / "json.pfm", "-q"}).exit_code, 0);
        EXPECT_EQ(read_text(scratch_ / "xml.pfm"), read_text(scratch_ / "json.pfm")) << filter;
        ASSERT_EQ(run({"render", scene, "-D", "filter=box", "-o", scratch_ / "box.pfm", "-q"}).exit_code, 0);
        EXPECT_NE(read_text(scratch_ / "box.pfm"), read_text(scratch_ / "json.pfm")) << filter;
    }
}

TEST_F(MitsubaCli, FailuresAreOneLineAndLeaveNoOutput) {
    write_text(scratch_ / "bad.xml",
               "<scene version=\"3.0.0\">\n<shape type=\"cylinder\"/>\n<sensor type=\"perspective\"/>\n</scene>\n");
    CommandResult result = run({"convert", scratch_ / "bad.xml", "-o", out_ / "bad.json"});
    EXPECT_EQ(result.exit_code, 3);
    EXPECT_EQ(result.err, "wavepath: error: " + (scratch_ / "bad.xml") +
                              ":2: shape \"cylinder\": not supported (supported: obj, ply, serialized, rectangle, "
                              "cube, sphere, disk)\n");
    result = run({"convert", (kScenes / "cornell_box.xml").string(), "-o", out_ / "box.exr"});
    EXPECT_EQ(result.exit_code, 2);
    EXPECT_EQ(result.err, "wavepath: error: convert: -o must name a .json file, got " + (out_ / "box.exr") + "\n");
    result = run({"render", std::string(WAVEPATH_SOURCE_DIR) + "/scenes/test/room_small.json", "-D", "spp=2", "-o",
                  out_ / "room.pfm"});
    EXPECT_EQ(result.exit_code, 2);
    EXPECT_EQ(result.err, "wavepath: error: -D: applies to Mitsuba XML scenes (.xml) only, and " +
                              std::string(WAVEPATH_SOURCE_DIR) + "/scenes/test/room_small.json is read as JSON\n");
    result = run({"render", (kScenes / "camera.xml").string(), "-D", "fov axis", "-o", out_ / "camera.pfm"});
    EXPECT_EQ(result.exit_code, 2);
    EXPECT_EQ(result.err,
              "wavepath: error: -D: expected name=value (name of letters, digits and '_'), got 'fov axis'\n");
    EXPECT_EQ(out_.entries(), std::vector<std::string>{});
}

}  // namespace mitsuba_cli_test
}  // namespace
}  // namespace wp::test
