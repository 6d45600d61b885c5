// check_before_assimp: which files go to check_ply and check_off (the
// corpus, tests/corpus/bad/scenes, has the files that made assimp allocate
// tens of GB, loop or crash).
#include "scene/assimp_prechecks.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <string>

#include "scene/mesh_file.h"
#include "support/mesh_files.h"
#include "support/thrown_message.h"

namespace wp::test {
namespace {

namespace fs = std::filesystem;

class AssimpPrechecks : public ::testing::Test {
 protected:
    // The message check_before_assimp throws for a file of `bytes`, or "(none)".
    std::string problem(const std::string& name, const std::string& bytes) {
        write_file(dir_ / name, bytes);
        return thrown_message<MeshFileError>([&] { check_before_assimp(dir_ / name); });
    }
    AssimpPrechecks() { fs::create_directories(dir_); }
    ~AssimpPrechecks() override { fs::remove_all(dir_); }

    const fs::path dir_ =
        fs::temp_directory_path() /
        ("wavepath-assimp-prechecks-" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) +
         "-" + std::to_string(::getpid()));
};

// check_off (tests/scene/off_check_test.cpp) reads every file assimp reads as OFF.
TEST_F(AssimpPrechecks, FilesAssimpReadsAsOffAreCheckedAsOff) {
    const std::string not_off =
        "OFF header: the first word must be OFF (after prefixes among ST, C, N, 4, n) or the vertex count";
    EXPECT_EQ(problem("a.off", "ply\nformat ascii 1.0\nend_header\n"), not_off);
    EXPECT_EQ(problem("a.OFF", "junk"), not_off);  // the extension in any case
    // A file whose extension assimp does not know, by its signature ("off" in any case).
    EXPECT_EQ(problem("mesh", "Off\n3 1 0\n"), not_off);
    EXPECT_EQ(problem("mesh.xyz", "OFF\n3 1\n"),
              "OFF header: expected the vertex, face and edge counts (whole numbers below 2^32)");
    EXPECT_EQ(problem("mesh.xyz", "OF F\n3 1\n"), "(none)");
    EXPECT_EQ(problem("mesh.obj", "OFF\n3 1\n"), "(none)");  // assimp reads it as OBJ
}

// check_ply (tests/scene/ply_check_test.cpp) reads every file assimp reads
// as PLY: one named .ply whatever it holds (fuzz_mesh: assimp skips a first
// line that starts with a line end and crashed on the "ply" after it), or,
// under a name no reader claims, one with "ply" in its first 200 bytes.
TEST_F(AssimpPrechecks, FilesAssimpReadsAsPlyAreCheckedAsPly) {
    const std::string not_ply = "PLY header line 1: expected \"ply\"";
    EXPECT_EQ(problem("a.ply", "plY\nformat ascii 1.0\nend_header\n"), not_ply);
    EXPECT_EQ(problem("a.PLY", "\r\r\xd3\xecPy\nply\nformat ascii 1.0\nend_header\n"),
              "PLY header line 1: a control byte \"\\x0d\" in the line");
    EXPECT_EQ(problem("a.ply", "junk\n"), not_ply);
    EXPECT_EQ(problem("mesh", "\n PLYX\n"), not_ply);
    EXPECT_EQ(problem("mesh.xyz", "x" + std::string(150, ' ') + "ply\n"), not_ply);
    EXPECT_EQ(problem("mesh.xyz", "x" + std::string(199, ' ') + "ply\n"), "(none)");
    EXPECT_EQ(problem("mesh.obj", "ply\nformat ascii 1.0\nend_header\n"), "(none)");  // assimp reads it as OBJ
    EXPECT_EQ(problem("a.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nend_header\n"),
              "PLY file ends after line 5, before \"vertex\" element 1 of 1");
}

// With several readers for an extension (glTF 1.0 and 2.0 for .gltf) and
// none accepting the file, assimp tries every reader's signature: fuzz_mesh's
// .gltf went to the Quick3D reader, which asked for 2 TB.
TEST_F(AssimpPrechecks, FilesNoReaderOfTheirExtensionAcceptsAreRefused) {
    const std::string refused = "none of assimp's readers for its extension (glTF Importer, glTF2 Importer) accepts it";
    EXPECT_EQ(problem("a.gltf", "quick3Ds{\"asset\": {}}"), refused);
    EXPECT_EQ(problem("a.GLB", "{}"), refused);
    EXPECT_EQ(problem("a.gltf", two_squares_gltf()), "(none)");
}

TEST_F(AssimpPrechecks, OtherFilesPassUnchecked) {
    EXPECT_EQ(problem("a.obj", kSquareObj), "(none)");
    EXPECT_EQ(problem("b.obj", "# ply\nOFF\n"), "(none)");
    EXPECT_EQ(problem("a.stl", square_stl_binary()), "(none)");
    EXPECT_EQ(problem("b.ply", square_ply_binary()), "(none)");
    EXPECT_EQ(problem("b.off", kSquareOff), "(none)");
}

}  // namespace
}  // namespace wp::test
