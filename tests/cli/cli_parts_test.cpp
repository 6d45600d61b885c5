// The CLI's pieces without the binary: progress output, the summary line and
// stats JSON, overrides, and the mapping from errors to exit codes.
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <thread>
#include <vector>

#include "cli/backends.h"
#include "cli/errors.h"
#include "cli/options.h"
#include "cli/progress.h"
#include "cli/scene_file.h"
#include "cli/summary.h"
#include "core/atomic_file.h"
#include "opencl/device.h"
#include "wavefront/intersector_choice.h"

namespace wp::cli {
namespace {

// A checkpoint's estimator names what traced its rays: Embree and the BVH
// may decide a near tie otherwise, so their films must not mix.
TEST(EstimatorName, NamesTheIntersector) {
    Scene with_mesh;
    with_mesh.meshes.push_back({});
    with_mesh.meshes.back().positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    with_mesh.meshes.back().triangles = {{0, 1, 2}};
    ASSERT_TRUE(with_mesh.features().meshes);
    auto name = [&](const char* backend, const char* intersector, const char* precision = "float") {
        BackendOptions options;
        options.name = backend;
        options.intersector = intersector;
        options.precision = precision;
        return estimator_name(options, with_mesh);
    };
    EXPECT_EQ(name("wavefront", "bvh"), "opencl");
    EXPECT_EQ(name("megakernel", ""), "opencl");
    EXPECT_EQ(name("wavefront", "embree"), "opencl-embree");
    EXPECT_EQ(name("reference", "embree"), "reference-embree");
    EXPECT_EQ(name("reference", "bvh"), "reference-float");
    EXPECT_EQ(name("reference", ""), "reference-embree");  // the reference's default in float
    EXPECT_EQ(name("reference", "", "double"), "reference-double");
    // The wavefront's default: the device's (on this CPU device, Embree for a scene with meshes).
    bool embree = default_intersector(choose_device(""), with_mesh.features()).intersector == Intersector::Embree;
    EXPECT_EQ(name("wavefront", ""), embree ? "opencl-embree" : "opencl");
}

TEST(Progress, DurationFormats) {
    EXPECT_EQ(format_duration(0.0), "0s");
    EXPECT_EQ(format_duration(59.4), "59s");
    EXPECT_EQ(format_duration(125.0), "2m05s");
    EXPECT_EQ(format_duration(3600.0 + 120.0 + 30.0), "1h02m");
    EXPECT_EQ(format_duration(-3.0), "0s");
}

TEST(Progress, BarShowsFillPercentAndEta) {
    EXPECT_EQ(format_progress_bar(0.25, 10.0, 30.0), "[#######-----------------------]  25.0%  elapsed 10s  ETA 30s");
    EXPECT_EQ(format_progress_bar(0.0, 1.0, -1.0), "[------------------------------]   0.0%  elapsed 1s  ETA --");
    EXPECT_EQ(format_progress_bar(1.0, 61.0, 0.0), "[##############################] 100.0%  elapsed 1m01s  ETA 0s");
}

TEST(Progress, LineShowsPercentAndEta) {
    EXPECT_EQ(format_progress_line(0.4, 20.0, 30.0), "wavepath: 40% done, 20s elapsed, ETA 30s");
    EXPECT_EQ(format_progress_line(0.0, 20.0, -1.0), "wavepath: 0% done, 20s elapsed, ETA --");
    EXPECT_EQ(format_progress_line(0.4, 20.0, 30.0, "25.6/64 spp"),
              "wavepath: 40% done, 25.6/64 spp, 20s elapsed, ETA 30s");
    EXPECT_EQ(format_progress_bar(0.25, 10.0, 30.0, "16.0/64 spp"),
              "[#######-----------------------]  25.0%  16.0/64 spp  elapsed 10s  ETA 30s");
}

TEST(Progress, EtaExtrapolatesTheRateSinceTheFirstSamples) {
    // 1e-4 done when the first samples came in (after the kernel build and
    // the first launches), 10% 1 s later: 0.0999 per second, 9 s to go; from
    // the start of the render 11 s ago it would be 99 s.
    EXPECT_NEAR(estimate_eta(0.1, 1e-4, 1.0), 0.9 / 0.0999, 1e-9);
    EXPECT_EQ(estimate_eta(1e-4, 1e-4, 5.0), -1.0);  // no samples since the first: nothing measured
    EXPECT_EQ(estimate_eta(0.0, 0.0, 5.0), -1.0);
    EXPECT_EQ(estimate_eta(0.5, 0.1, 0.0), -1.0);
}

TEST(Progress, EtaClockStartsAtTheFirstSamples) {
    std::ostringstream out;
    ProgressReporter reporter(ProgressStyle::Lines, out, ProgressReporter::Clock::duration::zero());
    const Progress progress = reporter.callback();
    progress.announce("building the kernels");
    std::this_thread::sleep_for(std::chrono::milliseconds(2000));  // the "build"
    progress.report(0.0);                                          // sampling starts: nothing shown
    progress.report(0.1);                                          // the first samples: the ETA's clock starts
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    progress.report(0.5);
    const std::string text = out.str();
    EXPECT_EQ(text.rfind("wavepath: building the kernels\n", 0), 0u) << text;
    EXPECT_EQ(text.find("wavepath: 0% done"), std::string::npos) << text;
    EXPECT_NE(text.find("wavepath: 10% done, 2s elapsed, ETA --\n"), std::string::npos) << text;
    // 40% more in ~0.1 s: ETA 0s (1s on a very busy machine); extrapolating
    // the whole elapsed time, build included, would give 2s or more.
    const std::size_t line = text.find("wavepath: 50% done, 2s elapsed, ETA ");
    ASSERT_NE(line, std::string::npos) << text;
    const std::string eta = text.substr(line + 36, text.find('\n', line) - line - 36);
    EXPECT_TRUE(eta == "0s" || eta == "1s") << text;
}

TEST(Progress, LinesStyleWritesOneLinePerUpdateAtZeroInterval) {
    std::ostringstream out;
    {
        ProgressReporter reporter(ProgressStyle::Lines, out, ProgressReporter::Clock::duration::zero());
        reporter.update(0.5);
        reporter.update(0.2);  // out of order: the larger fraction stands
        reporter.finish();
    }
    const std::string text = out.str();
    EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 2) << text;
    EXPECT_EQ(text.find("wavepath: 20%"), std::string::npos) << text;
    EXPECT_EQ(text.rfind("wavepath: 50% done", 0), 0u) << text;
}

TEST(Progress, LinesAreThrottled) {
    std::ostringstream out;
    ProgressReporter reporter(ProgressStyle::Lines, out, std::chrono::hours(1));
    for (int i = 1; i <= 100; ++i) reporter.update(i / 100.0);
    EXPECT_TRUE(out.str().empty()) << out.str();  // the first line is due after one interval
}

TEST(Progress, BarRedrawsInPlaceAndEndsItsLine) {
    std::ostringstream out;
    {
        ProgressReporter reporter(ProgressStyle::Bar, out, ProgressReporter::Clock::duration::zero());
        reporter.update(0.5);
        reporter.finish();
    }
    const std::string text = out.str();
    EXPECT_EQ(text.front(), '\r');
    EXPECT_NE(text.find(" 50.0%"), std::string::npos) << text;
    EXPECT_NE(text.find("100.0%"), std::string::npos) << text;
    EXPECT_EQ(text.back(), '\n');
    EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 1) << text;
}

