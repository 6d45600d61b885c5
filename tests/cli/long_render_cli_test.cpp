// Long renders through the binary: checkpoint and resume, refused
// checkpoints, SIGKILL at random moments, SIGINT (once and twice), --time,
// --adaptive, and partial films merged. The scene is scenes/test/room_small.json at
// 32x32; with --wavefront 64 a pass is one sample per pixel (1024 work
// items), so there are many passes to stop between.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/stat.h>

#include <chrono>
#include <cstring>
#include <nlohmann/json.hpp>
#include <numeric>
#include <random>
#include <thread>

#include "cli/run_wavepath.h"
#include "cli/small_room_render.h"
#include "image/image_io.h"
#include "longrun/film_file.h"

namespace wp::test {
namespace {

bool same_pixels(const Image& a, const Image& b) {
    return a.width == b.width && a.height == b.height && a.rgb.size() == b.rgb.size() &&
           std::memcmp(a.rgb.data(), b.rgb.data(), sizeof(float) * a.rgb.size()) == 0;
}

// Waits (up to 60 s) until `path` exists.
bool wait_for_file(const std::string& path) {
    for (int i = 0; i < 6000 && !std::filesystem::exists(path); ++i)
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    return std::filesystem::exists(path);
}

class LongRenderCli : public ::testing::Test {
 protected:
    CommandResult run(const std::vector<std::string>& args) { return run_wavepath(args, scratch_.path()); }
    // The uninterrupted render at `spp`, once per test.
    std::string whole_render(int spp, int wavefront = 64) {
        const std::string path = out_ / ("whole" + std::to_string(spp) + ".pfm");
        CommandResult r = run(small_room_render_args(path, spp, {"-q"}, wavefront));
        EXPECT_EQ(r.exit_code, 0) << r.err;
        return path;
    }
    TempDirectory scratch_{"scratch"}, out_{"out"};
};

// Rendering is deterministic, so a resume that started over would give the
// same bits too: the resumed run must render exactly the samples left.
TEST_F(LongRenderCli, ResumedRenderIsBitIdenticalToTheUninterruptedOne) {
    const std::string whole = whole_render(12), checkpoint = out_ / "c.wpfilm", stats = out_ / "stats.json";
    CommandResult first = run(small_room_render_args(out_ / "part.pfm", 5, {"--checkpoint", checkpoint}));
    ASSERT_EQ(first.exit_code, 0) << first.err;
    CommandResult rest =
        run(small_room_render_args(out_ / "resumed.pfm", 12, {"--resume", checkpoint, "--stats-json", stats}));
    ASSERT_EQ(rest.exit_code, 0) << rest.err;
    EXPECT_TRUE(same_bytes(out_ / "resumed.pfm", whole));
    EXPECT_FALSE(same_bytes(out_ / "part.pfm", whole));  // the comparison can tell images apart
    EXPECT_EQ(rendered_samples(stats), (12u - 5u) * 1024u);
}

// Each refusal: exit 3, one error line naming the file, and the files there
// before (the output and the checkpoint) exactly as they were.
TEST_F(LongRenderCli, RefusedCheckpointsChangeNothing) {
    const std::string checkpoint = out_ / "c.wpfilm", output = out_ / "out.pfm";
    ASSERT_EQ(run(small_room_render_args(out_ / "part.pfm", 3, {"-q", "--checkpoint", checkpoint})).exit_code, 0);
    std::string bytes = read_text(checkpoint);
    write_text(out_ / "truncated.wpfilm", bytes.substr(0, bytes.size() - 100));
    bytes[200] ^= 1;
    write_text(out_ / "corrupted.wpfilm", bytes);
    write_text(output, "an earlier image");
    const std::string before = read_text(checkpoint);
    const std::vector<std::string> entries = out_.entries();
    struct Case {
        std::vector<std::string> args;
        std::string message;
    };
    const Case cases[] = {
        {small_room_render_args(output, 8, {"--resume", checkpoint, "--seed", "9", "--checkpoint", checkpoint}),
         checkpoint + ": rendered with other settings"},
        {small_room_render_args(output, 8, {"--resume", checkpoint, "--width", "16"}),
         checkpoint + ": a film of 32x32 pixels"},
        {small_room_render_args(output, 8, {"--resume", checkpoint, "--backend", "reference"}),
         checkpoint + ": rendered by the opencl estimator, this render uses reference-embree"},
        // the room has no meshes: the wavefront's default traces with the OpenCL BVH
        {small_room_render_args(output, 8, {"--resume", checkpoint, "--intersector", "embree"}),
         checkpoint + ": rendered by the opencl estimator, this render uses opencl-embree"},
        {small_room_render_args(output, 2, {"--resume", checkpoint}),
         checkpoint + ": holds 3 samples per pixel, more than the 2"},
        {small_room_render_args(output, 8, {"--resume", out_ / "truncated.wpfilm"}), "truncated"},
        {small_room_render_args(output, 8, {"--resume", out_ / "corrupted.wpfilm"}), "corrupted (checksum mismatch)"},
    };
    for (const Case& c : cases) {
        CommandResult r = run(c.args);
        EXPECT_EQ(r.exit_code, 3) << r.err;
        EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
        EXPECT_EQ(r.err.rfind("wavepath: error: ", 0), 0u) << r.err;
        EXPECT_NE(r.err.find(c.message), std::string::npos) << r.err;
    }
    EXPECT_EQ(read_text(output), "an earlier image");
    EXPECT_EQ(read_text(checkpoint), before);
    EXPECT_EQ(out_.entries(), entries);
}

// The render's identity covers every mesh as loaded: a checkpoint of a scene
// whose mesh file had one vertex moved since is refused like one of another
// scene (the reference backend: no kernels to build). The file as it was
// resumes, so the refusal is the vertex's.
TEST_F(LongRenderCli, ResumeRefusesAMeshFileWithAVertexMoved) {
    const std::string mesh = out_ / "square.obj", scene = out_ / "scene.json", checkpoint = out_ / "c.wpfilm",
                      stats = out_ / "stats.json";
    write_text(mesh, "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nf 1 2 3 4\n");
    write_text(scene, R"({"camera": {"position": [0, 0, 3], "look_at": [0, 0, 0], "fov_y": 60, "width": 8, "height": 8},
        "render": {"spp": 4, "max_depth": 2},
        "materials": {"white": {"type": "diffuse", "albedo": [0.5, 0.5, 0.5]},
                      "lamp": {"type": "emitter", "radiance": [4, 4, 4]}},
        "shapes": [{"type": "mesh", "file": "square.obj", "material": "white"},
                   {"type": "quad", "corner": [-0.5, -0.5, 2], "edge1": [0, 1, 0], "edge2": [1, 0, 0],
                    "material": "lamp"}]})");
    auto render = [&](int spp, std::vector<std::string> extra) {
        std::vector<std::string> args{"render",    scene,       "-o", out_ / "out.pfm", "--spp", std::to_string(spp),
                                      "--backend", "reference", "-q"};
        args.insert(args.end(), extra.begin(), extra.end());
        return run(args);
    };
    CommandResult first = render(2, {"--checkpoint", checkpoint});
    ASSERT_EQ(first.exit_code, 0) << first.err;
    CommandResult same = render(4, {"--resume", checkpoint, "--stats-json", stats});
    ASSERT_EQ(same.exit_code, 0) << same.err;
    EXPECT_EQ(rendered_samples(stats), 2u * 64);

