// The mesh import's failures through the binary (import/import_process.h):
// a crash, an allocation beyond the memory limit, a hang and a malformed
// answer of wavepath-import each end the render with one error line naming
// the mesh file, exit 3 and no output.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cli/run_wavepath.h"

namespace wp::test {
namespace {

namespace fs = std::filesystem;

const fs::path kBunny = fs::path(WAVEPATH_SOURCE_DIR) / "scenes/meshes/bunny.obj";

class MeshImportCli : public ::testing::Test {
 protected:
    // A small scene of the mesh file and a light.
    std::string write_scene(const fs::path& mesh) const {
        nlohmann::json scene = nlohmann::json::parse(R"({
          "camera": {"position": [0, 1, 4], "look_at": [0, 0.5, 0], "fov_y": 45, "width": 8, "height": 8},
          "render": {"spp": 1},
          "materials": {"white": {"type": "diffuse", "albedo": [0.6, 0.6, 0.6]},
                        "lamp": {"type": "emitter", "radiance": [5, 5, 5]}},
          "shapes": [{"type": "quad", "corner": [-0.5, 2, -0.5], "edge1": [1, 0, 0], "edge2": [0, 0, 1],
                      "material": "lamp"}]
        })");
        scene["shapes"].push_back({{"type", "mesh"}, {"file", mesh.string()}, {"material", "white"}});
        const std::string path = files_ / "scene.json";
        write_text(path, scene.dump());
        return path;
    }
    CommandResult render(const fs::path& mesh, std::vector<std::string> flags,
                         const fs::path& binary = WAVEPATH_BINARY) {
        std::vector<std::string> args{"render", write_scene(mesh), "-o", outputs_ / "out.exr"};
        args.insert(args.end(), flags.begin(), flags.end());
        return run_wavepath(args, scratch_.path(), {}, binary);
    }
    void expect_one_error(const CommandResult& result, const fs::path& mesh, const std::string& problem) {
        EXPECT_EQ(result.exit_code, 3);
        EXPECT_EQ(result.err, "wavepath: error: " + (files_ / "scene.json") + ": shapes[1].file: " + mesh.string() +
                                  ": " + problem + "\n");
        EXPECT_EQ(result.out, "");
        EXPECT_EQ(outputs_.entries(), std::vector<std::string>{});
    }
    // A copy of the binary with a stand-in for its helper beside it (a /bin/sh script running `body`).
    fs::path binary_with_fake_helper(const std::string& body) const {
        const fs::path directory = files_.path() / "bin";
        fs::create_directories(directory);
        fs::copy_file(WAVEPATH_BINARY, directory / "wavepath", fs::copy_options::overwrite_existing);
        write_text(directory / "wavepath-import", "#!/bin/sh\n" + body + "\n");
        fs::permissions(directory / "wavepath-import", fs::perms::owner_all);
        return directory / "wavepath";
    }

    TempDirectory scratch_{"scratch"}, files_{"files"}, outputs_{"outputs"};
};

TEST_F(MeshImportCli, AnAllocationBeyondTheMemoryLimit) {
    expect_one_error(render(kBunny, {"--mesh-import-memory", "1"}), kBunny,
                     "wavepath-import ran out of memory importing it (limit 1 MiB, --mesh-import-memory)");
}

TEST_F(MeshImportCli, AHangStoppedAtTheWallTimeLimit) {
    // Opening a FIFO without a writer blocks the helper.
    const fs::path fifo = files_.path() / "mesh.obj";
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    expect_one_error(render(fifo, {"--mesh-import-time", "0.5"}), fifo,
                     "wavepath-import did not finish within 0.5 s and was stopped (--mesh-import-time)");
}

TEST_F(MeshImportCli, ACrash) {
    expect_one_error(render(kBunny, {}, binary_with_fake_helper("kill -SEGV $$")), kBunny,
                     "wavepath-import crashed importing it (signal 11: Segmentation fault)");
}

TEST_F(MeshImportCli, AMalformedAnswer) {
    expect_one_error(render(kBunny, {}, binary_with_fake_helper("printf 'WPIMPORT\\001' >&3")), kBunny,
                     "wavepath-import sent a malformed answer: it ends within the version (4 bytes, 1 left)");
}

TEST_F(MeshImportCli, AMissingHelperIsARuntimeError) {
    const fs::path directory = files_.path() / "bin";
    fs::create_directories(directory);
    fs::copy_file(WAVEPATH_BINARY, directory / "wavepath");
    const CommandResult result = render(kBunny, {}, directory / "wavepath");
    EXPECT_EQ(result.exit_code, 1);
    EXPECT_EQ(result.err, "wavepath: error: cannot start the mesh import helper " +
                              (directory / "wavepath-import").string() + ": No such file or directory\n");
    EXPECT_EQ(outputs_.entries(), std::vector<std::string>{});
}

}  // namespace
}  // namespace wp::test