TEST(Progress, UnfinishedBarEndsItsLineSoAnErrorStartsOnANewOne) {
    std::ostringstream out;
    {
        ProgressReporter reporter(ProgressStyle::Bar, out, ProgressReporter::Clock::duration::zero());
        reporter.update(0.3);
    }
    EXPECT_EQ(out.str().back(), '\n');
}

TEST(Progress, SilentWritesNothing) {
    std::ostringstream out;
    {
        ProgressReporter reporter(ProgressStyle::Silent, out, ProgressReporter::Clock::duration::zero());
        reporter.update(0.5);
        reporter.finish();
    }
    EXPECT_TRUE(out.str().empty());
    EXPECT_EQ(choose_progress_style(true), ProgressStyle::Silent);
}

TEST(Progress, ConcurrentUpdatesAreSafe) {
    std::ostringstream out;
    ProgressReporter reporter(ProgressStyle::Lines, out, ProgressReporter::Clock::duration::zero());
    const Progress progress = reporter.callback();
    std::vector<std::thread> threads;
    for (int t = 0; t < 4; ++t)
        threads.emplace_back([&, t] {
            for (int i = 0; i < 250; ++i) progress.report((t * 250 + i + 1) / 1000.0);
        });
    for (std::thread& thread : threads) thread.join();
    // Each line is whole (no interleaving): every line starts with the prefix.
    std::istringstream lines(out.str());
    int count = 0;
    for (std::string line; std::getline(lines, line); ++count) EXPECT_EQ(line.rfind("wavepath: ", 0), 0u) << line;
    EXPECT_GT(count, 0);
}

