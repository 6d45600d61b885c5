// The wavepath binary end to end: exit codes, one-line errors, no output
// file after any failure, flags overriding the scene, and --stats-json.
// Scenes are 8x8 at 1-4 spp so that every run takes milliseconds.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "cli/run_wavepath.h"
#include "image/image_io.h"
#include "reference/reference_renderer.h"
#include "scene/scene.h"
#include "support/scoped_env.h"

namespace wp::test {
namespace {

using nlohmann::json;

// A small valid scene: a diffuse sphere on a plane under a quad light.
json base_scene() {
    return json::parse(R"({
      "camera": {"position": [0, 1, 4], "look_at": [0, 0.5, 0], "fov_y": 45, "width": 8, "height": 8},
      "render": {"spp": 2, "max_depth": 4, "rr_depth": 2, "seed": 7},
      "materials": {
        "white": {"type": "diffuse", "albedo": [0.6, 0.6, 0.6]},
        "lamp": {"type": "emitter", "radiance": [5, 5, 5]}
      },
      "shapes": [
        {"type": "sphere", "center": [0, 0.5, 0], "radius": 0.5, "material": "white"},
        {"type": "plane", "point": [0, 0, 0], "normal": [0, 1, 0], "material": "white"},
        {"type": "quad", "corner": [-0.5, 2, -0.5], "edge1": [1, 0, 0], "edge2": [0, 0, 1], "material": "lamp"}
      ]
    })");
}

json patched_scene(const std::string& merge_patch) {
    json scene = base_scene();
    scene.merge_patch(json::parse(merge_patch));
    return scene;
}

int count_lines(const std::string& text) { return static_cast<int>(std::count(text.begin(), text.end(), '\n')); }

std::vector<std::string> split_lines(const std::string& text) {
    std::vector<std::string> lines;
    std::istringstream stream(text);
    for (std::string line; std::getline(stream, line);) lines.push_back(line);
    return lines;
}

class CliTest : public ::testing::Test {
 protected:
    // Scenes and outputs live in separate directories, so that "no output
    // file" means the output directory is empty, temporaries included.
    std::string write_scene(const std::string& text) {
        const std::string path = scenes_ / "scene.json";
        write_text(path, text);
        return path;
    }
    CommandResult run(const std::vector<std::string>& args) { return run_wavepath(args, scenes_.path()); }
    CommandResult render(const std::string& scene_text, std::vector<std::string> extra = {}) {
        std::vector<std::string> args{"render", write_scene(scene_text), "-o", output_path()};
        args.insert(args.end(), extra.begin(), extra.end());
        return run(args);
    }
    std::string output_path() const { return outputs_ / "out.exr"; }

    void expect_failure(const CommandResult& result, int exit_code, const std::string& message_start) {
        EXPECT_EQ(result.exit_code, exit_code) << result.err;
        EXPECT_EQ(count_lines(result.err), 1) << result.err;
        EXPECT_EQ(result.err.rfind("wavepath: error: " + message_start, 0), 0u) << result.err;
        EXPECT_TRUE(outputs_.entries().empty()) << "left in the output directory: " << outputs_.entries().front();
    }

