// Bad mesh files through the wavepath binary: exit 3, one error line naming
// the scene file, the JSON path and the mesh file, and no output file.
#include <gtest/gtest.h>

#include <algorithm>
#include <nlohmann/json.hpp>
#include <string>

#include "cli/run_wavepath.h"
#include "support/mesh_files.h"

namespace wp::test {
namespace {

nlohmann::json scene_with_shape(const char* shape) {
    nlohmann::json scene = nlohmann::json::parse(R"({
      "camera": {"position": [0, 0, 4], "look_at": [0, 0, 0], "fov_y": 45, "width": 8, "height": 8},
      "render": {"spp": 1, "max_depth": 2},
      "materials": {"white": {"type": "diffuse", "albedo": [0.6, 0.6, 0.6]}},
      "shapes": []
    })");
    scene["shapes"].push_back(nlohmann::json::parse(shape));
    return scene;
}

class BadMeshCli : public ::testing::TestWithParam<BadMeshCase> {
 protected:
    // Scenes and outputs apart, so that "no output" means an empty directory.
    TempDirectory scenes_{"scenes"}, outputs_{"outputs"};
};

TEST_P(BadMeshCli, OneLineExitCode3AndNoOutput) {
    const BadMeshCase& c = GetParam();
    if (c.file) write_file(scenes_.path() / c.file, c.contents);
    const std::string scene_path = scenes_ / "scene.json";
    write_text(scene_path, scene_with_shape(c.shape).dump(2));
    const CommandResult result = run_wavepath({"render", scene_path, "-o", outputs_ / "out.exr"}, scenes_.path());
    EXPECT_EQ(result.exit_code, 3) << result.err;
    EXPECT_EQ(std::count(result.err.begin(), result.err.end(), '\n'), 1) << result.err;
    EXPECT_EQ(result.err.rfind("wavepath: error: " + scene_path + ": " + c.message, 0), 0u) << result.err;
    EXPECT_TRUE(outputs_.entries().empty()) << "left in the output directory: " << outputs_.entries().front();
}

INSTANTIATE_TEST_SUITE_P(Cli, BadMeshCli, ::testing::ValuesIn(kBadMeshCases),
                         [](const auto& info) { return std::string(info.param.name); });

}  // namespace
}  // namespace wp::test