RunSummary example_summary() {
    RunSummary summary;  // by name: the summary's fields grow with the features that report in it
    summary.backend = "reference";
    summary.output_path = "out/room.png";
    summary.width = 640;
    summary.height = 480;
    summary.spp = summary.spp_min = summary.spp_max = 16;
    summary.estimator = "reference-embree";
    summary.stats.time_s = 2.0;
    summary.stats.samples = 640ull * 480 * 16;  // 4915200
    summary.stats.extension_rays = 12'000'000;
    summary.stats.shadow_rays = 5'000'000;
    summary.stats.add_nonfinite({1, 0, 2});
    return summary;
}

TEST(Progress, CountDoneFollowsThePlan) {
    EXPECT_EQ(format_count_done({0.0, 64.0, 0.0}, 0.25), "16.0/64 spp");
    EXPECT_EQ(format_count_done({8.0, 16.0, 0.0}, 0.5), "12.0/16 spp");  // resumed at 8 spp
    EXPECT_EQ(format_count_done({}, 0.5), "");
    EXPECT_EQ(format_count_done({0.0, 500.0, 0.0, "shapes", 0}, 0.24), "120/500 shapes");
}

// A scene's load shows the shapes read: one line per shape at zero interval,
// the last at the whole count, for either reader (the XML's sphere and
// rectangle are two shapes; cornell.json's count comes from its file).
TEST(Progress, SceneLoadShowsTheShapesRead) {
    const std::string cornell = WAVEPATH_SOURCE_DIR "/scenes/cornell.json";
    std::ifstream file(cornell);
    const std::size_t cornell_shapes = nlohmann::json::parse(file).at("shapes").size();
    const std::vector<std::pair<std::string, std::size_t>> scenes = {
        {cornell, cornell_shapes}, {WAVEPATH_SOURCE_DIR "/scenes/test/mitsuba/filters.xml", 2}};
    for (const auto& [path, shapes] : scenes) {
        std::ostringstream out;
        ProgressReporter reporter(ProgressStyle::Lines, out, ProgressReporter::Clock::duration::zero());
        load_scene_file(path, {}, {}, nullptr, &reporter);
        const std::string text = out.str();
        EXPECT_EQ(std::size_t(std::count(text.begin(), text.end(), '\n')), shapes) << path << "\n" << text;
        const std::string whole = std::to_string(shapes) + "/" + std::to_string(shapes) + " shapes, ";
        EXPECT_NE(text.find("wavepath: 100% done, " + whole), std::string::npos) << path << "\n" << text;
    }
}

TEST(Summary, LineHasTimeRatesNonfiniteAndPath) {
    EXPECT_EQ(format_summary_line(example_summary()),
              "wavepath: wrote out/room.png (640x480, 16 spp, reference) in 2.000 s: 2.458 Msamples/s, "
              "extension 6.00 Mrays/s, shadow 2.50 Mrays/s, 3 non-finite values (emission 1, direct 0, scatter 2)");
}

TEST(Summary, LineLeavesOutTheStagesWhenNothingWasDropped) {
    RunSummary summary = example_summary();
    summary.stats.nonfinite_by_stage = {};
    summary.stats.nonfinite = 0;
    EXPECT_TRUE(format_summary_line(summary).ends_with(", 0 non-finite values")) << format_summary_line(summary);
}

TEST(Summary, LineSaysWhatAnEarlyStopLeftThePixels) {
    RunSummary summary = example_summary();
    summary.spp_min = 12;
    summary.spp_max = 13;
    summary.stopped = "time budget";
    EXPECT_NE(format_summary_line(summary).find("(640x480, 12-13 of 16 spp, stopped: time budget, reference)"),
              std::string::npos)
        << format_summary_line(summary);
    summary.spp_max = 12;
    summary.stopped = "interrupted";
    EXPECT_NE(format_summary_line(summary).find("(640x480, 12 of 16 spp, stopped: interrupted, reference)"),
              std::string::npos)
        << format_summary_line(summary);
}