    TempDirectory scenes_{"scenes"}, outputs_{"outputs"};
};

// ---- scene errors: exit 3; malformed scenes and mesh files are the corpus's
// (tests/corpus/bad, bad_input_corpus_test.cpp) ----

TEST_F(CliTest, MissingSceneFileIsASceneError) {
    const CommandResult result = run({"render", scenes_ / "absent.json", "-o", output_path()});
    expect_failure(result, 3, scenes_ / "absent.json" + ": ");
}

// ---- usage errors: exit 2 ----

struct UsageCase {
    const char* name;
    std::vector<std::string> flags;
    const char* message;  // start of the message after "wavepath: error: "
};

const UsageCase kUsageErrors[] = {
    {"ZeroSpp", {"--spp", "0"}, "--spp: must be in [1, 1048576], got 0"},
    {"SppBeyondLimit", {"--spp", "1048577"}, "--spp: must be in [1, 1048576], got 1048577"},
    {"SppNotANumber", {"--spp", "many"}, "--spp: must be an integer in [1, 1048576], got many"},
    {"SppFraction", {"--spp", "2.5"}, "--spp: must be an integer"},
    {"ZeroWidth", {"--width", "0"}, "--width: must be in [1, 16384], got 0"},
    {"HeightTooLarge", {"--height", "16385"}, "--height: must be in [1, 16384], got 16385"},
    {"TooManyPixels", {"--width", "16384", "--height", "16384"}, "--width/--height: width * height must be <= "},
    {"NegativeMaxDepth", {"--max-depth", "-1"}, "--max-depth: must be in [0, 100000], got -1"},
    {"NegativeRrDepth", {"--rr-depth", "-2"}, "--rr-depth: must be in [0, 2147483647], got -2"},
    {"SeedBeyond32Bits", {"--seed", "4294967296"}, "--seed: must be in [0, 4294967295], got 4294967296"},
    {"NegativeThreads", {"--threads", "-1"}, "--threads: must be in [0, 4096], got -1"},
    {"ZeroMeshImportMemory", {"--mesh-import-memory", "0"}, "--mesh-import-memory: must be in [1, 1073741824], got 0"},
    {"ZeroMeshImportCpu", {"--mesh-import-cpu", "0"}, "--mesh-import-cpu: must be in [1, 1000000], got 0"},
    {"ZeroMeshImportTime",
     {"--mesh-import-time", "0"},
     "--mesh-import-time: must be a number in [0.001, 1e+06], got 0"},
    {"NanMeshImportTime",
     {"--mesh-import-time", "nan"},
     "--mesh-import-time: must be a number in [0.001, 1e+06], got nan"},
    {"NanTime", {"--time", "nan"}, "--time: must be a number in [0.001, 1e+09], got nan"},
    {"NanCheckpointEvery",
     {"--checkpoint-every", "nan"},
     "--checkpoint-every: must be a number in [0, 1e+09], got nan"},
    {"NanTargetError", {"--target-error", "nan"}, "--target-error: must be a number in [1e-09, 1], got nan"},
    {"NanAdaptive", {"--adaptive", "nan"}, "--adaptive: must be a number in [1e-09, 1e+09], got nan"},
    {"UnknownBackend", {"--backend", "quantum"}, "--backend: "},
    {"UnknownPrecision", {"--precision", "half"}, "--precision: "},
    {"UnknownIntersector", {"--intersector", "optix"}, "--intersector: "},
    {"EmbreeInDouble",
     {"--backend", "reference", "--precision", "double", "--intersector", "embree"},
     "--intersector embree: Embree traces in float only"},
    {"EmbreeOnTheMegakernel",
     {"--backend", "megakernel", "--intersector", "embree"},
     "--intersector embree: the megakernel traces with its OpenCL BVH"},
    {"UnknownNee", {"--nee", "maybe"}, "--nee: "},
    {"UnknownHemisphere", {"--hemisphere", "cos"}, "--hemisphere: "},
    {"UnknownFlag", {"--sp", "4"}, "The following argument"},
    {"FlagWithoutValue", {"--spp"}, "--spp"},
    {"UnknownIntegrator", {"--integrator", "bdpt"}, "--integrator: "},
    {"PhotonsWithoutSppm", {"--photons", "100"}, "--photons: applies to the sppm integrator only"},
    {"AlphaWithoutSppm", {"--alpha", "0.5"}, "--alpha: applies to the sppm integrator only"},
    {"ZeroPhotons", {"--integrator", "sppm", "--photons", "0"}, "--photons: must be in [1, 1073741824], got 0"},
    {"AlphaAboveOne", {"--integrator", "sppm", "--alpha", "1.5"}, "--alpha: "},
    {"SppmOnTheMegakernel", {"--integrator", "sppm", "--backend", "megakernel"}, "--backend megakernel: "},
    {"SppmWithTargetError",
     {"--integrator", "sppm", "--target-error", "0.1"},
     "--target-error: does not apply to the sppm integrator"},
    {"SppmAdaptive",
     {"--integrator", "sppm", "--adaptive", "0.1"},
     "--adaptive: does not apply to the sppm integrator"},
    {"SppmWithEmbreeOnTheWavefront",
     {"--integrator", "sppm", "--intersector", "embree"},
     "--intersector embree: the sppm integrator's photon stages trace on the device"},
};

void PrintTo(const UsageCase& c, std::ostream* out) { *out << c.name; }

class UsageErrorTest : public CliTest, public ::testing::WithParamInterface<UsageCase> {};

TEST_P(UsageErrorTest, OneLineExitCode2AndNoOutput) {
    const UsageCase& c = GetParam();
    expect_failure(render(base_scene().dump(), c.flags), 2, c.message);
}

INSTANTIATE_TEST_SUITE_P(Cli, UsageErrorTest, ::testing::ValuesIn(kUsageErrors),
                         [](const auto& info) { return std::string(info.param.name); });

TEST_F(CliTest, MissingOutputFlagIsAUsageError) {
    expect_failure(run({"render", write_scene(base_scene().dump())}), 2, "--output is required");
}

TEST_F(CliTest, MissingSubcommandIsAUsageError) { expect_failure(run({}), 2, "a subcommand is required"); }

TEST_F(CliTest, UnknownSubcommandIsAUsageError) { expect_failure(run({"paint"}), 2, "The following argument"); }

// ---- output errors: exit 4, found before rendering ----

TEST_F(CliTest, UnsupportedExtensionIsAnOutputError) {
    const CommandResult result = run({"render", write_scene(base_scene().dump()), "-o", outputs_ / "out.tga"});
    expect_failure(result, 4, "cannot write " + outputs_ / "out.tga" + ": unsupported image extension '.tga'");
}

TEST_F(CliTest, MissingOutputDirectoryIsAnOutputError) {
    const std::string target = outputs_ / "missing/out.png";
    const CommandResult result = run({"render", write_scene(base_scene().dump()), "-o", target});
    expect_failure(result, 4, "cannot write " + target + ": directory ");
}

TEST_F(CliTest, UnwritableStatsPathFailsBeforeRendering) {
    const std::string stats = outputs_ / "missing/stats.json";
    expect_failure(render(base_scene().dump(), {"--stats-json", stats}), 4, "cannot write " + stats + ": directory ");
}

TEST_F(CliTest, OutputErrorComesBeforeSceneErrors) {
    // An unusable output path is reported without even reading the scene.
    const CommandResult result = run({"render", scenes_ / "absent.json", "-o", outputs_ / "out.bmp"});
    expect_failure(result, 4, "cannot write ");
}

TEST_F(CliTest, AMissingImageLibraryFailsBeforeRendering) {
    // OpenImageIO is a module opened on the first image (image/image_codec.h).
    const ScopedEnv module("WAVEPATH_IMAGE_MODULE", outputs_ / "absent.so");
    const std::string target = outputs_ / "out.png";
    const CommandResult result = run({"render", write_scene(base_scene().dump()), "-o", target});
    expect_failure(result, 4,
                   "cannot write " + target + ": cannot load the image library: " + outputs_ / "absent.so" +
                       ": No such file or directory");
    EXPECT_EQ(result.out, "");
}

TEST_F(CliTest, AnImageLibraryThatDoesNotLoadIsAnOutputErrorAfterTheRender) {
    const std::string broken = scenes_ / "broken.so";
    write_text(broken, "not a shared library");
    const ScopedEnv module("WAVEPATH_IMAGE_MODULE", broken);
    const std::string target = outputs_ / "out.png";
    // -q: a cold kernel cache would add its note and progress lines before the error.
    expect_failure(run({"render", write_scene(base_scene().dump()), "-o", target, "-q"}), 4,
                   "cannot write " + target + ": cannot load the image library: " + broken + ": ");
}

// ---- successful runs ----

TEST_F(CliTest, RenderWritesImageSummaryAndNothingElse) {
    const CommandResult result = render(base_scene().dump());
    ASSERT_EQ(result.exit_code, 0) << result.err;
    EXPECT_EQ(outputs_.entries(), std::vector<std::string>{"out.exr"});
    const Image image = read_image(output_path());
    EXPECT_EQ(image.width, 8);
    EXPECT_EQ(image.height, 8);
    // The lamp lights the scene: some pixel is bright, none is negative.
    EXPECT_GT(*std::max_element(image.rgb.begin(), image.rgb.end()), 0.1f);
    EXPECT_GE(*std::min_element(image.rgb.begin(), image.rgb.end()), 0.0f);
    // stderr is not a terminal here: no bar. A cold kernel build says so, and
    // on a busy machine can outlast the 5 s between progress lines, so those
    // lines may come first; the summary is the last line.
    const std::vector<std::string> lines = split_lines(result.err);
    ASSERT_FALSE(lines.empty());
    for (std::size_t i = 0; i + 1 < lines.size(); ++i)
        EXPECT_TRUE(lines[i].find("% done, ") != std::string::npos ||
                    lines[i].rfind("wavepath: building the kernels for this scene", 0) == 0)
            << "not a progress line: " << lines[i];
    // The default backend is auto's choice, named with the situation that decided it.
    EXPECT_EQ(lines.back().rfind("wavepath: wrote " + output_path() + " (8x8, 2 spp, ", 0), 0u) << result.err;
    EXPECT_NE(lines.back().find(" (auto: "), std::string::npos) << result.err;
    EXPECT_NE(lines.back().find(", no meshes)) in "), std::string::npos) << result.err;
    EXPECT_NE(result.err.find("Mrays/s"), std::string::npos) << result.err;
    EXPECT_TRUE(result.out.empty()) << result.out;
}

TEST_F(CliTest, QuietPrintsNothing) {
    const CommandResult result = render(base_scene().dump(), {"--quiet"});
    ASSERT_EQ(result.exit_code, 0) << result.err;
    EXPECT_TRUE(result.err.empty()) << result.err;
    EXPECT_TRUE(result.out.empty()) << result.out;
}

TEST_F(CliTest, StatsJsonHasConsistentFigures) {
    const std::string stats_path = outputs_ / "stats.json";
    const CommandResult result =
        render(base_scene().dump(), {"--width", "6", "--height", "4", "--spp", "3", "--stats-json", stats_path});
    ASSERT_EQ(result.exit_code, 0) << result.err;
    EXPECT_EQ(outputs_.entries(), (std::vector<std::string>{"out.exr", "stats.json"}));

    const json stats = json::parse(read_text(stats_path));
    for (const char* key : {"backend", "width", "height", "spp", "time_s", "samples", "samples_per_s", "extension_rays",
                            "shadow_rays", "nonfinite"})
        EXPECT_TRUE(stats.contains(key)) << key;
    EXPECT_TRUE(stats["backend"] == "wavefront" || stats["backend"] == "megakernel") << stats["backend"];
    EXPECT_EQ(stats["backend_choice"].get<std::string>().rfind("auto: ", 0), 0u);  // the default backend
    EXPECT_EQ(stats["width"], 6);
    EXPECT_EQ(stats["height"], 4);
    EXPECT_EQ(stats["spp"], 3);
    EXPECT_EQ(stats["samples"], 6 * 4 * 3);
    EXPECT_EQ(stats["nonfinite"], 0);
    EXPECT_EQ(stats["nonfinite_by_stage"], (json{{"emission", 0}, {"direct", 0}, {"scatter", 0}}));
    const double time_s = stats["time_s"];
    ASSERT_GT(time_s, 0.0);
    EXPECT_NEAR(stats["samples_per_s"].get<double>(), 72.0 / time_s, 1e-9 * 72.0 / time_s);
    // Every sample traces a camera ray; every shadow ray leaves a vertex an
    // extension ray found, at most one per vertex.
    const std::uint64_t extension = stats["extension_rays"], shadow = stats["shadow_rays"];
    EXPECT_GE(extension, 72u);
    EXPECT_GT(shadow, 0u);
    EXPECT_LE(shadow, extension);
}

// SPPM on the reference (no kernel build): the photons' figures, from the
// 2 iterations of 5000 photons asked for. Photons deposit from their second
// hit on (the camera pass takes direct light), which about 1 in 100 does
// near this scene's 64 visible points: 83-157 deposits over seeds and
// samplers, so none at all has probability below e^-80.
TEST_F(CliTest, StatsJsonHasSppmFigures) {
    const std::string stats_path = outputs_ / "stats.json";
    const CommandResult result =
        render(base_scene().dump(), {"--backend", "reference", "--integrator", "sppm", "--photons", "5000",
                                     "--initial-radius", "0.25", "--stats-json", stats_path});
    ASSERT_EQ(result.exit_code, 0) << result.err;
    EXPECT_NE(result.err.find(", sppm: 10000 photons, "), std::string::npos) << result.err;
    const json stats = json::parse(read_text(stats_path));
    EXPECT_EQ(stats["sppm"]["photons"], 10000);
    EXPECT_GE(stats["sppm"]["photon_rays"].get<std::uint64_t>(), 10000u);
    EXPECT_GT(stats["sppm"]["photon_deposits"].get<std::uint64_t>(), 0u);
    const double radius = stats["sppm"]["mean_radius"];
    EXPECT_GT(radius, 0.0);
    EXPECT_LE(radius, 0.25);  // radii only shrink
    const double footprint = stats["sppm"]["mean_footprint"], footprints = stats["sppm"]["radius_in_footprints"];
    EXPECT_GT(footprint, 0.0);
    EXPECT_GT(footprints, 0.0);
    EXPECT_EQ(result.err.find("warning"), std::string::npos) << result.err;  // 0.25 is below 4 footprints here
}

// The radii against the footprints (issue 39): at the defaults each pixel
// starts at two footprints and shrinks, so no warning; a first radius far
// above them leaves the render blurred, which one line on stderr says, with
// --quiet too.
TEST_F(CliTest, SppmWarnsWhenItsRadiiEndFarAboveTheFootprints) {
    const std::string stats_path = outputs_ / "stats.json";
    const CommandResult defaults = render(base_scene().dump(), {"--backend", "reference", "--integrator", "sppm",
                                                                "--photons", "5000", "--stats-json", stats_path});
    ASSERT_EQ(defaults.exit_code, 0) << defaults.err;
    const double footprints = json::parse(read_text(stats_path))["sppm"]["radius_in_footprints"];
    EXPECT_GT(footprints, 0.0);
    EXPECT_LE(footprints, 2.0 * (1.0 + 1e-6));
    EXPECT_EQ(defaults.err.find("warning"), std::string::npos) << defaults.err;
    const CommandResult blurred = render(base_scene().dump(), {"--backend", "reference", "--integrator", "sppm",
                                                               "--photons", "5000", "--initial-radius", "100", "-q"});
    ASSERT_EQ(blurred.exit_code, 0) << blurred.err;
    EXPECT_EQ(blurred.err.rfind("wavepath: warning: sppm: the gathering radii are still ", 0), 0u) << blurred.err;
    EXPECT_NE(blurred.err.find("render more iterations or give a smaller --initial-radius\n"), std::string::npos)
        << blurred.err;
    EXPECT_EQ(std::count(blurred.err.begin(), blurred.err.end(), '\n'), 1) << blurred.err;
}

// The default backend (auto) never picks the megakernel, which refuses the
// sppm integrator, though it ranks first for this scene on a CPU device: the
// integrator narrows the choice as a flag does, and the choice says so.
TEST_F(CliTest, AutoChoosesABackendThatRunsSppm) {
    const std::string stats_path = outputs_ / "stats.json";
    const CommandResult result =
        render(base_scene().dump(), {"--integrator", "sppm", "--photons", "50", "--stats-json", stats_path});
    ASSERT_EQ(result.exit_code, 0) << result.err;
    const json stats = json::parse(read_text(stats_path));
    EXPECT_TRUE(stats["backend"] == "wavefront" || stats["backend"] == "reference") << stats["backend"];
    EXPECT_NE(stats["backend_choice"].get<std::string>().find("the sppm integrator given"), std::string::npos)
        << stats["backend_choice"];
    EXPECT_EQ(stats["sppm"]["photons"], 100);
}

TEST_F(CliTest, FlagsOverrideTheScene) {
    ASSERT_EQ(render(base_scene().dump(), {"--width", "5", "--height", "3", "-q"}).exit_code, 0);
    const Image image = read_image(output_path());
    EXPECT_EQ(image.width, 5);
    EXPECT_EQ(image.height, 3);

    // The seed is the only difference between these runs.
    const auto render_with_seed = [&](const char* seed) {
        const auto result = render(base_scene().dump(), {"--seed", seed, "-q"});
        EXPECT_EQ(result.exit_code, 0) << result.err;
        return read_image(output_path()).rgb;
    };
    EXPECT_EQ(render_with_seed("3"), render_with_seed("3"));
    EXPECT_NE(render_with_seed("3"), render_with_seed("4"));
}

TEST_F(CliTest, MaxDepthZeroTracesOnlyCameraRays) {
    // max_depth 0 ends every path at its first hit, before next-event
    // estimation: one extension ray per sample and no shadow rays.
    const std::string stats_path = outputs_ / "stats.json";
    ASSERT_EQ(render(base_scene().dump(), {"--max-depth", "0", "-q", "--stats-json", stats_path}).exit_code, 0);
    const json stats = json::parse(read_text(stats_path));
    EXPECT_EQ(stats["extension_rays"], 8 * 8 * 2);
    EXPECT_EQ(stats["shadow_rays"], 0);
}

// --precision and --threads act on the reference backend (the OpenCL ones
// ignore them). The image of --precision double is the library's double
// reference render, bit for bit, and not its float one (the same estimator
// and random numbers, rounded differently: measured, the images' means
// differ by 1e-8 of the mean and no value by more than 1e-5 of itself; the
// test allows 1e-6 for the means). A 48x16 image is three 16x16 tiles, so up to three threads have
// work; --stats-json's `threads` is what rendered, 1 or 3 as asked (the
// default, all cores, is 2 on the development machine: both are apart from it).
TEST_F(CliTest, ReferencePrecisionAndThreadsTakeEffect) {
    const std::string pfm = outputs_ / "out.pfm", stats = outputs_ / "stats.json";
    const std::string scene = write_scene(patched_scene(R"({"camera": {"width": 48, "height": 16}})").dump());
    auto render_reference_with = [&](const char* precision, const char* threads) {
        CommandResult r = run({"render", scene, "-o", pfm, "-q", "--backend", "reference", "--precision", precision,
                               "--threads", threads, "--stats-json", stats});
        EXPECT_EQ(r.exit_code, 0) << r.err;
        EXPECT_EQ(json::parse(read_text(stats))["threads"], std::atoi(threads)) << precision << ", " << threads;
        return read_image(pfm).rgb;
    };
    const std::vector<float> double_three = render_reference_with("double", "3");
    const std::vector<float> double_one = render_reference_with("double", "1");
    const std::vector<float> float_three = render_reference_with("float", "3");
    // Values that differ between two images of one size.
    auto differing = [](const std::vector<float>& a, const std::vector<float>& b) {
        EXPECT_EQ(a.size(), b.size());
        std::size_t count = 0;
        for (std::size_t i = 0; i < std::min(a.size(), b.size()); ++i) count += a[i] != b[i];
        return count;
    };
    EXPECT_EQ(differing(double_one, double_three), 0u);  // any thread count, the same bits

    const Scene loaded = load_scene(scene);
    const RenderResult in_double = render_reference(loaded, {.threads = 1, .double_precision = true});
    const RenderResult in_float = render_reference(loaded, {.threads = 1, .double_precision = false});
    EXPECT_EQ(differing(double_three, in_double.image.rgb), 0u);
    EXPECT_EQ(differing(float_three, in_float.image.rgb), 0u);
    EXPECT_GT(differing(in_double.image.rgb, in_float.image.rgb), 0u);
    double sum_double = 0.0, sum_float = 0.0;
    for (std::size_t i = 0; i < in_double.image.rgb.size(); ++i)
        sum_double += in_double.image.rgb[i], sum_float += in_float.image.rgb[i];
    EXPECT_NEAR(sum_float, sum_double, 1e-6 * sum_double);
}

TEST_F(CliTest, ReferenceRendersWithEitherIntersector) {
    for (const char* intersector : {"embree", "bvh"}) {
        const CommandResult result =
            render(base_scene().dump(), {"--backend", "reference", "--intersector", intersector, "-q"});
        ASSERT_EQ(result.exit_code, 0) << intersector << ": " << result.err;
        EXPECT_EQ(read_image(output_path()).width, 8);
    }
}

// The wavefront traces with either; --explain names the intersector and why
// (the test scene has no meshes: the OpenCL BVH by default), and both give
// the same image.
TEST_F(CliTest, WavefrontRendersWithEitherIntersectorAndExplainsWhich) {
    const CommandResult by_default = render(base_scene().dump(), {"--backend", "wavefront", "--explain", "-q"});
    ASSERT_EQ(by_default.exit_code, 0) << by_default.err;
    EXPECT_NE(by_default.out.find("intersector: bvh (the OpenCL BVH: without meshes"), std::string::npos)
        << by_default.out;
    const std::vector<float> bvh = read_image(output_path()).rgb;
    const CommandResult embree =
        render(base_scene().dump(), {"--backend", "wavefront", "--intersector", "embree", "--explain", "-q"});
    ASSERT_EQ(embree.exit_code, 0) << embree.err;
    EXPECT_NE(embree.out.find("intersector: embree (asked for)"), std::string::npos) << embree.out;
    EXPECT_EQ(read_image(output_path()).width, 8);
    EXPECT_EQ(read_image(output_path()).rgb, bvh);  // no triangles, so no near tie: the same hits
}

TEST_F(CliTest, ExistingOutputIsReplacedOnlyBySuccess) {
    ASSERT_EQ(render(base_scene().dump(), {"-q"}).exit_code, 0);
    const std::vector<float> first = read_image(output_path()).rgb;
    EXPECT_EQ(render(base_scene().dump(), {"--spp", "0"}).exit_code, 2);
    EXPECT_EQ(render(patched_scene(R"({"camera": null})").dump()).exit_code, 3);
    EXPECT_EQ(read_image(output_path()).rgb, first);
    EXPECT_EQ(outputs_.entries(), std::vector<std::string>{"out.exr"});
}

// ---- version and help ----

TEST_F(CliTest, VersionPrintsTheVersion) {
    const CommandResult result = run({"version"});
    EXPECT_EQ(result.exit_code, 0);
    EXPECT_EQ(result.out, "wavepath " WAVEPATH_VERSION "\n");
    EXPECT_TRUE(result.err.empty()) << result.err;
}

TEST_F(CliTest, HelpListsSubcommands) {
    const CommandResult result = run({"--help"});
    EXPECT_EQ(result.exit_code, 0);
    EXPECT_NE(result.out.find("render"), std::string::npos) << result.out;
    EXPECT_NE(result.out.find("version"), std::string::npos) << result.out;
}

TEST_F(CliTest, RenderHelpListsEveryFlag) {
    const CommandResult result = run({"render", "--help"});
    EXPECT_EQ(result.exit_code, 0);
    for (const char* flag :
         {"--output", "--spp", "--width", "--height", "--max-depth", "--rr-depth", "--seed", "--nee", "--hemisphere",
          "--backend", "--threads", "--precision", "--intersector", "--quiet", "--stats-json"})
        EXPECT_NE(result.out.find(flag), std::string::npos) << flag;
}

}  // namespace
}  // namespace wp::test
