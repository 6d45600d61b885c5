// `mpirun -n N wavepath render` on this machine (localhost, oversubscribed):
// the image of 1, 2 and 3 ranks is the one-process image, bit for bit; a
// checkpoint of one rank count resumes on another; the budgets and adaptive
// sampling's decisions are the same on every rank; a rank that fails or dies
// fails the job with no output. The scene is scenes/test/room_small.json at 32x32; with
// --wavefront 64 a rank's pass is one sample per pixel (1024 work items), so
// a round of N ranks is N samples per pixel and 7 spp take several rounds,
// the last one partial.
#include <gtest/gtest.h>
#include <signal.h>

#include <chrono>
#include <cstdlib>
#include <nlohmann/json.hpp>
#include <numeric>
#include <thread>

#include "cli/run_wavepath.h"
#include "cli/small_room_render.h"
#include "longrun/film_file.h"

namespace wp::test {
namespace {

class MpiCli : public ::testing::Test {
 protected:
    void SetUp() override {
#ifndef WAVEPATH_MPIEXEC
        GTEST_SKIP() << "built without MPI (WAVEPATH_MPI)";
#endif
        // CI runs as root, which mpirun refuses unless told.
        setenv("OMPI_ALLOW_RUN_AS_ROOT", "1", 1);
        setenv("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1", 1);
    }
    CommandResult run(const std::vector<std::string>& args) { return run_wavepath(args, scratch_.path()); }
    CommandResult run_on(int ranks, const std::vector<std::string>& args) {
        return run_wavepath(args, scratch_.path(), mpirun(ranks));
    }
    static std::vector<std::string> mpirun(int ranks) {
#ifdef WAVEPATH_MPIEXEC
        return {WAVEPATH_MPIEXEC, "--oversubscribe", "-n", std::to_string(ranks)};
#else
        return {"mpirun", "-n", std::to_string(ranks)};
#endif
    }
    // The one-process render at `spp`.
    std::string one_process(int spp) {
        const std::string path = out_ / ("one" + std::to_string(spp) + ".pfm");
        CommandResult r = run(small_room_render_args(path, spp, {"-q"}));
        EXPECT_EQ(r.exit_code, 0) << r.err;
        return path;
    }
    TempDirectory scratch_{"scratch"}, out_{"out"};
};

// The default backend (auto) on 2 ranks: each rank chooses for its own
// device, here the same kind as the one process's, so the image is the
// one-process render's.
TEST_F(MpiCli, AutoBackendOnTwoRanksGivesTheOneProcessBits) {
    const std::string one = out_ / "auto_one.pfm", two = out_ / "auto_two.pfm";
    ASSERT_EQ(run({"render", kSmallRoomScene, "-o", one, "--spp", "4", "-q"}).exit_code, 0);
    CommandResult r = run_on(2, {"render", kSmallRoomScene, "-o", two, "--spp", "4"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_TRUE(same_bytes(two, one));
    EXPECT_NE(r.err.find(" (auto: "), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(", 2 ranks) in "), std::string::npos) << r.err;
}

TEST_F(MpiCli, OneTwoAndThreeRanksGiveTheOneProcessBits) {
    const std::string one = one_process(7);
    EXPECT_FALSE(same_bytes(one_process(6), one));  // the comparison can tell renders apart
    for (int ranks : {1, 2, 3}) {
        SCOPED_TRACE(ranks);
        const std::string out = out_ / ("ranks" + std::to_string(ranks) + ".pfm"), stats = out_ / "stats.json";
        CommandResult r = run_on(ranks, small_room_render_args(out, 7, {"--stats-json", stats}));
        ASSERT_EQ(r.exit_code, 0) << r.err;
        EXPECT_TRUE(same_bytes(out, one));
        if (ranks > 1) {
            EXPECT_NE(r.err.find(", --wavefront given), " + std::to_string(ranks) + " ranks)"), std::string::npos)
                << r.err;
        }
        const nlohmann::json json = nlohmann::json::parse(read_text(stats));
        EXPECT_EQ(json["ranks"], ranks);
        ASSERT_EQ(json["samples_per_rank"].size(), std::size_t(ranks));
        std::uint64_t sum = 0;
        for (const auto& samples : json["samples_per_rank"]) {
            EXPECT_GE(samples.get<std::uint64_t>(), 7u * 1024 / ranks - 1024);  // a share of every round but the last
            sum += samples.get<std::uint64_t>();
        }
        EXPECT_EQ(sum, 7u * 1024);
        EXPECT_EQ(json["render_s_per_rank"].size(), std::size_t(ranks));
        EXPECT_EQ(json["samples"], 7u * 1024);
    }
}

// Each resume renders exactly the 7 spp the checkpoint did not hold (its
// --stats-json): one that started over would give the same bits.
TEST_F(MpiCli, CheckpointOfTwoRanksResumesOnOneAndThree) {
    const std::string one = one_process(12), checkpoint = out_ / "c.wpfilm", stats = out_ / "stats.json";
    CommandResult first = run_on(2, small_room_render_args(out_ / "part.pfm", 5, {"-q", "--checkpoint", checkpoint}));
    ASSERT_EQ(first.exit_code, 0) << first.err;
    EXPECT_EQ(read_film_file(checkpoint).film.items, (ItemRange{0, 5 * 1024}));
    CommandResult alone =
        run(small_room_render_args(out_ / "alone.pfm", 12, {"-q", "--resume", checkpoint, "--stats-json", stats}));
    ASSERT_EQ(alone.exit_code, 0) << alone.err;
    EXPECT_TRUE(same_bytes(out_ / "alone.pfm", one));
    EXPECT_EQ(rendered_samples(stats), 7u * 1024);
    CommandResult three = run_on(
        3, small_room_render_args(out_ / "three.pfm", 12, {"-q", "--resume", checkpoint, "--stats-json", stats}));
    ASSERT_EQ(three.exit_code, 0) << three.err;
    EXPECT_TRUE(same_bytes(out_ / "three.pfm", one));
    EXPECT_EQ(rendered_samples(stats), 7u * 1024);
}

// --time: the root decides for every rank, after one whole round (the first
// always runs): the film is the first round's, which continues to the
// one-process bits.
TEST_F(MpiCli, TimeBudgetStopsEveryRankAfterTheSameRound) {
    const std::string one = one_process(7), film = out_ / "t.wpfilm";
    CommandResult timed = run_on(2, small_room_render_args(film, 100000, {"--time", "0.001"}));
    ASSERT_EQ(timed.exit_code, 0) << timed.err;
    EXPECT_NE(timed.err.find("stopped: time budget"), std::string::npos) << timed.err;
    EXPECT_EQ(read_film_file(film).film.items, (ItemRange{0, 2 * 1024}));
    const std::string stats = out_ / "stats.json";
    CommandResult rest =
        run(small_room_render_args(out_ / "rest.pfm", 7, {"-q", "--resume", film, "--stats-json", stats}));
    ASSERT_EQ(rest.exit_code, 0) << rest.err;
    EXPECT_TRUE(same_bytes(out_ / "rest.pfm", one));
    EXPECT_EQ(rendered_samples(stats), 5u * 1024);
}

// --target-error: the root estimates from every rank's sums, so the ranks
// stop at the one-process sample.
TEST_F(MpiCli, TargetErrorStopsAtTheOneProcessSample) {
    const std::string one = out_ / "one.pfm", two = out_ / "two.pfm";
    ASSERT_EQ(run(small_room_render_args(one, 100000, {"-q", "--target-error", "0.3"})).exit_code, 0);
    CommandResult r = run_on(2, small_room_render_args(two, 100000, {"--target-error", "0.3"}));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.err.find("stopped: target error"), std::string::npos) << r.err;
    EXPECT_TRUE(same_bytes(two, one));
}

// --adaptive: the root finds the pixels still active in the summed film and
// every rank begins the same round over them, so 2 ranks give the
// one-process bits, and a checkpoint that 2 ranks wrote in an adaptive round
// resumes on 3 to them too.
TEST_F(MpiCli, AdaptiveSamplingGivesTheOneProcessBits) {
    const std::string one = out_ / "one.pfm", two = out_ / "two.pfm", checkpoint = out_ / "c.wpfilm",
                      one_stats = out_ / "one.json", three_stats = out_ / "three.json";
    ASSERT_EQ(run(small_room_render_args(one, 32, {"-q", "--adaptive", "0.1", "--stats-json", one_stats})).exit_code,
              0);
    CommandResult r = run_on(2, small_room_render_args(two, 32, {"--adaptive", "0.1"}));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.err.find("% of pixels stopped early"), std::string::npos) << r.err;
    EXPECT_TRUE(same_bytes(two, one));
    ASSERT_EQ(run_on(2, small_room_render_args(out_ / "part.pfm", 20,
                                               {"-q", "--adaptive", "0.1", "--checkpoint", checkpoint}))
                  .exit_code,
              0);
    const Film held = read_film_file(checkpoint).film;
    EXPECT_TRUE(held.in_round());
    CommandResult three = run_on(
        3, small_room_render_args(out_ / "three.pfm", 32,
                                  {"-q", "--adaptive", "0.1", "--resume", checkpoint, "--stats-json", three_stats}));
    ASSERT_EQ(three.exit_code, 0) << three.err;
    EXPECT_TRUE(same_bytes(out_ / "three.pfm", one));
    // The resume renders what the one-process render did beyond the checkpoint's samples.
    const std::vector<std::uint64_t> counts = held.sample_counts();
    EXPECT_EQ(rendered_samples(three_stats),
              rendered_samples(one_stats) - std::accumulate(counts.begin(), counts.end(), std::uint64_t(0)));
}

// Rank 1 runs its own command line (mpirun's MPMD form, `A : B`): a scene
// it cannot load, other settings or another estimator fail the job before anything is
// rendered: one error line naming the rank, its exit code, no output.
TEST_F(MpiCli, ARankThatCannotStartFailsTheJobWithOneLine) {
    const std::string out = out_ / "out.pfm";
    // Rank 0 renders the small room; after mpirun's `:`, one more rank runs wavepath with `rank1`.
    auto with_rank1 = [&](const std::vector<std::string>& rank1) {
        std::vector<std::string> command = small_room_render_args(out, 4);
        command.insert(command.end(), {":", "-n", "1", WAVEPATH_BINARY});
        command.insert(command.end(), rank1.begin(), rank1.end());
        return command;
    };
    CommandResult r =
        run_on(1, with_rank1({"render", out_ / "missing.json", "-o", out, "--spp", "4", "--wavefront", "64"}));
    EXPECT_EQ(r.exit_code, 3) << r.err;
    EXPECT_NE(r.err.find("wavepath: error: rank 1: "), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("missing.json"), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(out));

    const std::string brighter = out_ / "brighter.json";
    std::string scene = read_text(kSmallRoomScene);
    scene.replace(scene.find("[14, 14, 14]"), 12, "[15, 14, 14]");
    write_text(brighter, scene);
    r = run_on(1, with_rank1({"render", brighter, "-o", out, "--spp", "4", "--wavefront", "64"}));
    EXPECT_EQ(r.exit_code, 3) << r.err;
    EXPECT_NE(r.err.find("wavepath: error: rank 1 loaded another scene than rank 0 (their content differs): every "
                         "machine needs the same scene and mesh files"),
              std::string::npos)
        << r.err;
    EXPECT_FALSE(std::filesystem::exists(out));

    // Another spp: not part of the render's identity (the seed is), but of the plan.
    r = run_on(1, with_rank1(small_room_render_args(out, 5)));
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find("wavepath: error: rank 1 was given other settings than rank 0"), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(out));