TEST(Summary, SeveralRanksAreNamedWithWhatEachRendered) {
    RunSummary summary = example_summary();
    summary.samples_per_rank = {1638400, 1638400, 1638400};
    summary.busy_s_per_rank = {1.5, 1.25, 1.75};
    EXPECT_NE(format_summary_line(summary).find("(640x480, 16 spp, reference, 3 ranks)"), std::string::npos)
        << format_summary_line(summary);
    const nlohmann::json stats = stats_json(summary);
    EXPECT_EQ(stats["ranks"], 3);
    EXPECT_EQ(stats["samples_per_rank"], (nlohmann::json{1638400u, 1638400u, 1638400u}));
    EXPECT_EQ(stats["render_s_per_rank"], (nlohmann::json{1.5, 1.25, 1.75}));
}

// A backend that --backend auto chose is named with the situation that
// decided; --stats-json has the whole explanation.
TEST(Summary, AutoChoiceIsNamedWithItsSituation) {
    RunSummary summary = example_summary();
    summary.backend = "megakernel";
    summary.backend_choice = BackendChoice{"megakernel", "CPU device, no meshes", "2x the wavefront's"};
    summary.samples_per_rank = {2457600, 2457600};
    EXPECT_NE(format_summary_line(summary).find("(640x480, 16 spp, megakernel (auto: CPU device, no meshes), 2 ranks)"),
              std::string::npos)
        << format_summary_line(summary);
    const nlohmann::json stats = stats_json(summary);
    EXPECT_EQ(stats["backend"], "megakernel");
    EXPECT_EQ(stats["backend_choice"], "auto: CPU device, no meshes: 2x the wavefront's");
    EXPECT_TRUE(stats_json(example_summary())["backend_choice"].is_null());
}

TEST(Summary, StatsJsonHasTheFiguresAndRates) {
    const nlohmann::json stats = stats_json(example_summary());
    EXPECT_EQ(stats["backend"], "reference");
    EXPECT_EQ(stats["estimator"], "reference-embree");
    EXPECT_EQ(stats["width"], 640);
    EXPECT_EQ(stats["height"], 480);
    EXPECT_EQ(stats["spp"], 16);
    EXPECT_EQ(stats["spp_done_min"], 16u);
    EXPECT_EQ(stats["spp_done_max"], 16u);
    EXPECT_EQ(stats["stopped"], "done");
    EXPECT_TRUE(stats["error_estimate"].is_null());
    EXPECT_EQ(stats["ranks"], 1);
    EXPECT_EQ(stats["samples_per_rank"], (nlohmann::json{4915200u}));
    EXPECT_EQ(stats["time_s"], 2.0);
    EXPECT_EQ(stats["samples"], 4915200u);
    EXPECT_EQ(stats["samples_per_s"], 2457600.0);
    EXPECT_EQ(stats["extension_rays"], 12000000u);
    EXPECT_EQ(stats["extension_rays_per_s"], 6e6);
    EXPECT_EQ(stats["shadow_rays"], 5000000u);
    EXPECT_EQ(stats["shadow_rays_per_s"], 2.5e6);
    EXPECT_EQ(stats["nonfinite"], 3u);
    EXPECT_EQ(stats["nonfinite_by_stage"], (nlohmann::json{{"emission", 1u}, {"direct", 0u}, {"scatter", 2u}}));
}

// --adaptive: the line and the JSON add the mean spp and the pixels that stopped early.
TEST(Summary, AdaptiveAddsTheMeanSamplesAndThePixelsThatStoppedEarly) {
    RunSummary summary = example_summary();
    EXPECT_TRUE(stats_json(summary)["adaptive"].is_null());
    EXPECT_EQ(format_summary_line(summary).find("adaptive"), std::string::npos);
    summary.adaptive = true;
    summary.spp_mean = 9.25;
    summary.stopped_early = 0.6875;
    EXPECT_TRUE(format_summary_line(summary).ends_with(", adaptive: mean 9.2 spp, 68.8% of pixels stopped early"))
        << format_summary_line(summary);
    EXPECT_EQ(stats_json(summary)["adaptive"], (nlohmann::json{{"spp_mean", 9.25}, {"stopped_early", 0.6875}}));
}

TEST(Summary, ZeroTimeGivesZeroRatesNotInfinity) {
    RunSummary summary = example_summary();
    summary.stats.time_s = 0.0;
    EXPECT_EQ(stats_json(summary)["samples_per_s"], 0.0);
}

