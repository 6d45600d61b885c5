// --profile: the per-kernel figures agree with the render's own counts, and
// the JSON the CLI writes says the same as its --stats-json.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <numeric>
#include <optional>
#include <regex>
#include <string>

#include "opencl/device.h"
#include "reference/path_tracer.h"
#include "reference/reference_renderer.h"
#include "wavefront/stage.h"
#include "wavefront/wavefront_renderer.h"
#include "wavefront_test_support.h"

namespace wp {
namespace {

std::uint64_t sum(const std::vector<std::uint64_t>& values) {
    return std::accumulate(values.begin(), values.end(), std::uint64_t(0));
}

// A profiled wavefront render of scenes/test/room_small.json at size x size,
// 1 spp, max_depth `max_depth`, `wavefront` paths in flight (0: automatic),
// the shadow rays traced by shade or by their own stage.
struct ProfiledRender {
    RenderResult result;
    WavefrontReport report;
};
ProfiledRender profiled_small_room(int size, int max_depth, std::size_t wavefront = 0, bool shadow_stage = false,
                                   std::optional<bool> intersect_and_shade = std::nullopt) {
    Scene scene = test::scene_from_file("scenes/test/room_small.json");
    scene.camera.width = scene.camera.height = size;
    scene.render.spp = 1;
    scene.render.max_depth = max_depth;
    WavefrontOptions options;
    options.wavefront = wavefront;
    options.profile = true;
    options.shadow_stage = shadow_stage;
    options.intersect_and_shade = intersect_and_shade;
    ProfiledRender rendered;
    rendered.result = render_wavefront(scene, options, {}, &rendered.report);
    return rendered;
}

// The stage kernels' items against counts from sources independent of the
// host's queue bookkeeping (IterationRecord, from which fill_profile sums
// the items): the scalar reference renderer's rays for the same scene
// (the same random numbers, so the same paths; ImageAgreement checks the
// paths themselves), the count_depths kernel's histograms (counted on the
// device from the queues' contents), and the scene's pixels x spp. With the
// shadow rays traced by their own stage, or by shade (no intersect_shadow
// row; they are counted after shade); with intersect and shade as one
// kernel (a CPU's default) or apart.
void expect_kernel_items_match_the_rays_the_render_counted(bool shadow_stage, bool intersect_and_shade = true) {
    Scene scene = test::scene_from_file("scenes/test/room_small.json");
    scene.camera.width = scene.camera.height = 32;
    scene.render.spp = 2;
    const std::uint64_t samples = std::uint64_t(scene.camera.width) * scene.camera.height * scene.render.spp;
    WavefrontOptions options;
    options.wavefront = 512;  // several passes and a regenerating wavefront
    options.profile = true;
    options.shadow_stage = shadow_stage;
    options.intersect_and_shade = intersect_and_shade;
    WavefrontReport report;
    RenderResult result = render_wavefront(scene, options, {}, &report);
    RenderProfile& p = report.profile;
    const char* tracing = intersect_and_shade ? "intersect_and_shade" : "intersect";  // the extension rays' stage
    RenderResult reference = render_reference(scene, ReferenceOptions{2, false});
    ASSERT_EQ(reference.stats.samples, samples);

    EXPECT_EQ(p.kernel(tracing).items, reference.stats.extension_rays);
    EXPECT_EQ(p.has_kernel("intersect"), !intersect_and_shade);
    EXPECT_EQ(p.has_kernel("shade"), !intersect_and_shade);
    EXPECT_EQ(result.stats.shadow_rays, reference.stats.shadow_rays);
    EXPECT_EQ(p.has_kernel("intersect_shadow"), shadow_stage);
    if (shadow_stage) {
        EXPECT_EQ(p.kernel("intersect_shadow").items, reference.stats.shadow_rays);
    }
    EXPECT_EQ(p.kernel("accumulate").items, samples);
    EXPECT_EQ(p.kernel("generate").items, samples);  // every camera ray took one free slot
    // Every ray is shaded, a miss too.
    if (!intersect_and_shade) {
        EXPECT_EQ(p.kernel("shade").items, p.kernel("intersect").items);
    }

    // The kernels' own per-depth counts add up to the reference's rays; depth 0 is the camera rays.
    EXPECT_EQ(sum(p.extension_rays_by_depth), reference.stats.extension_rays);
    EXPECT_EQ(sum(p.shadow_rays_by_depth), reference.stats.shadow_rays);
    ASSERT_FALSE(p.extension_rays_by_depth.empty());
    EXPECT_EQ(p.extension_rays_by_depth[0], samples);
    for (std::size_t d = 1; d < p.extension_rays_by_depth.size(); ++d)
        EXPECT_LE(p.extension_rays_by_depth[d], p.extension_rays_by_depth[d - 1]) << "depth " << d;

    for (const char* stage : {"generate", "intersect", "shade", "intersect_and_shade", "intersect_shadow"}) {
        if (!p.has_kernel(stage)) continue;
        EXPECT_GT(p.kernel(stage).device_s, 0.0) << stage;
        if (std::string(stage) != "generate") {
            EXPECT_EQ(p.kernel(stage).launches, p.iterations) << stage;
        }
    }
    // Generate is launched only in the iterations that start paths (not in a pass's drain).
    const auto starting = std::count_if(report.iterations.begin(), report.iterations.end(),
                                        [](const IterationRecord& r) { return r.generated > 0; });
    EXPECT_EQ(p.kernel("generate").launches, std::uint64_t(starting));
    EXPECT_LT(starting, std::ptrdiff_t(p.iterations));
    EXPECT_EQ(p.iterations, report.iterations.size());
    EXPECT_EQ(p.kernel("accumulate").launches, (samples + report.pass_capacity - 1) / report.pass_capacity);
    // The kernels ran one after another inside the timed render, so their
    // device times (event nanoseconds, converted) add up to less than its
    // wall time: a wrong unit, or a render time that left sampling out, fails.
    EXPECT_GT(p.kernel_s(), 0.0);
    EXPECT_LE(p.kernel_s(), p.render_s);
    EXPECT_GT(p.intersect_bound_rays_per_s, 0.0);
    EXPECT_TRUE(std::isfinite(p.intersect_bound_rays_per_s));

    // Each stage's row has its declared bytes for the kernels' features (here
    // the scene's, with or without the shadow stage); the other kernels declare none.
    FeatureSet kernel_features = scene.features();
    kernel_features.shadow_stage = shadow_stage;
    kernel_features.intersect_and_shade = intersect_and_shade;
    for (const StageDeclaration& stage : stage_declarations) {
        if (!p.has_kernel(stage.kernel)) continue;
        EXPECT_EQ(p.kernel(stage.kernel).bytes_per_item, stage_bytes_per_item(stage, kernel_features).total())
            << stage.kernel;
    }
    EXPECT_GT(p.kernel(intersect_and_shade ? "intersect_and_shade" : "shade").bytes_per_item, 0u);
    EXPECT_EQ(p.kernel("accumulate").bytes_per_item, 0u);
    EXPECT_EQ(p.kernel("count_depths").bytes_per_item, 0u);
    // A copy bandwidth from event nanoseconds in bytes/s: between 0.1 GB/s and
    // 100 TB/s on any device; a wrong unit is off by 10^3 or more.
    EXPECT_GT(p.copy_bytes_per_s, 1e8);
    EXPECT_LT(p.copy_bytes_per_s, 1e14);
    EXPECT_EQ(p.copy_buffer_bytes, std::uint64_t(256) << 20);
}

TEST(Profile, KernelItemsMatchTheRaysTheRenderCountedWithShadowRaysTracedInShade) {
    expect_kernel_items_match_the_rays_the_render_counted(false);
}

TEST(Profile, KernelItemsMatchTheRaysTheRenderCountedWithAShadowStage) {
    expect_kernel_items_match_the_rays_the_render_counted(true);
}

TEST(Profile, KernelItemsMatchTheRaysTheRenderCountedWithIntersectAndShadeApart) {
    expect_kernel_items_match_the_rays_the_render_counted(true, false);
}

// Where the host traces (--intersector embree), its share of a tracing
// stage is a row of its own, "embree:<stage>", launched as often as the
// stage's kernel over the same rays; its time is the host's, taken out of
// the device's idle time between kernels (else counted twice); and no
// intersect bound is measured (the bound is the kernels' tracing). The
// extension rays' stage is intersect_and_shade, a CPU's default.
TEST(Profile, HostTracedStagesHaveRowsOfTheirOwn) {
    Scene scene = test::scene_from_file("scenes/cornell_mesh.json");
    scene.camera.width = scene.camera.height = 32;
    scene.render.spp = 2;
    WavefrontOptions options;
    options.intersector = Intersector::Embree;
    options.profile = true;
    WavefrontReport report;
    RenderResult result = render_wavefront(scene, options, {}, &report);
    RenderProfile& p = report.profile;
    EXPECT_FALSE(p.has_kernel("intersect"));
    for (const char* stage : {"intersect_and_shade", "intersect_shadow"}) {
        const std::string row = std::string("embree:") + stage;
        ASSERT_TRUE(p.has_kernel(row)) << row;
        EXPECT_EQ(p.kernel(row).launches, p.kernel(stage).launches) << row;
        EXPECT_EQ(p.kernel(row).items, p.kernel(stage).items) << row;
        EXPECT_GT(p.kernel(row).device_s, 0.0) << row;
    }
    EXPECT_EQ(p.kernel("embree:intersect_and_shade").items, result.stats.extension_rays);
    EXPECT_EQ(p.kernel("embree:intersect_shadow").items, result.stats.shadow_rays);
    EXPECT_LE(p.kernel_s() + p.gaps_s, 1.05 * p.render_s);
    EXPECT_EQ(p.intersect_bound_rays_per_s, 0.0);
}

// SPPM's photon stages and its grid and update kernels are profiled too:
// emit_photons takes every photon, intersect_photons every photon ray, and
// the grid and update kernels run once per iteration (each iteration has
// visible points here).
TEST(Profile, SppmProfilesThePhotonStagesAndTheGrid) {
    Scene scene = test::scene_from_file("bench/scenes/sppm_caustic.json");
    scene.camera.width = scene.camera.height = 16;
    scene.render.spp = 2;
    scene.render.integrator = Integrator::Sppm;
    scene.render.sppm.photons = 700;
    WavefrontOptions options;
    options.wavefront = 256;  // the photon pass takes several iterations of its stages
    options.profile = true;
    WavefrontReport report;
    const RenderResult result = render_wavefront(scene, options, {}, &report);
    RenderProfile& p = report.profile;
    EXPECT_EQ(result.stats.photons, 2u * 700u);
    EXPECT_EQ(p.kernel("emit_photons").items, result.stats.photons);
    EXPECT_EQ(p.kernel("intersect_photons").items, result.stats.photon_rays);
    EXPECT_LE(p.kernel("shade_photons").items, p.kernel("intersect_photons").items);
    for (const char* kernel : {"grid_bounds", "grid_count", "grid_fill", "sppm_update"})
        EXPECT_EQ(p.kernel(kernel).launches, 2u) << kernel;
}

// A shadow ray is counted at the depth of the vertex that cast it, although
// shade has moved its path's depth on by then: with max_depth 1 every light
// sample is cast at the camera ray's hit, depth 0; whether shade traces the
// shadow rays or their own stage does.
TEST(Profile, ShadowRaysAreCountedAtTheDepthOfTheirVertex) {
    for (bool shadow_stage : {false, true}) {
        SCOPED_TRACE(shadow_stage ? "a shadow stage" : "traced in shade");
        ProfiledRender rendered = profiled_small_room(16, 1, 0, shadow_stage);
        const std::vector<std::uint64_t>& shadow = rendered.report.profile.shadow_rays_by_depth;
        ASSERT_FALSE(shadow.empty());
        EXPECT_GT(shadow[0], 0u);
        EXPECT_EQ(shadow[0], rendered.result.stats.shadow_rays);
        EXPECT_EQ(sum(shadow), shadow[0]);
    }
}

// docs/architecture.md's count of the kernels an iteration launches (at most:
// scan compaction, next-event estimation with a shadow stage, and intersect
// and shade apart, as here) is
// what one iteration launches: every path of this render ends at its first
// hit (max_depth 0), so it is one pass of one iteration, and its profile
// counts every launch but the pass's accumulate.
TEST(Profile, ArchitectureDocCountsTheKernelsOfAnIteration) {
    WavefrontReport report = profiled_small_room(8, 0, 64, true, false).report;
    ASSERT_EQ(report.iterations.size(), 1u);
    std::uint64_t launches = 0;
    for (const KernelProfile& k : report.profile.kernels)
        if (k.name != "accumulate") launches += k.launches;
    const std::uint64_t depth_counts = report.profile.kernel("count_depths").launches;  // with --profile only
    EXPECT_GT(depth_counts, 0u);

    std::ifstream in(WAVEPATH_SOURCE_DIR "/docs/architecture.md");
    const std::string doc((std::istreambuf_iterator<char>(in)), {});
    std::smatch stated;
    ASSERT_TRUE(std::regex_search(
        doc, stated, std::regex(R"(up\s+to\s+(\d+)\s+kernels\s+per\s+iteration\s+\((\d+)\s+with\s+`--profile`\))")));
    EXPECT_EQ(std::stoull(stated[1]), launches - depth_counts);
    EXPECT_EQ(std::stoull(stated[2]), launches);
}

// The sum of the reference's closest-hit distances over rays 0..rays-1 of
// intersect_bound.cl: ray r through the centre of pixel r % (width * height).
double reference_hit_distance_sum(const Scene& scene, std::uint32_t rays) {
    using M = SharedMath<float>;
    reference::ReferenceScene<float> ref(scene);
    const auto& c = ref.camera;
    double sum = 0.0;
    for (std::uint32_t r = 0; r < rays; ++r) {
        std::uint32_t pixel = r % std::uint32_t(c.width * c.height);
        reference::Ray<float> ray{
            c.position, M::pixel_direction(c.frame, float(pixel % c.width), float(pixel / c.width), float(c.width),
                                           float(c.height), 0.5f, 0.5f)};
        auto hit = reference::closest_hit(ref, ray);
        if (hit.found()) sum += hit.t;
    }
    return sum;
}

// The bound kernel traces what it claims to: the reference's hits, with one
// lane and with eight, over more rays than pixels and a count that fills
// neither the last work group nor the last work item's lanes.
TEST(Profile, IntersectBoundTracesTheReferenceHits) {
    Scene scene = test::scene_from_file("scenes/test/room_small.json");
    constexpr std::uint32_t kRays = 2 * 32 * 32 + 77;
    double expected = reference_hit_distance_sum(scene, kRays);
    for (auto [lanes, compaction] : {std::pair{1u, Compaction::Atomic}, std::pair{8u, Compaction::Scan}}) {
        SCOPED_TRACE(std::to_string(lanes) + " lanes");
        PipelineOptions options;
        options.profile = true;
        options.compaction = compaction;
        options.lanes = lanes;
        Pipeline pipeline(scene, choose_device(""), 256, 256, scene.features(), options);
        IntersectBound bound = pipeline.measure_intersect_bound(kRays);
        EXPECT_NEAR(bound.hit_distance_sum, expected, 1e-6 * expected);  // float sums of at most 8 distances
        EXPECT_GT(bound.rays_per_s, 0.0);
        EXPECT_TRUE(std::isfinite(bound.rays_per_s));
    }
}

TEST(Profile, TableAndJsonReportTheTracingStagesAgainstTheBound) {
    RenderProfile p;
    p.kernel("intersect") = {"intersect", 3, 2'000'000, 0.5};                // 4 Mrays/s
    p.kernel("intersect_shadow") = {"intersect_shadow", 3, 1'000'000, 0.5};  // 2 Mrays/s
    p.intersect_bound_rays_per_s = 8e6;
    EXPECT_NE(format_profile_table(p).find("  intersect bound (ray-primitive tests only, no state traffic): 8.0 "
                                           "Mrays/s; intersect at 50% of it, intersect_shadow at 25%"),
              std::string::npos)
        << format_profile_table(p);
    nlohmann::json json = profile_json(p);
    EXPECT_EQ(json["intersect_bound_rays_per_s"], 8e6);
    EXPECT_EQ(json["of_intersect_bound"]["intersect"], 0.5);
    EXPECT_EQ(json["of_intersect_bound"]["intersect_shadow"], 0.25);

    p.kernels.erase(std::find_if(p.kernels.begin(), p.kernels.end(),
                                 [](const KernelProfile& k) { return k.name == "intersect_shadow"; }));
    // Shade traced the shadow rays: intersect alone.
    EXPECT_NE(format_profile_table(p).find("; intersect at 50% of it\n"), std::string::npos) << format_profile_table(p);
    EXPECT_FALSE(profile_json(p)["of_intersect_bound"].contains("intersect_shadow"));

    p.kernels.front().name = "intersect_and_shade";  // a CPU's one kernel for intersect and shade
    EXPECT_NE(format_profile_table(p).find("; intersect_and_shade at 50% of it (shading too)\n"), std::string::npos)
        << format_profile_table(p);
    EXPECT_EQ(profile_json(p)["of_intersect_bound"]["intersect_and_shade"], 0.5);
    EXPECT_FALSE(profile_json(p)["of_intersect_bound"].contains("intersect"));

    p.intersect_bound_rays_per_s = 0.0;  // not measured (the megakernel): not reported
    EXPECT_EQ(format_profile_table(p).find("intersect bound"), std::string::npos);
    EXPECT_FALSE(profile_json(p).contains("intersect_bound_rays_per_s"));
    EXPECT_FALSE(profile_json(p).contains("of_intersect_bound"));
}

// A row with declared bytes shows them, its GB/s (bytes x items / device
// time) and that as a fraction of the copy bandwidth; a row without shows none.
TEST(Profile, TableAndJsonReportStageBytesAgainstTheCopyBandwidth) {
    RenderProfile p;
    p.kernel("shade") = {"shade", 3, 2'000'000, 0.5, 100};  // 4e8 bytes/s
    p.kernel("accumulate") = {"accumulate", 1, 1000, 0.01};
    p.copy_bytes_per_s = 1.6e9;
    p.copy_buffer_bytes = std::uint64_t(64) << 20;
    const std::string table = format_profile_table(p);
    const std::size_t shade = table.find("  shade "), accumulate = table.find("  accumulate ");
    ASSERT_NE(shade, std::string::npos) << table;
    ASSERT_NE(accumulate, std::string::npos) << table;
    const std::string shade_row = table.substr(shade, table.find('\n', shade) - shade);
    EXPECT_NE(shade_row.find("   100     0.40     25%"), std::string::npos) << shade_row;
    const std::string accumulate_row = table.substr(accumulate, table.find('\n', accumulate) - accumulate);
    EXPECT_EQ(accumulate_row.find('%', accumulate_row.find('%') + 1), std::string::npos) << accumulate_row;
    EXPECT_NE(table.find("  copy bandwidth: 1.60 GB/s (bytes read + written; clEnqueueCopyBuffer of 64 MiB"),
              std::string::npos)
        << table;

    nlohmann::json json = profile_json(p);
    EXPECT_EQ(json["copy_bytes_per_s"], 1.6e9);
    EXPECT_EQ(json["copy_buffer_bytes"], std::uint64_t(64) << 20);
    EXPECT_EQ(json["kernels"][0]["bytes_per_item"], 100u);
    EXPECT_DOUBLE_EQ(json["kernels"][0]["bytes_per_s"].get<double>(), 4e8);
    EXPECT_DOUBLE_EQ(json["kernels"][0]["of_copy_bandwidth"].get<double>(), 0.25);
    EXPECT_FALSE(json["kernels"][1].contains("bytes_per_item"));
    EXPECT_FALSE(json["kernels"][1].contains("of_copy_bandwidth"));

    p.copy_bytes_per_s = 0.0;  // not measured (the megakernel): no fraction, no line
    EXPECT_EQ(format_profile_table(p).find("copy bandwidth"), std::string::npos);
    EXPECT_FALSE(profile_json(p).contains("copy_bytes_per_s"));
    EXPECT_FALSE(profile_json(p)["kernels"][0].contains("of_copy_bandwidth"));
    EXPECT_TRUE(profile_json(p)["kernels"][0].contains("bytes_per_s"));
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
    for (const char* text : {"kernel", "launches", "items", "device ms", "Mitems/s", "shade", "(between kernels)",
                             "extension rays by depth:", "shadow rays by depth:", "program build", "B/item", "GB/s",
                             "of copy", "copy bandwidth:"})
        EXPECT_NE(output.find(text), std::string::npos) << text << "\n" << output;

    nlohmann::json profile = read_json(dir / "profile.json"), stats = read_json(dir / "stats.json");
    std::map<std::string, nlohmann::json> kernels;
    for (const nlohmann::json& k : profile["kernels"]) kernels[k["name"]] = k;
    EXPECT_EQ(kernels["intersect_and_shade"]["items"], stats["extension_rays"]);  // a CPU device: one kernel
    EXPECT_EQ(kernels.count("intersect_shadow"), 0u);                             // and it traces the shadow rays
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
    const double copy = profile["copy_bytes_per_s"].get<double>();
    EXPECT_GT(copy, 0.0);
    for (const char* stage : {"generate", "intersect_and_shade"}) {
        const nlohmann::json& k = kernels[stage];
        const double bytes_per_s = k["bytes_per_s"].get<double>();
        EXPECT_NEAR(bytes_per_s, k["bytes_per_item"].get<double>() * k["items_per_s"].get<double>(), 1e-9 * bytes_per_s)
            << stage;
        EXPECT_NEAR(k["of_copy_bandwidth"].get<double>(), bytes_per_s / copy, 1e-9 * bytes_per_s / copy) << stage;
    }
    std::uint64_t by_depth = 0, shadow_by_depth = 0;
    for (std::uint64_t n : profile["extension_rays_by_depth"]) by_depth += n;
    for (std::uint64_t n : profile["shadow_rays_by_depth"]) shadow_by_depth += n;
    EXPECT_EQ(by_depth, stats["extension_rays"].get<std::uint64_t>());
    EXPECT_EQ(shadow_by_depth, stats["shadow_rays"].get<std::uint64_t>());
    EXPECT_GT(shadow_by_depth, 0u);

    // The bound, and the tracing stage's rays/s as a fraction of it, printed as in the JSON.
    double bound = profile["intersect_bound_rays_per_s"].get<double>();
    EXPECT_GT(bound, 0.0);
    EXPECT_TRUE(std::isfinite(bound));
    double printed_mrays, printed_intersect;
    std::size_t line = output.find("intersect bound");
    ASSERT_NE(line, std::string::npos) << output;
    ASSERT_EQ(std::sscanf(output.c_str() + line,
                          "intersect bound (ray-primitive tests only, no state traffic): %lf Mrays/s; "
                          "intersect_and_shade at %lf%% of it",
                          &printed_mrays, &printed_intersect),
              2)
        << output;
    EXPECT_NEAR(printed_mrays, bound * 1e-6, 0.05 + 1e-9);  // printed with one decimal
    double fraction = profile["of_intersect_bound"]["intersect_and_shade"].get<double>();
    EXPECT_NEAR(fraction, kernels["intersect_and_shade"]["items_per_s"].get<double>() / bound, 1e-9 * fraction);
    EXPECT_NEAR(printed_intersect, 100.0 * fraction, 0.5 + 1e-9);  // printed as a whole percentage
    EXPECT_FALSE(profile["of_intersect_bound"].contains("intersect_shadow"));
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