    write_text(mesh, "v -1 -1 0\nv 1 -1 0\nv 1 1 0.25\nv -1 1 0\nf 1 2 3 4\n");
    CommandResult moved = render(4, {"--resume", checkpoint});
    EXPECT_EQ(moved.exit_code, 3) << moved.err;
    EXPECT_NE(moved.err.find(checkpoint + ": rendered from another scene (its content differs)"), std::string::npos)
        << moved.err;
}

// The checkpoint file's inode (each atomic write makes a new one), 0 if none.
ino_t inode_of(const std::string& path) {
    struct stat info {};
    return ::stat(path.c_str(), &info) == 0 ? info.st_ino : 0;
}

// Waits (up to 60 s) until `path` is a file other than `inode`.
bool wait_for_new_file(const std::string& path, ino_t inode) {
    for (int i = 0; i < 6000; ++i) {
        const ino_t now = inode_of(path);
        if (now != 0 && now != inode) return true;
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    return false;
}

// Renders killed at random moments (fixed seed), each resuming from the
// latest checkpoint: that checkpoint always loads, never goes backwards,
// and the last run completes to the uninterrupted render's bits. With
// 1024 paths in flight a pass is 16 samples per pixel (25 passes of about
// 60 ms), and a checkpoint is written after every pass; each run is killed
// 0-300 ms after its first checkpoint (start-up takes seconds on a loaded
// machine), so the kills land among passes and checkpoint writes.
TEST_F(LongRenderCli, SigkillAtAnyMomentLeavesALoadableCheckpoint) {
    const int spp = 400, wavefront = 1024;
    const std::string whole = whole_render(spp, wavefront), checkpoint = out_ / "c.wpfilm", output = out_ / "out.pfm";
    std::mt19937 rng(13);
    std::uniform_int_distribution<int> delay_ms(0, 300);
    std::uint64_t last_end = 0;
    for (int kill = 0; kill < 4; ++kill) {
        std::vector<std::string> extra{"-q", "--checkpoint", checkpoint, "--checkpoint-every", "0"};
        if (std::filesystem::exists(checkpoint)) extra.insert(extra.end(), {"--resume", checkpoint});
        const ino_t before = inode_of(checkpoint);
        RunningWavepath process(small_room_render_args(output, spp, extra, wavefront), scratch_.path());
        ASSERT_TRUE(wait_for_new_file(checkpoint, before));
        std::this_thread::sleep_for(std::chrono::milliseconds(delay_ms(rng)));
        process.send(SIGKILL);
        process.wait();
        const FilmFile file = read_film_file(checkpoint);  // throws if corrupt
        EXPECT_GE(file.film.items.end, last_end);
        last_end = file.film.items.end;
        for (const std::string& name : out_.entries())  // a finished output is whole
            if (name == "out.pfm") {
                EXPECT_EQ(read_image(output).width, 32);
            }
    }
    const std::string stats = out_ / "stats.json";
    CommandResult last =
        run(small_room_render_args(output, spp, {"-q", "--resume", checkpoint, "--stats-json", stats}, wavefront));
    ASSERT_EQ(last.exit_code, 0) << last.err;
    EXPECT_TRUE(same_bytes(output, whole));
    EXPECT_EQ(rendered_samples(stats), std::uint64_t(spp) * 1024 - last_end);
}

// SIGINT: the pass in flight finishes, the image of the samples so far and
// the checkpoint are written (the same film), the summary says so, exit 5.
TEST_F(LongRenderCli, SigintWritesTheImageSoFarAndExits5) {
    const std::string checkpoint = out_ / "c.wpfilm", output = out_ / "out.pfm";
    RunningWavepath process(
        small_room_render_args(output, 100000, {"--checkpoint", checkpoint, "--checkpoint-every", "0"}),
        scratch_.path());
    ASSERT_TRUE(wait_for_file(checkpoint));
    process.send(SIGINT);
    const CommandResult r = process.wait();
    EXPECT_EQ(r.exit_code, 5) << r.err;
    EXPECT_NE(r.err.find("stopped: interrupted"), std::string::npos) << r.err;
    const Film film = read_film_file(checkpoint).film;
    EXPECT_LT(film.items.end, std::uint64_t(32) * 32 * 100000);
    EXPECT_TRUE(same_pixels(read_image(output), film.image()));
}

// A second SIGINT ends the process at once (exit 130), before the pass in
// flight (2^20 work items, about a second) ends; the checkpoint there still
// loads. (Signals sent back to back would merge into one: the first is
// given 100 ms to arrive.)
TEST_F(LongRenderCli, SecondSigintExitsAtOnce) {
    const std::string checkpoint = out_ / "c.wpfilm";
    RunningWavepath process(small_room_render_args(out_ / "out.pfm", 100000,
                                                   {"--checkpoint", checkpoint, "--checkpoint-every", "0"}, 1 << 16),
                            scratch_.path());
    ASSERT_TRUE(wait_for_file(checkpoint));
    process.send(SIGINT);
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    process.send(SIGINT);
    EXPECT_EQ(process.wait().exit_code, 130);
    EXPECT_NO_THROW(read_film_file(checkpoint));
}

TEST_F(LongRenderCli, TimeBudgetStopsAtAWholePass) {
    const std::string stats = out_ / "stats.json";
    CommandResult r = run(small_room_render_args(out_ / "out.pfm", 100000, {"--time", "0.001", "--stats-json", stats}));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.err.find("(32x32, 1 of 100000 spp, stopped: time budget, wavefront (auto: "), std::string::npos)
        << r.err;
    const nlohmann::json json = nlohmann::json::parse(read_text(stats));
    EXPECT_EQ(json["stopped"], "time budget");
    EXPECT_EQ(json["spp_done_min"], 1u);
    EXPECT_EQ(json["samples"], 1024u);
}

// The estimate is checked at whole samples per pixel (4, 5, 6, 7, 8, 10, ...).
TEST_F(LongRenderCli, TargetErrorStopsAtAWholeSampleAndSaysTheEstimate) {
    const std::string stats = out_ / "stats.json";
    CommandResult r =
        run(small_room_render_args(out_ / "out.pfm", 100000, {"--target-error", "0.3", "--stats-json", stats}));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.err.find("stopped: target error"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("estimated relative error 0."), std::string::npos) << r.err;
    const nlohmann::json json = nlohmann::json::parse(read_text(stats));
    EXPECT_EQ(json["stopped"], "target error");
    EXPECT_EQ(json["spp_done_min"], json["spp_done_max"]);
    EXPECT_LE(json["error_estimate"].get<double>(), 0.3);
    CommandResult partial =
        run(small_room_render_args(out_ / "p.wpfilm", 8, {"--target-error", "0.1", "--samples", "0:4"}));
    EXPECT_EQ(partial.exit_code, 2);
    EXPECT_NE(partial.err.find("--target-error: needs the whole render"), std::string::npos) << partial.err;
}

// --adaptive through the binary: the summary and JSON report the mean spp
// and the pixels that stopped early; an adaptive checkpoint resumes to the
// uninterrupted bits, but not with another threshold; --samples and merge
// refuse adaptive films by name.
TEST_F(LongRenderCli, AdaptiveReportsItsSamplesResumesAndRefusesPartials) {
    const std::string whole = out_ / "whole.pfm", stats = out_ / "stats.json", checkpoint = out_ / "c.wpfilm";
    CommandResult r = run(small_room_render_args(whole, 32, {"--adaptive", "0.1", "--stats-json", stats}));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.err.find(", adaptive: mean "), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("% of pixels stopped early"), std::string::npos) << r.err;
    const nlohmann::json json = nlohmann::json::parse(read_text(stats));
    const double mean = json["adaptive"]["spp_mean"], early = json["adaptive"]["stopped_early"];
    EXPECT_LT(mean, 32.0);
    EXPECT_GE(mean, 8.0);
    EXPECT_GT(early, 0.0);
    EXPECT_EQ(json["spp_done_max"], 32u);
    EXPECT_EQ(json["samples"].get<double>(), mean * 32 * 32);