TEST(Overrides, ReplaceOnlyWhatIsGiven) {
    Scene scene;
    scene.camera.width = 32;
    scene.camera.height = 24;
    scene.render = RenderSettings{.spp = 16, .max_depth = 8, .rr_depth = 3, .seed = 5};
    RenderOverrides overrides;
    overrides.spp = 2;
    overrides.height = 10;
    overrides.seed = 4294967295;
    apply_overrides(overrides, scene);
    EXPECT_EQ(scene.render.spp, 2);
    EXPECT_EQ(scene.render.max_depth, 8);
    EXPECT_EQ(scene.render.rr_depth, 3);
    EXPECT_EQ(scene.render.seed, 4294967295u);
    EXPECT_EQ(scene.camera.width, 32);
    EXPECT_EQ(scene.camera.height, 10);
}

TEST(Overrides, NeeAndHemisphere) {
    Scene scene;
    RenderOverrides overrides;
    overrides.nee = "off";
    overrides.hemisphere = "uniform";
    apply_overrides(overrides, scene);
    EXPECT_FALSE(scene.render.nee);
    EXPECT_EQ(scene.render.hemisphere, Hemisphere::Uniform);
    overrides.nee = "on";
    overrides.hemisphere = "cosine";
    apply_overrides(overrides, scene);
    EXPECT_TRUE(scene.render.nee);
    EXPECT_EQ(scene.render.hemisphere, Hemisphere::Cosine);
}

TEST(Overrides, PixelLimitAppliesToTheCombination) {
    Scene scene;
    scene.camera.width = 16384;
    scene.camera.height = 2;
    RenderOverrides overrides;
    overrides.height = 16384;
    EXPECT_THROW(apply_overrides(overrides, scene), UsageError);
}

int exit_code_of(const std::exception_ptr& error) {
    ::testing::internal::CaptureStderr();
    const int code = report_error(error);
    const std::string printed = ::testing::internal::GetCapturedStderr();
    EXPECT_EQ(std::count(printed.begin(), printed.end(), '\n'), 1) << printed;
    EXPECT_EQ(printed.rfind("wavepath: error: ", 0), 0u) << printed;
    return code;
}

TEST(Errors, EachKindHasItsExitCode) {
    EXPECT_EQ(exit_code_of(std::make_exception_ptr(UsageError("u"))), kExitUsage);
    EXPECT_EQ(exit_code_of(std::make_exception_ptr(SceneError("s"))), kExitScene);
    EXPECT_EQ(exit_code_of(std::make_exception_ptr(OutputError("o"))), kExitOutput);
    EXPECT_EQ(exit_code_of(std::make_exception_ptr(std::runtime_error("r"))), kExitRuntime);
    EXPECT_EQ(exit_code_of(std::make_exception_ptr(std::bad_alloc())), kExitRuntime);
    EXPECT_EQ(exit_code_of(std::make_exception_ptr(42)), kExitRuntime);
}

TEST(Errors, MultiLineMessagesAreFoldedIntoOneLine) {
    ::testing::internal::CaptureStderr();
    report_error(std::make_exception_ptr(std::runtime_error("build failed\nkernel.cl:3: error\n")));
    EXPECT_EQ(::testing::internal::GetCapturedStderr(), "wavepath: error: build failed; kernel.cl:3: error\n");
}

std::string printed_line(const std::string& message) {
    ::testing::internal::CaptureStderr();
    report_error(std::make_exception_ptr(SceneError(message)));
    return ::testing::internal::GetCapturedStderr();
}

TEST(Errors, ControlCharactersAndInvalidUtf8AreEscaped) {
    // A terminal escape, a carriage return and a tab from a file name or a file's contents.
    EXPECT_EQ(printed_line("a\x1b[31mb\rc\td"), "wavepath: error: a\\x1b[31mb\\x0dc\\x09d\n");
    // A stray continuation byte, a truncated sequence, an overlong '/', a UTF-16 surrogate, DEL.
    EXPECT_EQ(printed_line("\x80 \xc3 \xc0\xaf \xed\xa0\x80 \x7f"),
              "wavepath: error: \\x80 \\xc3 \\xc0\\xaf \\xed\\xa0\\x80 \\x7f\n");
    // Valid UTF-8 of 2, 3 and 4 bytes stays as it is.
    EXPECT_EQ(printed_line("sc\xc3\xa8ne \xe2\x82\xac \xf0\x9f\x90\x87"),
              "wavepath: error: sc\xc3\xa8ne \xe2\x82\xac \xf0\x9f\x90\x87\n");
}

}  // namespace
}  // namespace wp::cli
