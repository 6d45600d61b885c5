// Device listing, the program binary cache, build errors that name the file
// and line, scene specialisation (no dielectric code without glass), and
// kernel headers that each include what they use.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <set>

#include "opencl/device.h"
#include "opencl/kernel_options.h"
#include "opencl/program_cache.h"
#include "support/scoped_env.h"
#include "support/temp_directory.h"
#include "wavefront/pipeline.h"

namespace wp {
namespace {
namespace fs = std::filesystem;
using test::ScopedEnv;

// A fresh directory under the system temp dir, removed afterwards.
struct TempDir {
    fs::path path;
    TempDir() {
        path = fs::temp_directory_path() /
               ("wavepath-test-" + std::to_string(::getpid()) + "-" + std::to_string(counter()++));
        fs::remove_all(path);
        fs::create_directories(path);
    }
    ~TempDir() { fs::remove_all(path); }
    static int& counter() {
        static int n = 0;
        return n;
    }
};

FeatureSet diffuse_spheres() {
    FeatureSet f;
    f.spheres = f.diffuse = true;
    return f;
}

BuiltProgram build_wavefront(const DeviceInfo& device, const FeatureSet& features) {
    cl::Context context(device.device);
    return build_program(context, device, wavefront_kernel_files(), kernel_build_options(features, RenderSettings{}));
}

TEST(Devices, ListedWithTheirProperties) {
    std::vector<DeviceInfo> devices = list_devices();
    ASSERT_FALSE(devices.empty());
    for (const DeviceInfo& d : devices) {
        EXPECT_FALSE(d.name.empty());
        EXPECT_GT(d.compute_units, 0u);
        EXPECT_GT(d.global_memory_bytes, 0u);
        EXPECT_NE(d.opencl_c_version.find("OpenCL C"), std::string::npos);
        EXPECT_GT(d.preferred_float_vector_width, 0u);
        EXPECT_GT(d.native_float_vector_width, 0u);
    }
    std::string table = describe_devices(devices);
    EXPECT_NE(table.find(devices[0].name), std::string::npos);
    EXPECT_NE(table.find("compute units"), std::string::npos);
    EXPECT_NE(table.find("float vector width: preferred " + std::to_string(devices[0].preferred_float_vector_width) +
                         ", native " + std::to_string(devices[0].native_float_vector_width)),
              std::string::npos);
}

TEST(Devices, ChosenByIndexOrNameAndBadChoicesNamed) {
    std::vector<DeviceInfo> devices = list_devices();
    EXPECT_EQ(choose_device("0").name, devices[0].name);
    EXPECT_EQ(choose_device(devices[0].name.substr(0, 4)).name, devices[0].name);
    EXPECT_THROW(choose_device(std::to_string(devices.size())), DeviceError);
    try {
        choose_device("no-such-device-xyz");
        FAIL() << "expected DeviceError";
    } catch (const DeviceError& e) {
        EXPECT_NE(std::string(e.what()).find("no-such-device-xyz"), std::string::npos);
    }
}

TEST(ProgramCache, MissThenHitKeyedByOptionsAndSource) {
    TempDir cache;
    ScopedEnv env("WAVEPATH_CACHE_DIR", cache.path.string());
    DeviceInfo device = choose_device("");
    BuiltProgram first = build_wavefront(device, diffuse_spheres());
    EXPECT_FALSE(first.cache_hit);
    EXPECT_TRUE(fs::exists(first.cache_file));
    BuiltProgram second = build_wavefront(device, diffuse_spheres());
    EXPECT_TRUE(second.cache_hit);
    EXPECT_EQ(second.cache_file, first.cache_file);
    EXPECT_LT(second.build_seconds, first.build_seconds);
    std::printf("build: %.2f s from source, %.3f s from the cache\n", first.build_seconds, second.build_seconds);

    FeatureSet with_glass = diffuse_spheres();
    with_glass.glass = true;
    BuiltProgram other = build_wavefront(device, with_glass);
    EXPECT_FALSE(other.cache_hit);
    EXPECT_NE(other.cache_file, first.cache_file);
}

// Copies kernels/ into a temp dir (for WAVEPATH_KERNEL_DIR) and lets the test edit one file.
fs::path copy_kernels(const fs::path& to) {
    fs::copy(WAVEPATH_SOURCE_DIR "/kernels", to, fs::copy_options::recursive);
    return to;
}

void replace_in_file(const fs::path& file, const std::string& from, const std::string& to) {
    std::ifstream in(file);
    std::string text((std::istreambuf_iterator<char>(in)), {});
    std::size_t at = text.find(from);
    ASSERT_NE(at, std::string::npos) << from;
    text.replace(at, from.size(), to);
    std::ofstream(file) << text;
}

int line_of(const fs::path& file, const std::string& needle) {
    std::ifstream in(file);
    std::string line;
    for (int n = 1; std::getline(in, line); ++n)
        if (line.find(needle) != std::string::npos) return n;
    return -1;
}

TEST(ProgramBuild, BrokenKernelNamesFileAndLine) {
    TempDir cache, kernels;
    ScopedEnv cache_env("WAVEPATH_CACHE_DIR", cache.path.string());
    fs::path dir = copy_kernels(kernels.path / "kernels");
    ScopedEnv kernel_env("WAVEPATH_KERNEL_DIR", dir.string());
    replace_in_file(dir / "shade.cl", "next.continues);", "next.undeclared_thing);");
    int line = line_of(dir / "shade.cl", "undeclared_thing");
    try {
        build_wavefront(choose_device(""), diffuse_spheres());
        FAIL() << "expected KernelBuildError";
    } catch (const KernelBuildError& e) {
        std::string expected = (dir / "shade.cl").string() + ":" + std::to_string(line) + ": ";
        EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("undeclared_thing"), std::string::npos) << e.what();
        EXPECT_NE(e.log().find("undeclared_thing"), std::string::npos);
    }
}

// Builds the wavefront program from a copy of kernels/ in which `file` has
// `from` replaced by `to`: the one-line build error ("" when it builds), and
// the "file:line: " that error should start with, of the line of the copy's
// `located_in` that holds `needle`.
struct EditedBuild {
    std::string error, expected_location;
};
EditedBuild build_edited_copy(const std::string& file, const std::string& from, const std::string& to,
                              const std::string& located_in, const std::string& needle) {
    TempDir cache, kernels;
    ScopedEnv cache_env("WAVEPATH_CACHE_DIR", cache.path.string());
    fs::path dir = copy_kernels(kernels.path / "kernels");
    ScopedEnv kernel_env("WAVEPATH_KERNEL_DIR", dir.string());
    replace_in_file(dir / file, from, to);
    EditedBuild built{"", (dir / located_in).string() + ":" + std::to_string(line_of(dir / located_in, needle)) + ": "};
    try {
        build_wavefront(choose_device(""), diffuse_spheres());
    } catch (const KernelBuildError& e) {
        built.error = e.what();
    }
    return built;
}

// A stage kernel is held to its declaration (kernels/interface/stages.h) when
// it compiles: a push to a queue the declaration does not list fails the
// build at the push.
TEST(ProgramBuild, PushToAQueueTheStageDoesNotDeclareFailsToCompile) {
    EditedBuild built =
        build_edited_copy("intersect.cl", "STAGE_PUSH(HIT, lanes, lanes.active)",
                          "STAGE_PUSH(SHADOW, lanes, lanes.active)", "intersect.cl", "STAGE_PUSH(SHADOW");
    EXPECT_NE(built.error.find(built.expected_location), std::string::npos) << built.error;
    EXPECT_NE(built.error.find("a push to SHADOW, which the stage's declaration"), std::string::npos) << built.error;
}

// And a declaration changed without its kernel fails the build at the
// kernel's first line, which states its queues.
TEST(ProgramBuild, StageOpeningWithOtherQueuesThanItsDeclarationFailsToCompile) {
    EditedBuild built = build_edited_copy(
        "interface/stages.h", "X(shade, CAMERA, HIT, WP_PUSHES(SHADOW, RAY, FREE), HIT_STAGE, NO_RAYS)",
        "X(shade, CAMERA, HIT, WP_PUSHES(RAY, FREE), HIT_STAGE, NO_RAYS)", "shade.cl", "STAGE_QUEUES");
    EXPECT_NE(built.error.find(built.expected_location), std::string::npos) << built.error;
    EXPECT_NE(built.error.find("the queues of shade differ from its declaration"), std::string::npos) << built.error;
}

// docs/architecture.md ("Specialisation") lists exactly the macros that
// src/opencl/kernel_options.cpp can emit: the WP_ names in its string
// literals, which are those its functions put in the options.
TEST(KernelOptions, ArchitectureDocListsEveryMacroTheyEmit) {
    const std::string code = test::read_text(WAVEPATH_SOURCE_DIR "/src/opencl/kernel_options.cpp");
    const std::string doc = test::read_text(WAVEPATH_SOURCE_DIR "/docs/architecture.md");
    const std::size_t section = doc.find("\n## Specialisation\n");
    ASSERT_NE(section, std::string::npos);
    const std::string specialisation = doc.substr(section, doc.find("\n## ", section + 1) - section);
    auto names = [](const std::string& text, const std::regex& pattern) {
        std::set<std::string> found;
        for (std::sregex_iterator m(text.begin(), text.end(), pattern), end; m != end; ++m) found.insert((*m)[1]);
        return found;
    };
    std::set<std::string> emitted;
    static const std::regex literal(R"(("(?:[^"\\\n]|\\.)*"))"), macro(R"((WP_[A-Z0-9_]+))");
    for (const std::string& text : names(code, literal))
        for (const std::string& name : names(text, macro)) emitted.insert(name);
    EXPECT_EQ(names(specialisation, std::regex(R"(-D(WP_[A-Z0-9_]+))")), emitted);

    // The literals are what the functions emit: every macro of a build with many features is among them.
    FeatureSet many = diffuse_spheres();
    many.quads = many.glass = many.quad_lights = many.nee = many.mis = true;
    RenderSettings uniform_independent;
    uniform_independent.hemisphere = Hemisphere::Uniform;
    uniform_independent.sampler = Sampler::Independent;
    const std::string options = kernel_build_options(many, uniform_independent);
    const std::set<std::string> used = names(options, std::regex(R"(-D(WP_[A-Z0-9_]+))"));
    EXPECT_FALSE(used.empty()) << options;
    for (const std::string& name : used) EXPECT_EQ(emitted.count(name), 1u) << name;
}

// Without glass the kernels are built without WP_HAS_GLASS, and
// kernels/device/path_vertex.h then poisons the dielectric functions: the
// build succeeding proves no dielectric code is compiled in. The poison is
// checked too: the same program with the glass material forced in fails.
TEST(ProgramBuild, SceneWithoutGlassBuildsWithoutDielectricCode) {
    TempDir cache, kernels;
    ScopedEnv cache_env("WAVEPATH_CACHE_DIR", cache.path.string());
    FeatureSet no_glass = diffuse_spheres();
    no_glass.mirror = true;
    std::string options = kernel_build_options(no_glass, RenderSettings{});
    EXPECT_EQ(options.find("GLASS"), std::string::npos) << options;
    DeviceInfo device = choose_device("");
    EXPECT_NO_THROW(build_wavefront(device, no_glass));

    fs::path dir = copy_kernels(kernels.path / "kernels");
    ScopedEnv kernel_env("WAVEPATH_KERNEL_DIR", dir.string());
    replace_in_file(dir / "device" / "path_vertex.h", "#ifdef WP_HAS_GLASS\n#include \"shared/materials/glass.h\"",
                    "#if 1\n#include \"shared/materials/glass.h\"");
    try {
        build_wavefront(device, no_glass);
        FAIL() << "the glass code compiled without WP_HAS_GLASS";
    } catch (const KernelBuildError& e) {
        EXPECT_TRUE(std::regex_search(std::string(e.what()), std::regex("poisoned|fresnel_dielectric"))) << e.what();
    }
}

// Every kernel header compiles as the only include of a program, with each
// lane count (1, 4, 8, 16), and twice in a row (include guards): each includes
// what it uses, so no header depends on what an includer happened to include first.
TEST(ProgramBuild, EveryKernelHeaderCompilesOnItsOwn) {
    DeviceInfo device = choose_device("");
    cl::Context context(device.device);
    int headers = 0;
    const fs::path root(WAVEPATH_SOURCE_DIR "/kernels");
    for (const char* folder : {"shared", "interface", "device"}) {
        for (const fs::directory_entry& entry : fs::recursive_directory_iterator(root / folder)) {
            if (!entry.is_regular_file()) continue;  // shared/materials/ holds headers of its own
            const std::string include = "#include \"" + entry.path().lexically_relative(root).string() + "\"\n";
            for (const char* lanes : {"1", "4", "8", "16"}) {
                SCOPED_TRACE(include + " with " + lanes + " lanes");
                cl::Program program(context, include + include);
                const std::string options =
                    std::string("-cl-std=CL1.2 -I " WAVEPATH_SOURCE_DIR "/kernels -DWP_LANES=") + lanes +
                    (std::string(lanes) != "1" ? " -DWP_COMPACT_SCAN" : "");
                try {
                    program.build({device.device}, options.c_str());
                } catch (const cl::BuildError&) {
                    ADD_FAILURE() << program.getBuildInfo<CL_PROGRAM_BUILD_LOG>(device.device);
                }
            }
            ++headers;
        }
    }
    EXPECT_GE(headers, 18);
}

}  // namespace
}  // namespace wp