    ASSERT_EQ(
        run(small_room_render_args(out_ / "part.pfm", 20, {"-q", "--adaptive", "0.1", "--checkpoint", checkpoint}))
            .exit_code,
        0);
    const std::vector<std::uint64_t> held = read_film_file(checkpoint).film.sample_counts();
    const std::string rest_stats = out_ / "rest_stats.json";
    CommandResult rest = run(small_room_render_args(
        out_ / "resumed.pfm", 32, {"-q", "--adaptive", "0.1", "--resume", checkpoint, "--stats-json", rest_stats}));
    ASSERT_EQ(rest.exit_code, 0) << rest.err;
    EXPECT_TRUE(same_bytes(out_ / "resumed.pfm", whole));
    EXPECT_FALSE(same_bytes(out_ / "part.pfm", whole));
    EXPECT_EQ(rendered_samples(rest_stats),
              json["samples"].get<std::uint64_t>() - std::accumulate(held.begin(), held.end(), std::uint64_t(0)));
    CommandResult other =
        run(small_room_render_args(out_ / "other.pfm", 32, {"-q", "--adaptive", "0.2", "--resume", checkpoint}));
    EXPECT_EQ(other.exit_code, 3);
    EXPECT_NE(other.err.find("rendered with other settings"), std::string::npos) << other.err;