    // Another estimator: what --backend auto's choices on two kinds of device would give.
    r = run_on(1, with_rank1(small_room_render_args(out, 4, {"--backend", "reference"})));
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find("wavepath: error: rank 1 renders with another estimator than rank 0 (another backend: "
                         "--backend auto chooses per kind of device; give --backend)"),
              std::string::npos)
        << r.err;
    EXPECT_FALSE(std::filesystem::exists(out));
}

// A rank that fails once the others are rendering (here: no such OpenCL
// device, which is not part of the render's identity) reports its error and
// ends the job at once with its exit code (MPI_Abort).
TEST_F(MpiCli, ARankThatFailsWhileOthersRenderEndsTheJob) {
    const std::string out = out_ / "out.pfm";
    std::vector<std::string> args = small_room_render_args(out, 100000);
    std::vector<std::string> failing = args;
    failing.insert(failing.end(), {":", "-n", "1", WAVEPATH_BINARY});
    failing.insert(failing.end(), args.begin(), args.end());
    failing.insert(failing.end(), {"--device", "no such device"});
    CommandResult r = run_on(1, failing);
    EXPECT_NE(r.exit_code, 0) << r.err;
    EXPECT_NE(r.err.find("wavepath: error: rank 1: "), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(out));
}

// A rank killed during the render (SIGKILL, 2 s after its start, from
// timeout(1) that runs it) ends the job: a non-zero exit, and no output. The
// checkpoint (of 3 spp before, perhaps later ones since) still resumes to
// the one-process bits.
TEST_F(MpiCli, ARankThatDiesFailsTheJobAndTheCheckpointStillResumes) {
    const std::string out = out_ / "out.pfm", checkpoint = out_ / "c.wpfilm";
    ASSERT_EQ(run_on(2, small_room_render_args(out_ / "first.pfm", 3, {"-q", "--checkpoint", checkpoint})).exit_code,
              0);
    std::vector<std::string> args = small_room_render_args(
        out, 100000, {"--resume", checkpoint, "--checkpoint", checkpoint, "--checkpoint-every", "0"});
    std::vector<std::string> dying = args;
    dying.insert(dying.end(), {":", "-n", "1", "timeout", "-s", "KILL", "2", WAVEPATH_BINARY});
    dying.insert(dying.end(), args.begin(), args.end());
    CommandResult r = run_on(1, dying);
    EXPECT_NE(r.exit_code, 0) << r.err;
    EXPECT_FALSE(r.err.empty());
    EXPECT_FALSE(std::filesystem::exists(out));

    const Film film = read_film_file(checkpoint).film;
    ASSERT_EQ(film.items.begin, 0u);
    ASSERT_GE(film.items.end, 3u * 1024);
    const int spp = int(film.max_samples()) + 1;
    const std::string stats = out_ / "stats.json";
    CommandResult rest =
        run(small_room_render_args(out_ / "rest.pfm", spp, {"-q", "--resume", checkpoint, "--stats-json", stats}));
    ASSERT_EQ(rest.exit_code, 0) << rest.err;
    EXPECT_TRUE(same_bytes(out_ / "rest.pfm", one_process(spp)));
    EXPECT_EQ(rendered_samples(stats), std::uint64_t(spp) * 1024 - film.items.end);
}

