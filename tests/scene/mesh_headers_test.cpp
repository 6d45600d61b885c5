// check_mesh_header: PLY element counts against the file's size at the
// boundary, PLY header lines, and which files go to check_off (the corpus,
// tests/corpus/bad/scenes, has the files that made assimp allocate tens of
// GB, loop or crash).
#include "scene/mesh_headers.h"

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

class MeshHeaders : public ::testing::Test {
 protected:
    // The message check_mesh_header throws for a file of `bytes`, or "(none)".
    std::string problem(const std::string& name, const std::string& bytes) {
        write_file(dir_ / name, bytes);
        return thrown_message<MeshFileError>([&] { check_mesh_header(dir_ / name); });
    }
    MeshHeaders() { fs::create_directories(dir_); }
    ~MeshHeaders() override { fs::remove_all(dir_); }

    const fs::path dir_ =
        fs::temp_directory_path() /
        ("wavepath-mesh-headers-" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) + "-" +
         std::to_string(::getpid()));
};

// check_off (tests/scene/off_check_test.cpp) reads every file assimp reads as OFF.
TEST_F(MeshHeaders, FilesAssimpReadsAsOffAreCheckedAsOff) {
    const std::string not_off =
        "OFF header: the first word must be OFF (after prefixes among ST, C, N, 4, n) or the vertex count";
    EXPECT_EQ(problem("a.off", "ply\nformat ascii 1.0\nend_header\n"), not_off);
    EXPECT_EQ(problem("a.OFF", "junk"), not_off);  // the extension in any case
    // A file whose extension assimp does not know, by its first bytes in any case.
    EXPECT_EQ(problem("mesh", "Off\n3 1 0\n"), not_off);
    EXPECT_EQ(problem("mesh.xyz", "OFF\n3 1\n"),
              "OFF header: expected the vertex, face and edge counts (whole numbers below 2^32)");
    EXPECT_EQ(problem("mesh.xyz", "OF F\n3 1\n"), "(none)");
    EXPECT_EQ(problem("mesh.obj", "OFF\n3 1\n"), "(none)");  // assimp reads it as OBJ
}

TEST_F(MeshHeaders, BinaryPlyCountsMustFitTheirSizes) {
    // Two vertices of three floats (24 bytes) and a face of at least its uchar count (1 byte).
    const std::string header =
        "ply\nformat binary_little_endian 1.0\nelement vertex 2\nproperty float x\nproperty float y\n"
        "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
    EXPECT_EQ(problem("a.ply", header + std::string(25, '\0')), "(none)");
    EXPECT_EQ(problem("a.ply", header + std::string(24, '\0')),
              "PLY header declares 1 \"face\" elements, more than the remaining 0 bytes of the file can hold");
    EXPECT_EQ(problem("a.ply", header + std::string(23, '\0')),
              "PLY header declares 2 \"vertex\" elements, more than the remaining 23 bytes of the file can hold");
}

TEST_F(MeshHeaders, AsciiPlyCountsMustFitTwoBytesAProperty) {
    const std::string header =
        "ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty float y\nend_header\n";
    EXPECT_EQ(problem("a.ply", header + "0 0\n1 1\n"), "(none)");
    EXPECT_EQ(problem("a.ply", header + "0 0\n1 1"),
              "PLY header declares 2 \"vertex\" elements, more than the remaining 7 bytes of the file can hold");
}

// A NUL byte in a face line made assimp allocate 15 GB (fuzz_mesh; the
// corpus's mesh_ply_nul_in_ascii_body.ply); binary bodies may hold any byte.
TEST_F(MeshHeaders, AsciiPlyBodyHoldsNoNulByte) {
    const std::string header =
        "ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty float y\nend_header\n";
    EXPECT_EQ(problem("a.ply", header + "0 0\n1 1\n"), "(none)");
    EXPECT_EQ(problem("a.ply", header + "0 0\n1 1" + std::string(1, '\0') + "\n"),
              "PLY byte " + std::to_string(header.size() + 7) + ": a NUL byte in an ASCII PLY's body");
    const std::string binary = "ply\nformat binary_little_endian 1.0\nelement vertex 1\nproperty float x\nend_header\n";
    EXPECT_EQ(problem("a.ply", binary + std::string(4, '\0')), "(none)");
}

TEST_F(MeshHeaders, PlyHeaderMustEndAndCountsMustBeCounts) {
    EXPECT_EQ(problem("a.ply", "ply\nformat ascii 1.0\nelement vertex 0\n"), "PLY header has no end_header line");
    EXPECT_EQ(problem("a.ply", "ply\nformat ascii 1.0\n" + std::string(1 << 16, 'x') + "\nend_header\n"),
              "PLY header has no end_header line in the first 65536 bytes");
    EXPECT_EQ(problem("a.ply", "ply\nformat ascii 1.0\nelement vertex -1\nend_header\n"),
              "PLY header line 3: expected \"element NAME COUNT\"");
}

TEST_F(MeshHeaders, PlyHeaderLinesAreWhatTheFormatDefines) {
    // assimp's reader looped forever on the first (found by fuzz_mesh).
    EXPECT_EQ(problem("a.ply", "ply\nply\xff\xff\nformat ascii 1.0\nend_header\n"),
              "PLY header line 2: expected \"format ascii|binary_little_endian|binary_big_endian VERSION\"");
    EXPECT_EQ(problem("a.ply", "ply extra\nformat ascii 1.0\nend_header\n"), "PLY header line 1: expected \"ply\"");
    EXPECT_EQ(problem("a.ply", "ply\xff\nformat ascii 1.0\nend_header\n"), "PLY header line 1: expected \"ply\"");
    // assimp reads the magic word in any case (fuzz_mesh: "plY" with 2e9 vertices took 2 GB).
    EXPECT_EQ(problem("a.ply", "plY\nformat ascii 1.0\nend_header\n"), "PLY header line 1: expected \"ply\"");
    EXPECT_EQ(problem("a.ply", "ply\nformat ascii 1.0\nproperty float x\nend_header\n"),
              "PLY header line 3: a property before any element");
    EXPECT_EQ(problem("a.ply", "ply\nformat ascii 1.0\nelement v 1\nproperty float3 x\nend_header\n"),
              "PLY header line 4: expected \"property TYPE NAME\" or \"property list COUNT_TYPE TYPE NAME\"");
    EXPECT_EQ(problem("a.ply", "ply\nformat ascii 1.0\nelement v 1\nproperty list uchar x\nend_header\n"),
              "PLY header line 4: expected \"property TYPE NAME\" or \"property list COUNT_TYPE TYPE NAME\"");
    EXPECT_EQ(problem("a.ply", "ply\nformat ascii 1.0\nvertex 3\nend_header\n"),
              "PLY header line 3: not a format, element, property, comment, obj_info or end_header line");
    EXPECT_EQ(problem("a.ply",
                      "ply\r\nformat ascii 1.0\r\ncomment made by hand\r\nelement v 1\r\n"
                      "property float x\r\nend_header\r\n0\r\n"),
              "(none)");
}

TEST_F(MeshHeaders, OtherFilesPassUnchecked) {
    EXPECT_EQ(problem("a.obj", kSquareObj), "(none)");
    EXPECT_EQ(problem("b.obj", "# ply\nOFF\n"), "(none)");
    EXPECT_EQ(problem("a.stl", square_stl_binary()), "(none)");
    EXPECT_EQ(problem("b.ply", square_ply_binary()), "(none)");
    EXPECT_EQ(problem("b.off", kSquareOff), "(none)");
}

}  // namespace
}  // namespace wp::test