    CommandResult partial =
        run(small_room_render_args(out_ / "p.wpfilm", 8, {"--adaptive", "0.05", "--samples", "0:4"}));
    EXPECT_EQ(partial.exit_code, 2);
    EXPECT_NE(partial.err.find("--adaptive: needs the whole render"), std::string::npos) << partial.err;
    CommandResult merged = run({"merge", checkpoint, "-o", out_ / "merged.pfm"});
    EXPECT_EQ(merged.exit_code, 3);
    EXPECT_NE(merged.err.find("rendered with --adaptive"), std::string::npos) << merged.err;
}

// Partial films from both OpenCL backends, given in any order, merge into
// the one-process render's bits.
TEST_F(LongRenderCli, MergedPartialFilmsGiveTheOneProcessImage) {
    const std::string whole = whole_render(12);
    ASSERT_EQ(run(small_room_render_args(out_ / "a.wpfilm", 12, {"-q", "--samples", "0:3", "--backend", "megakernel"}))
                  .exit_code,
              0);
    ASSERT_EQ(run(small_room_render_args(out_ / "b.wpfilm", 12, {"-q", "--samples", "3:7"})).exit_code, 0);
    ASSERT_EQ(run(small_room_render_args(out_ / "c.wpfilm", 12, {"-q", "--samples", "7:12"})).exit_code, 0);
    CommandResult merged =
        run({"merge", out_ / "c.wpfilm", out_ / "a.wpfilm", out_ / "b.wpfilm", "-o", out_ / "merged.pfm"});
    ASSERT_EQ(merged.exit_code, 0) << merged.err;
    EXPECT_TRUE(same_bytes(out_ / "merged.pfm", whole));
    EXPECT_NE(merged.err.find("merged 3 films"), std::string::npos) << merged.err;
}