// SIGINT on mpirun: it sends SIGTERM to every rank, and SIGKILL
// odls_base_sigkill_timeout seconds later (3 here, to outlast a round of
// 2048 work items on a loaded machine; mpirun waits it out twice). The ranks
// stop after the same round and rank 0 writes the image of the checkpoint's
// film; mpirun reports the job as killed (exit 1).
TEST_F(MpiCli, SigintOnMpirunWritesTheImageOfTheCheckpoint) {
    const std::string out = out_ / "out.pfm", checkpoint = out_ / "c.wpfilm", merged = out_ / "merged.pfm";
    std::vector<std::string> launcher = mpirun(2);
    launcher.insert(launcher.begin() + 1, {"--mca", "odls_base_sigkill_timeout", "3"});
    RunningWavepath job(small_room_render_args(out, 100000, {"--checkpoint", checkpoint, "--checkpoint-every", "0"}),
                        scratch_.path(), launcher);
    for (int i = 0; i < 6000 && !std::filesystem::exists(checkpoint); ++i)
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    ASSERT_TRUE(std::filesystem::exists(checkpoint));
    job.send(SIGINT);
    CommandResult r = job.wait();
    EXPECT_NE(r.exit_code, 0) << r.err;
    EXPECT_NE(r.err.find("stopped: interrupted, wavefront (auto: "), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(", --wavefront given), 2 ranks)"), std::string::npos) << r.err;
    ASSERT_EQ(run({"merge", checkpoint, "-o", merged, "-q"}).exit_code, 0);
    EXPECT_TRUE(same_bytes(out, merged));
}

}  // namespace
}  // namespace wp::test
