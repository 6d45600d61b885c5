// --profile: the per-kernel figures agree with the render's own counts, and
// the JSON the CLI writes says the same as its --stats-json.
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <numeric>

#include "wavefront/wavefront_renderer.h"
#include "wavefront_test_support.h"

namespace wp {
namespace {

std::uint64_t sum(const std::vector<std::uint64_t>& values) {
    return std::accumulate(values.begin(), values.end(), std::uint64_t(0));
}

TEST(Profile, KernelItemsMatchTheRaysTheRenderCounted) {
    Scene scene = test::scene_from_file("scenes/test/room_small.json");
    scene.camera.width = scene.camera.height = 32;
    scene.render.spp = 2;
    WavefrontOptions options;
    options.wavefront = 512;  // several passes and a regenerating wavefront
    options.profile = true;
    WavefrontReport report;
    RenderResult result = render_wavefront(scene, options, {}, &report);
    WavefrontProfile& p = report.profile;

    EXPECT_EQ(p.kernel("intersect").items, result.stats.extension_rays);
    EXPECT_EQ(p.kernel("intersect_shadow").items, result.stats.shadow_rays);
    EXPECT_EQ(p.kernel("accumulate").items, result.stats.samples);
    EXPECT_GE(p.kernel("generate").items, result.stats.samples);  // every camera ray took a free slot
    // Every hit is shaded; those that did not end there scatter.
    EXPECT_LE(p.kernel("scatter").items, p.kernel("shade_direct").items);
    EXPECT_LE(p.kernel("shade_direct").items, p.kernel("intersect").items);

    // The kernels' own per-depth counts add up to the same rays; depth 0 is the camera rays.
    EXPECT_EQ(sum(p.extension_rays_by_depth), result.stats.extension_rays);
    EXPECT_EQ(sum(p.shadow_rays_by_depth), result.stats.shadow_rays);
    ASSERT_FALSE(p.extension_rays_by_depth.empty());
    EXPECT_EQ(p.extension_rays_by_depth[0], result.stats.samples);
    for (std::size_t d = 1; d < p.extension_rays_by_depth.size(); ++d)
        EXPECT_LE(p.extension_rays_by_depth[d], p.extension_rays_by_depth[d - 1]) << "depth " << d;

    for (const char* stage : {"generate", "intersect", "shade_direct", "intersect_shadow", "scatter"}) {
        EXPECT_EQ(p.kernel(stage).launches, p.iterations) << stage;
        EXPECT_GT(p.kernel(stage).device_s, 0.0) << stage;
    }
    EXPECT_EQ(p.iterations, report.iterations.size());
    EXPECT_EQ(p.kernel("accumulate").launches,
              (result.stats.samples + report.pass_capacity - 1) / report.pass_capacity);
    EXPECT_GT(p.render_s, 0.0);
    EXPECT_EQ(p.render_s, result.stats.time_s);
}

// Runs a shell command; returns its stdout and stderr, and its exit status.
std::string run_shell(const std::string& command, int& exit_code) {
    FILE* pipe = ::popen((command + " 2>&1").c_str(), "r");
    std::string output;
    std::array<char, 4096> buffer;
    while (std::size_t n = std::fread(buffer.data(), 1, buffer.size(), pipe)) output.append(buffer.data(), n);
    int status = ::pclose(pipe);
    exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return output;
}

nlohmann::json read_json(const std::filesystem::path& path) {
    std::ifstream in(path);
    return nlohmann::json::parse(in);
}

TEST(Profile, CliWritesJsonConsistentWithStatsAndPrintsTable) {
    test::use_build_tree_program_cache();
    std::filesystem::path dir = std::filesystem::temp_directory_path() / "wavepath-profile-test";
    std::filesystem::create_directories(dir);
    std::string command = "'" WAVEPATH_BINARY "' render '" WAVEPATH_SOURCE_DIR "/scenes/test/room_small.json' -o '" +
                          (dir / "out.pfm").string() + "' --spp 2 --wavefront 1024 --profile --profile-json '" +
                          (dir / "profile.json").string() + "' --stats-json '" + (dir / "stats.json").string() + "'";
    int exit_code;
    std::string output = run_shell(command, exit_code);
    ASSERT_EQ(exit_code, 0) << output;
    for (const char* text : {"kernel", "launches", "items", "device ms", "Mitems/s", "intersect_shadow",
                             "(between kernels)", "extension rays by depth:", "program build"})
        EXPECT_NE(output.find(text), std::string::npos) << text << "\n" << output;

    nlohmann::json profile = read_json(dir / "profile.json"), stats = read_json(dir / "stats.json");
    std::map<std::string, nlohmann::json> kernels;
    for (const nlohmann::json& k : profile["kernels"]) kernels[k["name"]] = k;
    EXPECT_EQ(kernels["intersect"]["items"], stats["extension_rays"]);
    EXPECT_EQ(kernels["intersect_shadow"]["items"], stats["shadow_rays"]);
    EXPECT_EQ(kernels["accumulate"]["items"], stats["samples"]);
    EXPECT_EQ(profile["render_s"], stats["time_s"]);
    double kernel_s = 0.0;
    for (const auto& [name, k] : kernels) {
        kernel_s += k["device_s"].get<double>();
        EXPECT_NEAR(k["items_per_s"].get<double>(), k["items"].get<double>() / k["device_s"].get<double>(),
                    1e-9 * k["items_per_s"].get<double>())
            << name;
    }
    EXPECT_NEAR(profile["kernel_s"].get<double>(), kernel_s, 1e-12);
    std::uint64_t by_depth = 0;
    for (std::uint64_t n : profile["extension_rays_by_depth"]) by_depth += n;
    EXPECT_EQ(by_depth, stats["extension_rays"].get<std::uint64_t>());
    std::filesystem::remove_all(dir);
}

TEST(Profile, ReferenceBackendRefusesProfile) {
    std::string command = "'" WAVEPATH_BINARY "' render '" WAVEPATH_SOURCE_DIR
                          "/scenes/test/room_small.json' -o /tmp/wavepath-profile-ref.pfm --backend reference "
                          "--profile";
    int exit_code;
    std::string output = run_shell(command, exit_code);
    EXPECT_EQ(exit_code, 2) << output;
    EXPECT_NE(output.find("--profile"), std::string::npos) << output;
    EXPECT_FALSE(std::filesystem::exists("/tmp/wavepath-profile-ref.pfm"));
}

}  // namespace
}  // namespace wp
