// check_off: OFF files laid out as assimp 5.2.5 reads them pass, and each
// way assimp would misread one, or crash on it, is one message (the corpus,
// tests/corpus/bad/scenes, has the file fuzz_mesh found, through the binary).
#include "scene/off_check.h"

#include <gtest/gtest.h>

#include <string>

#include "scene/mesh_file.h"
#include "support/mesh_files.h"
#include "support/thrown_message.h"

namespace wp::test {
namespace {

// The message check_off throws, or "(none)".
std::string problem(const std::string& text) {
    return thrown_message<MeshFileError>([&] { check_off(text); });
}

// A triangle's header and vertices (lines 1 to 5): the face lines follow.
constexpr const char* kTriangleVertices = "OFF\n3 1 0\n0 0 0\n1 0 0\n1 1 0\n";

TEST(OffCheck, FilesAsTheFormatDefinesThemPass) {
    EXPECT_EQ(problem(kSquareOff), "(none)");
    EXPECT_EQ(problem(std::string(kTriangleVertices) + "3 0 1 2 0.5 0.5 0.5\n# the end\n\n"), "(none)");
    EXPECT_EQ(problem("# made by hand\r\nOFF\r\n# counts\r\n3 1 0\r\n-1e-3 +2 .5\r\n1\t0 0\r\n\r\n1 1 0\r\n3 0 1 2"),
              "(none)");
    EXPECT_EQ(problem("3 1 0\n0 0 0\n1 0 0\n1 1 0\n3 0 1 2\n"), "(none)");     // no keyword
    EXPECT_EQ(problem("OFF 3 1 0 0 0 0\n1 0 0\n1 1 0\n3 0 1 2\n"), "(none)");  // the body starts at a word
    EXPECT_EQ(problem("STCN4nOFF 2\n3 1 0\n0 0 1 0 0 1 1 1 1 0 0\n1 0 1\n1 1 1\n3 0 1 2\n"), "(none)");
    EXPECT_EQ(problem("OFF\n3 1 0\n0 0 inf\n1 0 1e999\n1 1 nan\n1 0\n"), "(none)");  // the mesh checks report these
}

TEST(OffCheck, FaceLinesThatAssimpDropsAreRefused) {
    // assimp dropped such lines and lowered the face count, here below zero:
    // SIGSEGV (found by fuzz_mesh).
    EXPECT_EQ(problem(std::string(kTriangleVertices) + "OFF\n\xa0 1 "),
              "OFF line 6: expected a face's vertex count (face 1 of 1)");
    EXPECT_EQ(problem(std::string(kTriangleVertices) + "0\n"),
              "OFF line 6: a face of 0 vertices (assimp reads faces of 1 to 9)");
    EXPECT_EQ(problem(std::string(kTriangleVertices) + "10 0 1 2 0 1 2 0 1 2 0\n"),
              "OFF line 6: a face of 10 vertices (assimp reads faces of 1 to 9)");
    EXPECT_EQ(problem(std::string(kTriangleVertices) + "9 0 1 2 0 1 2 0 1 2\n"), "(none)");
    EXPECT_EQ(problem(std::string(kTriangleVertices) + "# a face\n3 0 1 2\n"),
              "OFF line 6: expected a face's vertex count (face 1 of 1)");
}

TEST(OffCheck, FaceIndicesMustBeIndicesOfVertices) {
    // assimp clamped an index out of range and read a word that is not a number as 0.
    EXPECT_EQ(problem(std::string(kTriangleVertices) + "3 0 1 3\n"),
              "OFF line 6: vertex index 3 out of range (3 vertices)");
    EXPECT_EQ(problem(std::string(kTriangleVertices) + "3 0 1 4294967298\n"),
              "OFF line 6: expected 3 vertex indices after the face's count");
    EXPECT_EQ(problem(std::string(kTriangleVertices) + "3 0 1 2x\n"),
              "OFF line 6: expected 3 vertex indices after the face's count");
    EXPECT_EQ(problem(std::string(kTriangleVertices) + "3 0 -1 2\n"),
              "OFF line 6: expected 3 vertex indices after the face's count");
    EXPECT_EQ(problem(std::string(kTriangleVertices) + "3 0 1\n"),
              "OFF line 6: expected 3 vertex indices after the face's count");
}

TEST(OffCheck, VertexLinesMustStartWithTheirCoordinates) {
    EXPECT_EQ(problem("OFF\n3 1 0\n0 0 0\n1 0\n1 1 0\n3 0 1 2\n"), "OFF line 4: expected 3 numbers (vertex 2 of 3)");
    EXPECT_EQ(problem("OFF\n3 1 0\n0 0 0\n1,0,0\n1 1 0\n3 0 1 2\n"), "OFF line 4: expected 3 numbers (vertex 2 of 3)");
    EXPECT_EQ(problem("OFF\n3 1 0\n0 0 0\n   \n1 0 0\n1 1 0\n3 0 1 2\n"),
              "OFF line 4: expected 3 numbers (vertex 2 of 3)");  // a line of blanks is a line to assimp
    EXPECT_EQ(problem("4OFF\n3 1 0\n0 0 0 1\n1 0 0 1\n1 1 0\n3 0 1 2\n"),
              "OFF line 5: expected 4 numbers (vertex 3 of 3)");
    EXPECT_EQ(problem("nOFF 1\n3 1 0\n0\n1\n2\n3 0 1 2\n"), "(none)");
}

TEST(OffCheck, CountsMustMatchTheLines) {
    EXPECT_EQ(problem("OFF\n1000000000 1 0\n0 0 0\n"),
              "OFF header declares 1000000000 vertices and 1 faces, but only 1 lines follow it");
    EXPECT_EQ(problem(std::string(kTriangleVertices)),
              "OFF header declares 3 vertices and 1 faces, but only 3 lines follow it");
    EXPECT_EQ(problem(std::string(kTriangleVertices) + "3 0 1 2\n3 0 1 2\n"),
              "OFF line 7: more lines than the header declares (3 vertices, 1 faces)");
}

TEST(OffCheck, HeaderWordsMustBeWhatTheFormatDefines) {
    const std::string counts = "OFF header: expected the vertex, face and edge counts (whole numbers below 2^32)";
    // assimp read "1\xa5X" as 1 (fuzz_mesh), 2^32 as 0, and allocated 1e9 vertices.
    EXPECT_EQ(problem("OFF\n1000000000 1\xa5X\n"), counts);
    EXPECT_EQ(problem("OFF\n4294967296 1 0\n"), counts);
    // Without the edge count assimp takes the first coordinate for it.
    EXPECT_EQ(problem("OFF\n3 1\n0 0 0\n1 0 0\n1 1 0\n3 0 1 2\n"), "OFF line 3: expected 3 numbers (vertex 1 of 3)");
    EXPECT_EQ(problem("OFF\n3 1"), counts);
    const std::string keyword =
        "OFF header: the first word must be OFF (after prefixes among ST, C, N, 4, n) or the vertex count";
    EXPECT_EQ(problem("off\n3 1 0\n"), keyword);
    EXPECT_EQ(problem("NCOFF\n3 1 0\n"), keyword);
    EXPECT_EQ(problem("OFF3 1 0\n"), keyword);
    EXPECT_EQ(problem("\xef\xbb\xbfOFF\n3 1 0\n"), keyword);  // a byte order mark, which assimp converts
    // assimp read "42 1 0" without a keyword as 2 vertices, taking the 4 for 4OFF's.
    EXPECT_EQ(problem("42 1 0\n"), "OFF header: a vertex count that begins with 4 needs the OFF keyword before it");
    EXPECT_EQ(problem("OFF 4 1 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n"), "(none)");
    EXPECT_EQ(problem("nOFF 4\n"), "OFF header: expected the dimension after nOFF, 1, 2 or 3");
    EXPECT_EQ(problem("nOFF 0\n"), "OFF header: expected the dimension after nOFF, 1, 2 or 3");
}

TEST(OffCheck, LinesMustFitAssimpsBufferAndHoldNoNul) {
    // assimp copies a line into 4096 bytes and then writes its terminator.
    const std::string face = "3 0 1 2";
    EXPECT_EQ(problem(kTriangleVertices + face + std::string(4095 - face.size(), ' ') + "\n"), "(none)");
    EXPECT_EQ(problem(kTriangleVertices + face + std::string(4096 - face.size(), ' ') + "\n"),
              "OFF line 6: longer than 4095 bytes, assimp's limit");
    EXPECT_EQ(problem(kTriangleVertices + std::string("3 0 1 2\n\0\n", 10)),
              "OFF line 7: a NUL byte (assimp's OFF reader ends the text there)");
}

}  // namespace
}  // namespace wp::test