TEST_F(LongRenderCli, MergeRefusesGapsOverlapsAndOtherRenders) {
    ASSERT_EQ(run(small_room_render_args(out_ / "a.wpfilm", 12, {"-q", "--samples", "0:3"})).exit_code, 0);
    ASSERT_EQ(run(small_room_render_args(out_ / "b.wpfilm", 12, {"-q", "--samples", "4:6"})).exit_code, 0);
    ASSERT_EQ(run(small_room_render_args(out_ / "c.wpfilm", 12, {"-q", "--samples", "2:4"})).exit_code, 0);
    ASSERT_EQ(run(small_room_render_args(out_ / "d.wpfilm", 12, {"-q", "--samples", "3:4", "--seed", "5"})).exit_code,
              0);
    struct Case {
        std::vector<std::string> films;
        std::string message;
    };
    const Case cases[] = {
        {{"a.wpfilm", "b.wpfilm"}, "b.wpfilm: starts at work item 4096 but the films before it end at 3072 (a gap)"},
        {{"a.wpfilm", "c.wpfilm"},
         "c.wpfilm: starts at work item 2048 but the films before it end at 3072 (an overlap)"},
        {{"a.wpfilm", "d.wpfilm"}, "d.wpfilm: rendered with other settings"},
    };
    for (const Case& c : cases) {
        std::vector<std::string> args{"merge"};
        for (const std::string& f : c.films) args.push_back(out_ / f);
        args.insert(args.end(), {"-o", out_ / "merged.png"});
        CommandResult r = run(args);
        EXPECT_EQ(r.exit_code, 3) << r.err;
        EXPECT_NE(r.err.find(c.message), std::string::npos) << r.err;
        EXPECT_FALSE(std::filesystem::exists(out_ / "merged.png"));
    }
    CommandResult image = run(small_room_render_args(out_ / "x.png", 12, {"--samples", "0:3"}));
    EXPECT_EQ(image.exit_code, 2);
    EXPECT_NE(image.err.find("--samples: a partial render writes a film"), std::string::npos) << image.err;
}

}  // namespace
}  // namespace wp::test
