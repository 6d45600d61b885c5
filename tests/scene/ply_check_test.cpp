// check_ply: PLY files as the format defines them pass, and each way assimp
// 5.2.5 would loop, misread one or allocate for it is one message (the
// corpus, tests/corpus/bad/scenes, has the files fuzz_mesh found, through
// the binary).
#include "scene/ply_check.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <string>

#include "scene/mesh_file.h"
#include "support/mesh_files.h"
#include "support/thrown_message.h"

namespace wp::test {
namespace {

// The message check_ply throws, or "(none)".
std::string ply_problem(const std::string& file) {
    return thrown_message<MeshFileError>([&] { check_ply(file); });
}

// Two vertices and a face list (lines 1 to 7): the body follows.
const std::string kAsciiHeader =
    "ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty int y\n"
    "element face 1\nproperty list uchar int vertex_indices\nend_header\n";

// Two vertices of three floats (24 bytes) and a face list with uint counts.
std::string binary_header(const std::string& format, const std::string& count_type = "uint") {
    return "ply\nformat " + format +
           " 1.0\nelement vertex 2\nproperty float x\nproperty float y\nproperty float z\n"
           "element face 1\nproperty list " +
           count_type + " int vertex_indices\nend_header\n";
}

TEST(PlyCheck, FilesAsTheFormatDefinesThemPass) {
    EXPECT_EQ(ply_problem(kSquarePlyAscii), "(none)");
    EXPECT_EQ(ply_problem(square_ply_binary()), "(none)");
    EXPECT_EQ(ply_problem(kAsciiHeader + "0.5 -1\n+1e-3 +2\n3 0 1 -7\n"), "(none)");
    // Blanks around words, CRLF, blank lines after the last element, no final line end.
    EXPECT_EQ(ply_problem(kAsciiHeader + " nan\t0 \r\n-inf 1\r\n0\r\n\r\n \n"), "(none)");
    EXPECT_EQ(ply_problem(kAsciiHeader + "0 0\n1 1\n2 0 1"), "(none)");
    EXPECT_EQ(ply_problem("ply\r\nformat ascii 1.0\r\ncomment made by hand\r\nobj_info x\r\nelement vertex 1\r\n"
                          "property float x\r\nend_header\r\n0\r\n"),
              "(none)");
    std::string little = binary_header("binary_little_endian") + std::string(24, '\0');
    append_bytes(little, std::uint32_t{1});
    append_bytes(little, std::int32_t{0});
    EXPECT_EQ(ply_problem(little), "(none)");
    EXPECT_EQ(ply_problem(little + "bytes after the last element"), "(none)");  // assimp ignores them
    // The same count, 1, big-endian.
    EXPECT_EQ(ply_problem(binary_header("binary_big_endian") + std::string(24, '\0') + std::string("\0\0\0\1", 4) +
                          std::string(4, '\0')),
              "(none)");
}

TEST(PlyCheck, HeaderMustEnd) {
    EXPECT_EQ(ply_problem("ply\nformat ascii 1.0\nelement vertex 0\n"), "PLY header has no end_header line");
    EXPECT_EQ(ply_problem("ply\nformat ascii 1.0\n" + std::string(1 << 16, 'x') + "\nend_header\n"),
              "PLY header has no end_header line in the first 65536 bytes");
}

TEST(PlyCheck, HeaderLinesAreWhatTheFormatDefines) {
    // assimp's reader looped forever on the first (found by fuzz_mesh).
    EXPECT_EQ(ply_problem("ply\nply\xff\xff\nformat ascii 1.0\nend_header\n"),
              "PLY header line 2: expected \"format ascii|binary_little_endian|binary_big_endian VERSION\"");
    EXPECT_EQ(ply_problem("ply extra\nformat ascii 1.0\nend_header\n"), "PLY header line 1: expected \"ply\"");
    EXPECT_EQ(ply_problem("ply\xff\nformat ascii 1.0\nend_header\n"), "PLY header line 1: expected \"ply\"");
    EXPECT_EQ(ply_problem("plY\nformat ascii 1.0\nend_header\n"), "PLY header line 1: expected \"ply\"");
    EXPECT_EQ(ply_problem("ply\nformat ascii 1.0\nelement vertex -1\nend_header\n"),
              "PLY header line 3: expected \"element NAME COUNT\"");
    EXPECT_EQ(ply_problem("ply\nformat ascii 1.0\nproperty float x\nend_header\n"),
              "PLY header line 3: a property before any element");
    const std::string not_a_property =
        "PLY header line 4: expected \"property TYPE NAME\" or \"property list COUNT_TYPE TYPE NAME\"";
    EXPECT_EQ(ply_problem("ply\nformat ascii 1.0\nelement vertex 1\nproperty float3 x\nend_header\n"), not_a_property);
    EXPECT_EQ(ply_problem("ply\nformat ascii 1.0\nelement vertex 1\nproperty list uchar x\nend_header\n"),
              not_a_property);
    EXPECT_EQ(ply_problem("ply\nformat ascii 1.0\nelement vertex 1\nproperty list uchar8 int x\nend_header\n"),
              not_a_property);
    // assimp takes the count of an element of another name from the name, as 0
    // (fuzz_mesh: "vert\x96...ex 3" made the face's count come from the vertices' bytes).
    EXPECT_EQ(
        ply_problem("ply\nformat ascii 1.0\nelement camera 1\nproperty float x\nend_header\n0\n"),
        "PLY header line 3: element \"camera\": assimp reads vertex, face, tristrips, edge and material elements");
    // assimp ends an element's properties at any other line than a comment, and drops the ones after it.
    EXPECT_EQ(ply_problem("ply\nformat ascii 1.0\nelement vertex 1\nobj_info x\nproperty float x\nend_header\n0\n"),
              "PLY header line 5: a property after an obj_info line (assimp drops it)");
    EXPECT_EQ(ply_problem("ply\nformat ascii 1.0\nobj_info x\nelement vertex 1\ncomment c\nproperty float x\n"
                          "obj_info y\nend_header\n0\n"),
              "(none)");
    // assimp ends a line at NUL, \r and \f and splits words at blanks only
    // (fuzz_mesh: "element \0...\0vertex 3" made it allocate 15 GB).
    EXPECT_EQ(ply_problem("ply\nformat ascii 1.0\nelement " + std::string(3, '\0') + "vertex 3\nend_header\n"),
              "PLY header line 3: a control byte \"\\x00\" in the line");
    EXPECT_EQ(ply_problem("ply\nformat ascii 1.0\nelement\fvertex 3\nend_header\n"),
              "PLY header line 3: a control byte \"\\x0c\" in the line");
    EXPECT_EQ(ply_problem("ply\rformat ascii 1.0\nend_header\n"),
              "PLY header line 1: a control byte \"\\x0d\" in the line");
    EXPECT_EQ(ply_problem("ply\nformat ascii 1.0\nvertex 3\nend_header\n"),
              "PLY header line 3: not a format, element, property, comment, obj_info or end_header line");
}

// assimp sizes a list by its count before reading it, as 32 bits whatever
// the count's type: fuzz_mesh's face line "8888800000000000012425" (the
// corpus's mesh_ply_ascii_list_count_beyond_its_type) made it allocate
// gigabytes.
TEST(PlyCheck, AsciiListCountsFitTheirTypeAndTheirLine) {
    const std::string face = "PLY line 11: \"face\" element 1 of 1, property \"vertex_indices\": ";
    const std::string vertices = "0 0\n1 1\n";
    EXPECT_EQ(ply_problem(kAsciiHeader + vertices + "8888800000000000012425\n"),
              face + "\"8888800000000000012425\" is not a list count of type uchar");
    EXPECT_EQ(ply_problem(kAsciiHeader + vertices + "256 0\n"), face + "\"256\" is not a list count of type uchar");
    EXPECT_EQ(ply_problem(kAsciiHeader + vertices + "3 0 1\n"), face + "a list of 3 but 2 words follow its count");
    const std::string header = "ply\nformat ascii 1.0\nelement face 1\nproperty list char int i\nend_header\n";
    const std::string list = "PLY line 6: \"face\" element 1 of 1, property \"i\": ";
    EXPECT_EQ(ply_problem(header + "-1\n"), list + "\"-1\" is not a list count of type char");
    const std::string real_header = "ply\nformat ascii 1.0\nelement face 1\nproperty list float int i\nend_header\n";
    EXPECT_EQ(ply_problem(real_header + "1.5 0\n"), list + "\"1.5\" is not a list count of type float");
    EXPECT_EQ(ply_problem(real_header + "2.0 0 1\n"), "(none)");
}

TEST(PlyCheck, AsciiValuesAreNumbersOfTheirType) {
    const std::string first = "PLY line 9: \"vertex\" element 1 of 2, property ";
    const std::string face = "0 0 1\n";
    EXPECT_EQ(ply_problem(kAsciiHeader + "zero 0\n1 1\n" + face),
              first + "\"x\": \"zero\" is not a value of type float");
    EXPECT_EQ(ply_problem(kAsciiHeader + "0 1.5\n1 1\n" + face), first + "\"y\": \"1.5\" is not a value of type int");
    EXPECT_EQ(ply_problem(kAsciiHeader + "0 2147483648\n1 1\n" + face),
              first + "\"y\": \"2147483648\" is not a value of type int");
    EXPECT_EQ(ply_problem(kAsciiHeader + "0 0\n1 1\n2 0 x\n"),
              "PLY line 11: \"face\" element 1 of 1, property \"vertex_indices\": \"x\" is not a value of type int");
    EXPECT_EQ(ply_problem(kAsciiHeader + "0 \xff\xfe" + std::string(40, 'x') + "\n1 1\n" + face),
              first + "\"y\": \"\\xff\\xfe" + std::string(30, 'x') + "...\" is not a value of type int");
}

// A NUL byte in a face line made assimp allocate 15 GB (fuzz_mesh; the
// corpus's mesh_ply_nul_in_ascii_body): it ends a line at NUL, \r and \f,
// which would shift every element after it.
TEST(PlyCheck, AsciiElementsAreOneALine) {
    EXPECT_EQ(ply_problem(kAsciiHeader + "0 0\n1 1" + std::string(1, '\0') + "2\n2 0 1\n"),
              "PLY line 10: a control byte \"\\x00\" in the line");
    EXPECT_EQ(ply_problem(kAsciiHeader + "0 0\r1 1\n2 0 1\n"), "PLY line 9: a control byte \"\\x0d\" in the line");
    EXPECT_EQ(ply_problem(kAsciiHeader + "0 0\n1 1\f\n2 0 1\n"), "PLY line 10: a control byte \"\\x0c\" in the line");
    EXPECT_EQ(ply_problem(kAsciiHeader + "0 0\n\n1 1\n2 0 1\n"),
              "PLY line 10: \"vertex\" element 2 of 2, property \"x\": missing");
    EXPECT_EQ(ply_problem(kAsciiHeader + "0\n1 1\n2 0 1\n"),
              "PLY line 9: \"vertex\" element 1 of 2, property \"y\": missing");
    EXPECT_EQ(ply_problem(kAsciiHeader + "0 0 0\n1 1\n2 0 1\n"),
              "PLY line 9: \"vertex\" element 1 of 2: 1 words after its last property");
    EXPECT_EQ(ply_problem(kAsciiHeader + "0 0\n1 1\n"), "PLY file ends after line 10, before \"face\" element 1 of 1");
    EXPECT_EQ(ply_problem(kAsciiHeader + "0 0\n1 1\n2 0 1\n\n3 0 1 2\n"), "PLY line 13: text after the last element");
}

TEST(PlyCheck, BinaryListCountsFitTheirTypeAndTheFile) {
    const std::string vertices(24, '\0');
    // The start of the message for the face list's count, after `header` and the vertices.
    const auto face = [&](const std::string& header) {
        return "PLY byte " + std::to_string(header.size() + vertices.size()) +
               ": \"face\" element 1 of 1, property \"vertex_indices\": ";
    };
    const std::string little = binary_header("binary_little_endian");
    std::string all_ones = little + vertices;
    append_bytes(all_ones, std::uint32_t{0xffffffff});
    EXPECT_EQ(ply_problem(all_ones + std::string(8, '\0')),
              face(little) + "a list of 4294967295 int but 8 bytes follow its count");
    const std::string big = binary_header("binary_big_endian");
    const std::string three = big + vertices + std::string("\0\0\0\3", 4);
    EXPECT_EQ(ply_problem(three + std::string(8, '\0')), face(big) + "a list of 3 int but 8 bytes follow its count");
    EXPECT_EQ(ply_problem(three + std::string(12, '\0')), "(none)");
    const std::string chars = binary_header("binary_little_endian", "char");
    std::string negative = chars + vertices;
    append_bytes(negative, std::int8_t{-1});
    EXPECT_EQ(ply_problem(negative), face(chars) + "list count -1 is not a whole number below 2^32");
    const std::string doubles = binary_header("binary_little_endian", "double");
    std::string fraction = doubles + vertices;
    append_bytes(fraction, 2.5);
    EXPECT_EQ(ply_problem(fraction + std::string(12, '\0')),
              face(doubles) + "list count 2.5 is not a whole number below 2^32");
}

// assimp reserves the elements the header declares before reading them
// (fuzz_mesh: 2e9 vertices in a file of a few hundred bytes).
TEST(PlyCheck, BinaryElementsFitTheFile) {
    const std::string header = binary_header("binary_little_endian");
    EXPECT_EQ(ply_problem(header + std::string(23, '\0')),
              "PLY byte " + std::to_string(header.size() + 12) + ": the file ends within \"vertex\" element 2 of 2");
    EXPECT_EQ(ply_problem(header + std::string(26, '\0')),
              "PLY byte " + std::to_string(header.size() + 24) + ": the file ends within \"face\" element 1 of 1");
    const std::string claims_2e9 =
        "ply\nformat binary_little_endian 1.0\nelement vertex 2000000000\nproperty float x\nend_header\n";
    EXPECT_EQ(ply_problem(claims_2e9), "PLY byte " + std::to_string(claims_2e9.size()) +
                                           ": the file ends within \"vertex\" element 1 of 2000000000");
}

}  // namespace
}  // namespace wp::test
