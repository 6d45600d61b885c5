// The contained mesh import (import/import_process.h): wavepath-import's
// answer is assimp's scene in process to the bit; each way the helper can
// fail (a crash, its memory, CPU and wall-time limits, a malformed answer,
// an exit status) is one ImportProcessError; a malformed answer is refused
// whichever part of it is wrong; a reader of another format is refused.
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/stat.h>

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "import/answer.h"
#include "import/helper/assimp_import.h"
#include "import/import_process.h"
#include "scene/mesh_file.h"
#include "support/mesh_files.h"
#include "support/temp_directory.h"
#include "support/thrown_message.h"

namespace wp::test {
namespace {

namespace fs = std::filesystem;

template <class T>
bool same_bytes(const std::vector<T>& a, const std::vector<T>& b) {
    // An empty vector's data() may be null, which memcmp must not be given.
    return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

void expect_same_scene(const ImportedScene& a, const ImportedScene& b) {
    ASSERT_EQ(a.meshes.size(), b.meshes.size());
    for (std::size_t m = 0; m < a.meshes.size(); ++m) {
        SCOPED_TRACE("mesh " + std::to_string(m));
        EXPECT_TRUE(same_bytes(a.meshes[m].positions, b.meshes[m].positions));
        EXPECT_EQ(a.meshes[m].has_normals, b.meshes[m].has_normals);
        EXPECT_TRUE(same_bytes(a.meshes[m].normals, b.meshes[m].normals));
        EXPECT_EQ(a.meshes[m].has_uvs, b.meshes[m].has_uvs);
        EXPECT_TRUE(same_bytes(a.meshes[m].uvs, b.meshes[m].uvs));
        EXPECT_TRUE(same_bytes(a.meshes[m].triangles, b.meshes[m].triangles));
        EXPECT_EQ(a.meshes[m].material, b.meshes[m].material);
    }
    ASSERT_EQ(a.nodes.size(), b.nodes.size());
    for (std::size_t n = 0; n < a.nodes.size(); ++n) {
        SCOPED_TRACE("node " + std::to_string(n));
        EXPECT_EQ(a.nodes[n].parent, b.nodes[n].parent);
        EXPECT_EQ(a.nodes[n].name, b.nodes[n].name);
        EXPECT_EQ(std::memcmp(a.nodes[n].transform.data(), b.nodes[n].transform.data(), 64), 0);
        EXPECT_EQ(a.nodes[n].meshes, b.nodes[n].meshes);
    }
    ASSERT_EQ(a.materials.size(), b.materials.size());
    for (std::size_t m = 0; m < a.materials.size(); ++m) {
        const ImportedMaterial &x = a.materials[m], &y = b.materials[m];
        EXPECT_EQ(x.name, y.name);
        EXPECT_EQ(x.base_color, y.base_color);
        EXPECT_EQ(x.metallic, y.metallic);
        EXPECT_EQ(x.roughness, y.roughness);
        EXPECT_EQ(x.emissive, y.emissive);
        EXPECT_EQ(x.emissive_strength, y.emissive_strength);
        EXPECT_EQ(x.transmission, y.transmission);
        EXPECT_EQ(x.ior, y.ior);
        EXPECT_EQ(x.base_color_texture, y.base_color_texture);
        EXPECT_EQ(x.normal_texture, y.normal_texture);
        EXPECT_EQ(x.alpha_mode, y.alpha_mode);
        EXPECT_EQ(x.alpha_cutoff, y.alpha_cutoff);
        EXPECT_EQ(x.unread_textures, y.unread_textures);
        EXPECT_EQ(x.base_color_transform, y.base_color_transform);
        EXPECT_EQ(x.normal_transform, y.normal_transform);
    }
    ASSERT_EQ(a.cameras.size(), b.cameras.size());
    for (std::size_t c = 0; c < a.cameras.size(); ++c) {
        const ImportedCamera &x = a.cameras[c], &y = b.cameras[c];
        EXPECT_EQ(x.name, y.name);
        EXPECT_EQ(x.node, y.node);
        EXPECT_EQ(x.position, y.position);
        EXPECT_EQ(x.look_at, y.look_at);
        EXPECT_EQ(x.up, y.up);
        EXPECT_EQ(x.yfov, y.yfov);
        EXPECT_EQ(x.aspect, y.aspect);
    }
    ASSERT_EQ(a.lights.size(), b.lights.size());
    for (std::size_t l = 0; l < a.lights.size(); ++l) {
        const ImportedLight &x = a.lights[l], &y = b.lights[l];
        EXPECT_EQ(x.name, y.name);
        EXPECT_EQ(x.node, y.node);
        EXPECT_EQ(x.type, y.type);
        EXPECT_EQ(x.color, y.color);
        EXPECT_EQ(x.position, y.position);
        EXPECT_EQ(x.direction, y.direction);
        EXPECT_EQ(x.inner_cone, y.inner_cone);
        EXPECT_EQ(x.outer_cone, y.outer_cone);
    }
    ASSERT_EQ(a.images.size(), b.images.size());
    for (std::size_t i = 0; i < a.images.size(); ++i) {
        EXPECT_EQ(a.images[i].format, b.images[i].format);
        EXPECT_EQ(a.images[i].bytes, b.images[i].bytes);
    }
}

void expect_same_mesh(const Mesh& a, const Mesh& b) {
    EXPECT_TRUE(same_bytes(a.positions, b.positions));
    EXPECT_TRUE(same_bytes(a.normals, b.normals));
    EXPECT_TRUE(same_bytes(a.triangles, b.triangles));
    EXPECT_EQ(a.degenerate_dropped, b.degenerate_dropped);
}

const fs::path kBunny = fs::path(WAVEPATH_SOURCE_DIR) / "scenes/meshes/bunny.obj";

// ---- contained and in process alike ----

struct SameFileCase {
    const char* name;
    const char* file;
    std::string (*contents)();
};

const SameFileCase kSameFileCases[] = {
    {"Obj", "square.obj", [] { return std::string(kSquareObj); }},
    {"PlyAsciiWithNormals", "square.ply", [] { return std::string(kSquarePlyAscii); }},
    {"PlyBinary", "square.ply", square_ply_binary},
    {"Off", "square.off", [] { return std::string(kSquareOff); }},
    {"StlAscii", "square.stl", [] { return std::string(kSquareStlAscii); }},
    {"StlBinary", "square.stl", square_stl_binary},
    {"GltfNodeGraph", "squares.gltf", two_squares_gltf},
};

class ContainedImport : public ::testing::TestWithParam<SameFileCase> {};

TEST_P(ContainedImport, IsTheInProcessImportToTheBit) {
    const TempDirectory dir("files");
    const fs::path file = dir.path() / GetParam().file;
    write_file(file, GetParam().contents());
    const ImportedScene contained = import_in_child(file, {});
    const ImportedScene in_process = import_with_assimp(file);
    ASSERT_FALSE(in_process.meshes.empty());
    expect_same_scene(contained, in_process);
    expect_same_mesh(mesh_from_import(contained, {}), mesh_from_import(in_process, {}));
}

INSTANTIATE_TEST_SUITE_P(Formats, ContainedImport, ::testing::ValuesIn(kSameFileCases),
                         [](const auto& info) { return std::string(info.param.name); });

TEST(ContainedImportOfTheBunny, IsTheInProcessImportToTheBit) {
    ASSERT_TRUE(fs::exists(kBunny)) << kBunny << " is missing: run scripts/setup.sh";
    const ImportedScene contained = import_in_child(kBunny, {});
    const ImportedScene in_process = import_with_assimp(kBunny);
    expect_same_scene(contained, in_process);
    MeshImporter importer({});
    const Mesh mesh = read_mesh_file(kBunny, {}, importer);
    EXPECT_EQ(mesh.triangles.size(), 69666u);
    expect_same_mesh(mesh, mesh_from_import(in_process, {}));
}

TEST(ContainedImport, PassesTheHelpersMessageOn) {
    EXPECT_EQ(thrown_message<MeshFileError>([] { import_in_child("/nonexistent/mesh.obj", {}); }),
              "cannot open: No such file or directory");
}

// ---- one helper for many files ----

TEST(MeshImporter, ImportsFileAfterFileEachAsAloneToTheBit) {
    const TempDirectory dir("files");
    const fs::path square_obj = dir.path() / "square.obj", square_ply = dir.path() / "square.ply";
    write_file(square_obj, kSquareObj);
    write_file(square_ply, kSquarePlyAscii);
    MeshImporter importer({});
    for (const fs::path& file : {square_obj, kBunny, square_ply, square_obj}) {
        SCOPED_TRACE(file.string());
        expect_same_scene(importer.import(file), import_with_assimp(file));
    }
}

TEST(MeshImporter, AFailureEndsOnlyItsOwnFile) {
    // Under 64 MiB the bunny's importer runs out of memory (it needs about 85,
    // bench/results/mesh_import.md) and the helper goes on; a hang ends the
    // helper, and the next file starts another.
    const TempDirectory dir("files");
    const fs::path square = dir.path() / "square.obj", fifo = dir.path() / "hang.obj";
    write_file(square, kSquareObj);
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    MeshImporter importer({64, 60, 0.5});
    const ImportedScene expected = import_with_assimp(square);
    expect_same_scene(importer.import(square), expected);
    EXPECT_EQ(thrown_message<ImportProcessError>([&] { importer.import(kBunny); }),
              "wavepath-import ran out of memory importing it (limit 64 MiB, --mesh-import-memory)");
    expect_same_scene(importer.import(square), expected);
    EXPECT_EQ(thrown_message<ImportProcessError>([&] { importer.import(fifo); }),
              "wavepath-import did not finish within 0.5 s and was stopped (--mesh-import-time)");
    expect_same_scene(importer.import(square), expected);
    EXPECT_EQ(thrown_message<MeshFileError>([&] { importer.import("/nonexistent/mesh.obj"); }),
              "cannot open: No such file or directory");
    expect_same_scene(importer.import(square), expected);
}

TEST(MeshImporter, ImportsExpectedFilesAheadEachAsAlone) {
    const TempDirectory dir("files");
    const fs::path obj = dir.path() / "square.obj", ply = dir.path() / "square.ply", fifo = dir.path() / "hang.obj";
    write_file(obj, kSquareObj);
    write_file(ply, kSquarePlyAscii);
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    MeshImporter importer({64, 60, 0.5});
    importer.expect({obj, kBunny, fifo, ply, obj});
    expect_same_scene(importer.import(obj), import_with_assimp(obj));
    // Each failure is its own file's; the hang's clock ran from the file's start.
    EXPECT_EQ(thrown_message<ImportProcessError>([&] { importer.import(kBunny); }),
              "wavepath-import ran out of memory importing it (limit 64 MiB, --mesh-import-memory)");
    EXPECT_EQ(thrown_message<ImportProcessError>([&] { importer.import(fifo); }),
              "wavepath-import did not finish within 0.5 s and was stopped (--mesh-import-time)");
    expect_same_scene(importer.import(ply), import_with_assimp(ply));
    // Asked for another file than expected: that file, then the expected one alone.
    expect_same_scene(importer.import(kBunny.parent_path() / "cornell_box.obj"),
                      import_with_assimp(kBunny.parent_path() / "cornell_box.obj"));
    expect_same_scene(importer.import(obj), import_with_assimp(obj));
}

// ---- only the documented formats ----

TEST(ContainedImport, RefusesTheReaderOfAnotherFormatNamingIt) {
    const TempDirectory dir("files");
    // OBJ text, which the OBJ reader would read; the extension is the Neutral File Format's.
    const fs::path file = dir.path() / "square.nff";
    write_file(file, kSquareObj);
    const std::string message =
        "format not supported: assimp chose its reader \"Neutral File Format Importer\"; wavepath reads OBJ, PLY, "
        "OFF, STL and glTF 2.0";
    EXPECT_EQ(thrown_message<MeshFileError>([&] { import_in_child(file, {}); }), message);
    EXPECT_EQ(thrown_message<MeshFileError>([&] { import_with_assimp(file); }), message);
}

// ---- the helper's failures ----

// A stand-in for the helper: a /bin/sh script in `dir` that runs `body`.
fs::path fake_helper(const TempDirectory& dir, const std::string& body) {
    const fs::path helper = dir.path() / kImportHelperName;
    write_text(helper, "#!/bin/sh\n" + body + "\n");
    fs::permissions(helper, fs::perms::owner_all);
    return helper;
}

// What a stand-in helper does, and the error that makes (after "wavepath-import "); limits {64 MiB, 1 s, 2 s}.
struct FailureCase {
    const char* name;
    const char* helper_body;
    ImportProcessFailure failure;
    const char* message;
};

using enum ImportProcessFailure;
const FailureCase kFailureCases[] = {
    {"Crash", "kill -SEGV $$", Crashed, "crashed importing it (signal 11: Segmentation fault)"},
    {"Abort", "kill -ABRT $$", Crashed, "crashed importing it (signal 6: Aborted)"},
    {"OutOfMemoryStatus", "exit 10", OutOfMemory,
     "ran out of memory importing it (limit 64 MiB, --mesh-import-memory)"},
    {"OtherStatus", "exit 7", ExitStatus, "exited with status 7"},
    {"Hang", "exec sleep 60", WallTime, "did not finish within 2 s and was stopped (--mesh-import-time)"},
    {"HangAfterClosingItsAnswer", "exec 3>&-; exec sleep 60", WallTime,
     "did not finish within 2 s and was stopped (--mesh-import-time)"},
    {"Garbage", "printf garbage >&3", Malformed, "sent a malformed answer: it does not begin with \"WPIMPORT\""},
    {"NoAnswer", "exit 0", Malformed, "sent a malformed answer: it does not begin with \"WPIMPORT\""},
    {"AnswerBeyondItsMemory", "head -c 70000000 /dev/zero >&3", Malformed,
     "sent a malformed answer: more than 67108864 bytes"},
};

class HelperFailure : public ::testing::TestWithParam<FailureCase> {};

// The error `import_in_child` throws with a stand-in helper running `body`, checked to be of `failure`.
std::string helper_failure(const std::string& body, const MeshImportLimits& limits, ImportProcessFailure failure) {
    const TempDirectory dir("helper");
    try {
        import_in_child(kBunny, limits, fake_helper(dir, body));
    } catch (const ImportProcessError& error) {
        EXPECT_EQ(error.failure(), failure);
        return error.what();
    }
    return "(none)";
}

TEST_P(HelperFailure, IsOneImportProcessError) {
    const FailureCase& c = GetParam();
    const auto start = std::chrono::steady_clock::now();
    EXPECT_EQ(helper_failure(c.helper_body, {64, 1, 2.0}, c.failure), std::string("wavepath-import ") + c.message);
    // Stopped at its limit, not left to finish (sleep 60).
    EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(30));
}

INSTANTIATE_TEST_SUITE_P(Helpers, HelperFailure, ::testing::ValuesIn(kFailureCases),
                         [](const auto& info) { return std::string(info.param.name); });

TEST(HelperFailure, SpinningPastItsCpuLimit) {
    // The wall-time limit far above the CPU limit: a loaded machine must still give it its second.
    EXPECT_EQ(helper_failure("ulimit -S -t 1; while :; do :; done", {64, 1, 60.0}, CpuTime),
              "wavepath-import used its 1 s of CPU time importing it (--mesh-import-cpu)");
}

TEST(HelperFailure, AnAnswerThenACrashIsACrash) {
    const TempDirectory dir("helper");
    write_file(dir.path() / "answer", encode_answer(import_with_assimp(kBunny)));
    const fs::path helper = fake_helper(dir, "cat \"$(dirname \"$0\")/answer\" >&3; kill -SEGV $$");
    EXPECT_EQ(thrown_message<ImportProcessError>([&] { import_in_child(kBunny, {}, helper); }),
              "wavepath-import crashed importing it (signal 11: Segmentation fault)");
}

// An ImporterStatus as printf's octal escapes: answered (wait status 0), no CPU time, `files_before`.
std::string status_escapes(std::uint32_t files_before) {
    ImporterStatus status{};
    status.files_before = files_before;
    std::string escapes;
    const auto* bytes = reinterpret_cast<const unsigned char*>(&status);
    for (std::size_t i = 0; i < sizeof status; ++i) {
        char octal[8];
        std::snprintf(octal, sizeof octal, "\\%03o", unsigned(bytes[i]));
        escapes += octal;
    }
    return escapes;
}

// A stand-in helper whose first importer had answered `files_before` files
// and sends garbage for this one; a helper started after it answers the bunny.
std::string garbage_then_bunny(const TempDirectory& dir, std::uint32_t files_before) {
    write_file(dir.path() / "answer", encode_answer(import_with_assimp(kBunny)));
    const fs::path helper = fake_helper(dir,
                                        "cd \"$(dirname \"$0\")\"; if [ -e started ]; then cat answer >&3; exit; fi; "
                                        "touch started; printf garbage >&3; printf '" +
                                            status_escapes(files_before) + "' >&4; exec sleep 60");
    try {
        const ImportedScene scene = import_in_child(kBunny, {64, 60, 30.0}, helper);
        return scene.meshes.size() == 1 ? "the bunny" : "another scene";
    } catch (const ImportProcessError& error) {
        return error.what();
    }
}

TEST(HelperFailure, AFailureInAnImporterThatReadOtherFilesIsRetriedInAFreshOne) {
    const TempDirectory first("helper"), again("helper");
    EXPECT_EQ(garbage_then_bunny(first, 0),
              "wavepath-import sent a malformed answer: it does not begin with \"WPIMPORT\"");
    EXPECT_EQ(garbage_then_bunny(again, 3), "the bunny");
}

TEST(RealHelper, EndsOnItsOwnAtTheEndWithItsImporterReaped) {
    // The bunny's importer peaks at about 50 MiB, the helper at about 7: a
    // helper killed at the end leaves its importer unreaped, whose usage then
    // counts nowhere (bench/big_scenes.py reads it in RUSAGE_CHILDREN).
    // ctest runs each test in a process of its own, where no child came before.
    {
        MeshImporter importer({1024, 60, 60.0});
        importer.import(kBunny);
    }
    rusage children{};
    ASSERT_EQ(::getrusage(RUSAGE_CHILDREN, &children), 0);
    EXPECT_GT(children.ru_maxrss, 30 * 1024) << "KiB";
}

TEST(RealHelper, FilesAfterACrashInTheSameHelperAreRight) {
    // assimp 5.2.5 crashes on this OFF file (tests/corpus/bad/scenes): in an
    // importer that read the square first, then alone in a fresh one.
    const fs::path crash =
        fs::path(WAVEPATH_SOURCE_DIR) / "tests/corpus/bad/scenes/mesh_off_count_beginning_with_4.off";
    const TempDirectory dir("files");
    const fs::path square = dir.path() / "square.obj";
    write_file(square, kSquareObj);
    MeshImporter importer({1024, 60, 60.0});
    importer.expect({square, crash, square});
    const ImportedScene expected = import_with_assimp(square);
    expect_same_scene(importer.import(square), expected);
    EXPECT_EQ(thrown_message<ImportProcessError>([&] { importer.import(crash); }),
              "wavepath-import crashed importing it (signal 11: Segmentation fault)");
    expect_same_scene(importer.import(square), expected);
}

TEST(HelperFailure, AWellFormedAnswerFromAnyHelperIsTaken) {
    // The fake helper's answer is the bunny's, whatever file it was asked for:
    // the test of the fakes above is the process, not the file.
    const TempDirectory dir("helper");
    const ImportedScene bunny = import_with_assimp(kBunny);
    write_file(dir.path() / "answer", encode_answer(bunny));
    const fs::path helper = fake_helper(dir, "cat \"$(dirname \"$0\")/answer\" >&3");
    expect_same_scene(import_in_child("/nonexistent.obj", {}, helper), bunny);
}

// The real helper under its own limits.
TEST(RealHelper, RunsOutOfMemoryUnderASmallLimit) {
    EXPECT_EQ(thrown_message<ImportProcessError>([] {
                  import_in_child(kBunny, {1, 60, 60.0});
              }),
              "wavepath-import ran out of memory importing it (limit 1 MiB, --mesh-import-memory)");
}

TEST(RealHelper, IsStoppedWhenItHangs) {
    // Opening a FIFO without a writer blocks: the helper hangs before assimp reads anything.
    const TempDirectory dir("fifo");
    const fs::path fifo = dir.path() / "mesh.obj";
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    EXPECT_EQ(thrown_message<ImportProcessError>([&] {
                  import_in_child(fifo, {64, 60, 0.5});
              }),
              "wavepath-import did not finish within 0.5 s and was stopped (--mesh-import-time)");
}

TEST(RealHelper, IsFoundBesideTheRunningExecutable) {
    EXPECT_EQ(import_helper_path(), fs::read_symlink("/proc/self/exe").parent_path() / "wavepath-import");
    EXPECT_TRUE(fs::exists(import_helper_path()));
}

TEST(RealHelper, MissingIsAnInstallationProblem) {
    EXPECT_EQ(thrown_message<ImportHelperUnavailable>([] { import_in_child(kBunny, {}, "/nonexistent/helper"); }),
              "cannot start the mesh import helper /nonexistent/helper: No such file or directory");
}

// ---- the answer's format ----

// Two meshes (one with normals) of two materials, three nodes (two of them
// instancing mesh 1), a camera, a light and two embedded images.
ImportedScene small_scene() {
    ImportedScene scene;
    scene.meshes.push_back({{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, false, {}, {{0, 1, 2}}, false, {}});
    scene.meshes.push_back({{{0, 0, 1}, {1, 0, 1}, {0, 1, 1}, {1, 1, 1}},
                            true,
                            {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}, {0, 0, 1}},
                            {{0, 1, 2}, {2, 1, 3}},
                            true,
                            {{0, 0}, {1, 0}, {0, 1}, {1, 1}}});
    const std::array<float, 16> identity{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    std::array<float, 16> moved = identity;
    moved[3] = 2.5f;
    scene.nodes.push_back({ImportedNode::kNoParent, "root", identity, {0}});
    scene.nodes.push_back({0, "a", moved, {1}});
    scene.nodes.push_back({1, "b", identity, {1, 0}});
    scene.meshes[1].material = 1;
    scene.materials.push_back({"plain",
                               {0.5f, 0.25f, 1, 1},
                               0,
                               0.5f,
                               {0, 0, 0},
                               1,
                               0,
                               1.5f,
                               "",
                               "",
                               {1, 0, 0, 0, 1, 0},
                               {1, 0, 0, 0, 1, 0},
                               ImportedAlphaMode::Opaque,
                               0.5f});
    scene.materials.push_back({"lit",
                               {1, 1, 1, 1},
                               1,
                               0,
                               {1, 0.5f, 0},
                               4,
                               0.5f,
                               1.25f,
                               "wood.png",
                               "bumps.png",
                               {0, -4, 0.5f, 2, 0, 0.25f},
                               {2, 0, 0, 0, 2, 0},
                               ImportedAlphaMode::Blend,
                               0.25f,
                               kMetallicRoughnessTexture | kEmissiveTexture});
    scene.cameras.push_back({"eye", 1, {0, 1, 5}, {0, 1, 4}, {0, 1, 0}, 0.75f, 1.5f});
    scene.lights.push_back({"sun", 2, ImportedLightType::Directional, {2, 2, 1.5f}, {0, 0, 0}, {0, 0, -1}, 0, 0});
    scene.lights.push_back({"lamp", 1, ImportedLightType::Spot, {4, 3, 2}, {0, 1, 0}, {0, 0, -1}, 0.25f, 0.5f});
    scene.images.push_back({"png", std::string("\x89PNG\0\r\n", 7)});
    scene.images.push_back({"", ""});  // an uncompressed one
    return scene;
}

std::string malformation(const std::string& bytes) {
    return thrown_message<MalformedAnswer>([&] { decode_answer(bytes); });
}

TEST(Answer, RoundTrips) {
    ImportedScene scene = small_scene();
    expect_same_scene(std::get<ImportedScene>(decode_answer(encode_answer(scene))), scene);
    // Empty arrays, whose data() is null (fuzz_mesh: an OBJ of vertices and no face).
    scene.meshes.emplace_back();
    scene.nodes.push_back({0, "", {}, {}});
    expect_same_scene(std::get<ImportedScene>(decode_answer(encode_answer(scene))), scene);
    EXPECT_EQ(std::get<ImportFailure>(decode_answer(encode_answer(ImportFailure{"no good"}))).message, "no good");
}

TEST(Answer, EveryTruncationIsMalformed) {
    const std::string bytes = encode_answer(small_scene());
    for (std::size_t size = 0; size < bytes.size(); ++size)
        EXPECT_NE(malformation(bytes.substr(0, size)), "(none)") << size << " of " << bytes.size() << " bytes";
}

TEST(Answer, MalformedPartsAreNamed) {
    const std::string good = encode_answer(small_scene());
    EXPECT_EQ(malformation(good + "x"), "1 bytes after the answer");
    std::string bytes = good;
    bytes[8] = 3;  // the version
    EXPECT_EQ(malformation(bytes), "version 3, not 5");
    bytes = good;
    bytes[12] = 3;  // the kind
    EXPECT_EQ(malformation(bytes), "kind 3, neither 1 nor 2");
    bytes = good;
    bytes[24] = 4;  // mesh 0's flags (after the header's 16 bytes, the mesh count, its vertex count)
    EXPECT_EQ(malformation(bytes), "mesh 0's flags are 4");
    bytes = good;
    bytes[20] = static_cast<char>(0xff);  // mesh 0's vertex count, now 255 vertices of 12 bytes
    EXPECT_EQ(malformation(bytes).rfind("it ends within mesh 0's positions (3060 bytes, ", 0), 0u);

    ImportedScene scene = small_scene();
    scene.nodes[2].parent = 2;
    EXPECT_EQ(malformation(encode_answer(scene)), "node 2's parent is 2 (not an earlier node)");
    scene = small_scene();
    scene.nodes[0].parent = 0;
    EXPECT_EQ(malformation(encode_answer(scene)), "node 0's parent is 0 (the root has none)");
    scene = small_scene();
    scene.nodes[1].meshes = {2};
    EXPECT_EQ(malformation(encode_answer(scene)), "node 1 names mesh 2 of 2");
    scene = small_scene();
    scene.nodes[1].name.assign(kMaxNodeName + 1, 'n');
    EXPECT_EQ(malformation(encode_answer(scene)), "node 1's name of 1024 bytes (0 to 1023 expected)");
    scene = small_scene();
    scene.meshes[0].material = 2;
    EXPECT_EQ(malformation(encode_answer(scene)), "mesh 0 names material 2 of 2");
    scene = small_scene();
    scene.materials.clear();
    EXPECT_EQ(malformation(encode_answer(scene)), "mesh 1 names material 1 of 0");
    scene = small_scene();
    scene.cameras[0].node = 3;
    EXPECT_EQ(malformation(encode_answer(scene)), "camera 0 names node 3 of 3");
    scene = small_scene();
    scene.lights[0].node = 7;
    EXPECT_EQ(malformation(encode_answer(scene)), "light 0 names node 7 of 3");
    scene = small_scene();
    scene.lights[0].type = static_cast<ImportedLightType>(4);
    EXPECT_EQ(malformation(encode_answer(scene)), "light 0's type is 4 (1 to 3 expected)");
    scene = small_scene();
    scene.materials[0].alpha_mode = static_cast<ImportedAlphaMode>(3);
    EXPECT_EQ(malformation(encode_answer(scene)), "material 0's alpha mode is 3 (0 to 2 expected)");
    scene = small_scene();
    scene.materials[1].base_color_texture.assign(kMaxImportedName + 1, 't');
    EXPECT_EQ(malformation(encode_answer(scene)),
              "material 1's base colour texture of 1024 bytes (0 to 1023 expected)");
    scene = small_scene();
    scene.materials[0].unread_textures = 4;
    EXPECT_EQ(malformation(encode_answer(scene)), "material 0's unread textures are 4 (0 to 3 expected)");
    scene = small_scene();
    scene.images[0].format = "jpegjpegj";
    EXPECT_EQ(malformation(encode_answer(scene)), "image 0's format of 9 bytes (0 to 8 expected)");
    EXPECT_EQ(malformation(encode_answer(ImportFailure{""})), "the failure message of 0 bytes (1 to 4096 expected)");
}

// ---- wavepath's invariants, checked again on what came back ----

TEST(ImportedMeshChecks, RefuseWhatTheHelperShouldHaveRefused) {
    ImportedScene scene = small_scene();
    scene.meshes[1].triangles[1].z = 4;
    EXPECT_EQ(thrown_message<MeshFileError>([&] { mesh_from_import(scene, {}); }),
              "vertex index 4 out of range (4 vertices)");
    scene = small_scene();
    scene.meshes[0].positions[1].y = std::numeric_limits<float>::infinity();
    EXPECT_EQ(thrown_message<MeshFileError>([&] { mesh_from_import(scene, {}); }), "vertex (1, inf, 0) is not finite");
}

}  // namespace
}  // namespace wp::test
