// The mesh import's failures through the binary (import/import_process.h):
// a crash, an allocation beyond the memory limit, a hang and a malformed
// answer of wavepath-import each end the render with one error line naming
// the mesh file, exit 3 and no output, as does a missing file among
// others; a mesh in pieces renders as the mesh in one file.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "cli/run_wavepath.h"

namespace wp::test {
namespace {

namespace fs = std::filesystem;

const fs::path kBunny = fs::path(WAVEPATH_SOURCE_DIR) / "scenes/meshes/bunny.obj";

class MeshImportCli : public ::testing::Test {
 protected:
    // A small scene of the mesh files and a light.
    std::string write_scene(const std::vector<fs::path>& meshes) const {
        nlohmann::json scene = nlohmann::json::parse(R"({
          "camera": {"position": [0, 1, 4], "look_at": [0, 0.5, 0], "fov_y": 45, "width": 8, "height": 8},
          "render": {"spp": 1},
          "materials": {"white": {"type": "diffuse", "albedo": [0.6, 0.6, 0.6]},
                        "lamp": {"type": "emitter", "radiance": [5, 5, 5]}},
          "shapes": [{"type": "quad", "corner": [-0.5, 2, -0.5], "edge1": [1, 0, 0], "edge2": [0, 0, 1],
                      "material": "lamp"}]
        })");
        for (const fs::path& mesh : meshes)
            scene["shapes"].push_back({{"type", "mesh"}, {"file", mesh.string()}, {"material", "white"}});
        const std::string path = files_ / "scene.json";
        write_text(path, scene.dump());
        return path;
    }
    CommandResult render(const fs::path& mesh, std::vector<std::string> flags,
                         const fs::path& binary = WAVEPATH_BINARY) {
        std::vector<std::string> args{"render", write_scene({mesh}), "-o", outputs_ / "out.exr"};
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

// The bunny's faces in `count` OBJ files, in order, each with all of its vertices (the import keeps the
// ones its faces use).
std::vector<fs::path> bunny_in_pieces(const fs::path& directory, int count) {
    std::string vertices;
    std::vector<std::string> faces;
    std::istringstream lines(read_text(kBunny));
    for (std::string line; std::getline(lines, line);) {
        if (line.starts_with("v ")) vertices += line + "\n";
        if (line.starts_with("f ")) faces.push_back(line + "\n");
    }
    std::vector<fs::path> pieces;
    for (int i = 0; i < count; ++i) {
        std::string text = vertices;
        for (std::size_t f = faces.size() * i / count; f < faces.size() * (i + 1) / count; ++f) text += faces[f];
        pieces.push_back(directory / ("piece" + std::to_string(i) + ".obj"));
        write_text(pieces.back(), text);
    }
    return pieces;
}

TEST_F(MeshImportCli, TheBunnyInPiecesRendersAsTheBunnyInOneFile) {
    // The same triangles in the same order: the same BVH, the same image to the bit (the pieces are imported
    // ahead, one after another, while wavepath checks the one before).
    const std::vector<fs::path> pieces = bunny_in_pieces(files_.path(), 4);
    const auto render_to = [&](const std::vector<fs::path>& meshes, const std::string& image) {
        const std::vector<std::string> args{"render", write_scene(meshes), "-o", outputs_ / image, "--spp", "2", "-q"};
        EXPECT_EQ(run_wavepath(args, scratch_.path()).exit_code, 0);
        return read_text(outputs_ / image);
    };
    EXPECT_EQ(render_to({kBunny}, "whole.pfm"), render_to(pieces, "pieces.pfm"));
}

TEST_F(MeshImportCli, AMissingFileAmongOthersIsNamed) {
    std::vector<fs::path> pieces = bunny_in_pieces(files_.path(), 4);
    pieces[2] = files_.path() / "absent.obj";
    const std::vector<std::string> args{"render", write_scene(pieces), "-o", outputs_ / "out.exr"};
    const CommandResult result = run_wavepath(args, scratch_.path());
    EXPECT_EQ(result.exit_code, 3);
    EXPECT_EQ(result.err, "wavepath: error: " + (files_ / "scene.json") + ": shapes[3].file: " + pieces[2].string() +
                              ": cannot open: No such file or directory\n");
    EXPECT_EQ(outputs_.entries(), std::vector<std::string>{});
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
