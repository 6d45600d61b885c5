// The wavefront through the wavepath executable: --explain, --wavefront, --lanes, `wavepath devices`, and device
// errors.
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <string>

namespace wp {
namespace {

struct CommandRun {
    int exit_code;
    std::string output;  // stdout and stderr
};

CommandRun run(const std::string& environment, const std::string& arguments) {
    std::string command = environment + " '" WAVEPATH_BINARY "' " + arguments + " 2>&1";
    FILE* pipe = ::popen(command.c_str(), "r");
    CommandRun result{-1, ""};
    std::array<char, 4096> buffer;
    while (std::size_t n = std::fread(buffer.data(), 1, buffer.size(), pipe)) result.output.append(buffer.data(), n);
    int status = ::pclose(pipe);
    result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return result;
}

std::string cache_env() {
    return "WAVEPATH_CACHE_DIR='" +
           (std::filesystem::path(WAVEPATH_BINARY).parent_path() / "test-program-cache").string() + "'";
}

std::string output_path(const char* name) { return (std::filesystem::temp_directory_path() / name).string(); }

TEST(WavefrontCli, ExplainSaysWhatWasBuilt) {
    std::string out = output_path("wavepath-wavefront-cli.pfm");
    CommandRun r = run(cache_env(), "render '" WAVEPATH_SOURCE_DIR "/scenes/test/room_small.json' -o '" + out +
                                        "' --spp 1 --backend wavefront --wavefront 256 --explain");
    EXPECT_EQ(r.exit_code, 0) << r.output;
    for (const char* text :
         {"backend: wavefront (--backend)\n", "features: spheres quads diffuse mirror glass emitter quad-lights nee",
          "build options: -cl-std=CL1.2", "-DWP_HAS_GLASS", "program: cache", "wavefront: 256 paths in flight",
          "paths per work item in the stage kernels", "bytes per path", "spp, wavefront) in "})
        EXPECT_NE(r.output.find(text), std::string::npos) << text << "\n" << r.output;
    EXPECT_TRUE(std::filesystem::exists(out));
    std::filesystem::remove(out);
}

// A cold program cache: the first progress line says the kernels are being
// built, and no progress line gives an ETA before samples were measured; the
// same render again reuses the cache and says nothing of a build.
TEST(WavefrontCli, ColdCacheSaysKernelsAreBuiltWarmCacheDoesNot) {
    const std::filesystem::path cache = std::filesystem::temp_directory_path() / "wavepath-cold-cache-test";
    std::filesystem::remove_all(cache);
    const std::string environment = "WAVEPATH_CACHE_DIR='" + cache.string() + "'";
    const std::string out = output_path("wavepath-cold-cache.pfm");
    const std::string args =
        "render '" WAVEPATH_SOURCE_DIR "/scenes/test/room_small.json' -o '" + out + "' --spp 1 --wavefront 256";
    const CommandRun cold = run(environment, args);
    ASSERT_EQ(cold.exit_code, 0) << cold.output;
    EXPECT_EQ(cold.output.rfind("wavepath: building the kernels for this scene; later runs with the same features "
                                "reuse them from " +
                                    cache.string() + "\n",
                                0),
              0u)
        << cold.output;
    // An ETA comes only from measured samples: none on a line that shows 0% done.
    for (std::size_t at = cold.output.find("wavepath: 0% done"); at != std::string::npos;
         at = cold.output.find("wavepath: 0% done", at + 1))
        EXPECT_NE(cold.output.substr(at, cold.output.find('\n', at) - at).find("ETA --"), std::string::npos)
            << cold.output;
    const CommandRun warm = run(environment, args);
    ASSERT_EQ(warm.exit_code, 0) << warm.output;
    EXPECT_EQ(warm.output.find("building the kernels"), std::string::npos) << warm.output;
    std::filesystem::remove_all(cache);
    std::filesystem::remove(out);
}

TEST(WavefrontCli, DevicesListed) {
    CommandRun r = run("", "devices");
    EXPECT_EQ(r.exit_code, 0);
    for (const char* text :
         {"[0] ", "platform: ", "type: ", "compute units: ", "memory: ", "OpenCL C ", "float vector width: preferred "})
        EXPECT_NE(r.output.find(text), std::string::npos) << text << "\n" << r.output;
}

// ocl-icd reads the installed platforms from OCL_ICD_VENDORS: an empty
// directory stands for a machine without any OpenCL platform.
TEST(WavefrontCli, NoPlatformOrUnknownDeviceIsOneClearError) {
    std::filesystem::path empty = std::filesystem::temp_directory_path() / "wavepath-no-icd";
    std::filesystem::create_directories(empty);
    CommandRun none = run("OCL_ICD_VENDORS='" + empty.string() + "'", "devices");
    EXPECT_EQ(none.exit_code, 1);
    EXPECT_EQ(none.output,
              "wavepath: error: no OpenCL device found (no platform installed, or none with a device; "
              "try `clinfo -l`)\n");

    std::string out = output_path("wavepath-no-device.png");
    CommandRun unknown = run(cache_env(), "render '" WAVEPATH_SOURCE_DIR "/scenes/test/room_small.json' -o '" + out +
                                              "' --device no-such-device");
    EXPECT_EQ(unknown.exit_code, 1);
    EXPECT_NE(unknown.output.find("--device no-such-device: "), std::string::npos) << unknown.output;
    EXPECT_FALSE(std::filesystem::exists(out));
}

// `render` of the small room with `flags` fails as a usage error with `message` alone, writing nothing.
void expect_usage_error(const std::string& flags, const std::string& message) {
    std::string out = output_path("wavepath-usage-error.png");
    CommandRun r =
        run(cache_env(), "render '" WAVEPATH_SOURCE_DIR "/scenes/test/room_small.json' -o '" + out + "' " + flags);
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_EQ(r.output, "wavepath: error: " + message + "\n");
    EXPECT_FALSE(std::filesystem::exists(out));
}

TEST(WavefrontCli, EightLanesWithAtomicPushesIsAUsageError) {
    expect_usage_error("--lanes 8 --compaction atomic",
                       "--lanes 8 needs --compaction scan (atomic pushes are per work item)");
}

TEST(WavefrontCli, LaneCountTheKernelsDoNotCompileIsAUsageError) {
    expect_usage_error("--lanes 2", "--lanes: 2 not in {0,1,4,8,16} (see wavepath render --help)");
}

}  // namespace
}  // namespace wp
