// --backend auto, the default, through the binary on a CPU device (PoCL):
// its choice for a scene with and without meshes, stated by --explain, the
// summary line and --stats-json; an explicit --backend and the flags only
// some backends take honoured; --profile-json under it; and checkpoints of
// its renders resumed to the same bits.
#include <gtest/gtest.h>

#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>

#include "cli/backend_choice.h"
#include "cli/run_wavepath.h"
#include "cli/small_room_render.h"

namespace wp::test {
namespace {

using nlohmann::json;

std::string first_line(const std::string& text) { return text.substr(0, text.find('\n')); }

class AutoBackendCli : public ::testing::Test {
 protected:
    void SetUp() override {
        // Without --device a GPU is preferred: the CPU's choice is tested where PoCL's CPU is the only device.
        const CommandResult devices = run({"devices"});
        ASSERT_EQ(devices.exit_code, 0) << devices.err;
        if (devices.out.find("type: CPU") == std::string::npos || devices.out.find("type: GPU") != std::string::npos)
            GTEST_SKIP() << "the default device is not a CPU:\n" << devices.out;
    }
    CommandResult run(const std::vector<std::string>& args) { return run_wavepath(args, scratch_.path()); }
    // The small room (no meshes) at 32x32, as `wavepath render SCENE -o OUT --spp N` and `extra`.
    CommandResult render_room(const std::string& out, int spp, std::vector<std::string> extra) {
        std::vector<std::string> args{"render", kSmallRoomScene, "-o", out, "--spp", std::to_string(spp)};
        args.insert(args.end(), extra.begin(), extra.end());
        return run(args);
    }
    // A square mesh lit by a small quad light between it and the camera, 8x8.
    std::string mesh_scene() {
        write_text(out_ / "square.obj", "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nf 1 2 3 4\n");
        const std::string scene = out_ / "mesh.json";
        write_text(scene, R"({"camera": {"position": [0, 0, 3], "look_at": [0, 0, 0], "fov_y": 60, "width": 8,
            "height": 8}, "render": {"spp": 2, "max_depth": 2},
            "materials": {"white": {"type": "diffuse", "albedo": [0.5, 0.5, 0.5]},
                          "lamp": {"type": "emitter", "radiance": [4, 4, 4]}},
            "shapes": [{"type": "mesh", "file": "square.obj", "material": "white"},
                       {"type": "quad", "corner": [-0.25, -0.25, 1], "edge1": [0, 0.5, 0], "edge2": [0.5, 0, 0],
                        "material": "lamp"}]})");
        return scene;
    }
    TempDirectory scratch_{"scratch"}, out_{"out"};
};

// For each scene: --explain's first line names the backend and the
// situation with the table's evidence, the summary line the backend and the
// situation, --stats-json the backend, the explanation and the estimator
// (of the intersector the table ranks the backend with).
TEST_F(AutoBackendCli, ChoosesForTheSceneOnACpuDeviceAndSaysWhy) {
    struct Case {
        std::string scene;
        bool meshes;
        std::string situation;
    };
    for (const Case& c :
         {Case{kSmallRoomScene, false, "CPU device, no meshes"}, Case{mesh_scene(), true, "CPU device, meshes"}}) {
        SCOPED_TRACE(c.situation);
        const cli::BackendChoice choice = cli::choose_backend({cli::DeviceKind::Cpu, c.meshes});
        const std::string stats = out_ / "stats.json";
        const CommandResult r =
            run({"render", c.scene, "-o", out_ / "out.pfm", "--spp", "1", "--explain", "--stats-json", stats});
        ASSERT_EQ(r.exit_code, 0) << r.err;
        const std::string explanation = "auto: " + c.situation + ": " + choice.evidence;
        EXPECT_EQ(first_line(r.out), "backend: " + choice.backend + " (" + explanation + ")") << r.out;
        EXPECT_NE(explanation.find(" in bench/results/efficiency.md"), std::string::npos) << explanation;
        EXPECT_NE(r.err.find(", " + choice.backend + " (auto: " + c.situation + ")) in "), std::string::npos) << r.err;
        const json figures = json::parse(read_text(stats));
        EXPECT_EQ(figures["backend"], choice.backend);
        EXPECT_EQ(figures["backend_choice"], explanation);
        // The backend traced with the intersector the table ranks it with (the estimator names Embree).
        const bool embree =
            std::string(cli::rule_for({cli::DeviceKind::Cpu, c.meshes}).ranking[0].intersector) == "embree";
        EXPECT_EQ(figures["estimator"].get<std::string>().ends_with("-embree"), embree) << figures["estimator"];
    }
}

TEST_F(AutoBackendCli, ExplicitBackendAndFlagsSomeBackendsTakeAreHonoured) {
    const std::string stats = out_ / "stats.json";
    const CommandResult named =
        render_room(out_ / "a.pfm", 1, {"--backend", "wavefront", "--explain", "--stats-json", stats});
    ASSERT_EQ(named.exit_code, 0) << named.err;
    EXPECT_EQ(first_line(named.out), "backend: wavefront (--backend)");
    EXPECT_NE(named.err.find(", wavefront) in "), std::string::npos) << named.err;
    EXPECT_TRUE(json::parse(read_text(stats))["backend_choice"].is_null());

    const CommandResult flags = render_room(out_ / "b.pfm", 1, {"--compaction", "atomic", "--lanes", "1", "--explain"});
    ASSERT_EQ(flags.exit_code, 0) << flags.err;
    EXPECT_EQ(
        first_line(flags.out),
        "backend: wavefront (auto: CPU device, no meshes, --compaction, --lanes given: only the wavefront with bvh "
        "takes them all)");
    EXPECT_NE(flags.err.find(", wavefront (auto: CPU device, no meshes, --compaction, --lanes given)) in "),
              std::string::npos)
        << flags.err;

    const CommandResult none = render_room(out_ / "c.pfm", 1, {"--precision", "double", "--profile"});
    EXPECT_EQ(none.exit_code, 2) << none.err;
    EXPECT_EQ(none.err, "wavepath: error: --precision, --profile: no backend takes all of these together\n");
    EXPECT_FALSE(std::filesystem::exists(out_ / "c.pfm"));
}

// The sppm integrator on a scene with meshes: the wavefront is ranked there
// with Embree (first or second: the bench finds the two tied), which its SPPM
// does not trace with, so auto runs what the table's figures hold for, the
// reference with Embree (as choose_backend says under the sppm integrator's
// limits).
TEST_F(AutoBackendCli, SppmOnMeshesRunsAsTheTableRanks) {
    const std::string stats = out_ / "stats.json";
    const CommandResult r = run({"render", mesh_scene(), "-o", out_ / "out.pfm", "--integrator", "sppm", "--photons",
                                 "64", "--explain", "--stats-json", stats});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const cli::BackendChoice choice = cli::choose_backend(
        {cli::DeviceKind::Cpu, true}, {{"the sppm integrator", {"wavefront", "reference"}, {"wavefront"}}});
    EXPECT_EQ(choice.backend, "reference");
    EXPECT_EQ(first_line(r.out), "backend: reference (" + cli::explain_choice(choice) + ")") << r.out;
    EXPECT_EQ(json::parse(read_text(stats))["estimator"], "reference-embree");
}

// --profile-json on the mesh scene, whose first pick may be one without
// kernels: auto takes the best OpenCL backend, whose profile agrees with the
// render's figures.
TEST_F(AutoBackendCli, ProfileTakesAnOpenClBackend) {
    const std::string stats = out_ / "stats.json", profile_path = out_ / "profile.json";
    const CommandResult r =
        run({"render", mesh_scene(), "-o", out_ / "out.pfm", "--stats-json", stats, "--profile-json", profile_path});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const json figures = json::parse(read_text(stats)), profile = json::parse(read_text(profile_path));
    const std::string backend = figures["backend"];
    ASSERT_EQ(
        backend,
        cli::choose_backend({cli::DeviceKind::Cpu, true}, {{"--profile-json", {"wavefront", "megakernel"}}}).backend);
    EXPECT_EQ(figures["backend_choice"].get<std::string>().rfind("auto: CPU device, meshes, --profile-json given: ", 0),
              0u);
    std::map<std::string, json> kernels;
    for (const json& k : profile["kernels"]) kernels[k["name"]] = k;
    EXPECT_EQ(kernels.count(backend == "megakernel" ? "megakernel" : "intersect_and_shade"), 1u) << profile.dump();
    EXPECT_EQ(kernels["accumulate"]["items"], figures["samples"]);
    EXPECT_EQ(figures["samples"], 2u * 8 * 8);
    EXPECT_EQ(profile["render_s"], figures["time_s"]);
}

// Without a limiting flag the choice depends on the device kind and the
// scene alone, so a checkpoint of auto's render resumes under auto to the
// bits of its uninterrupted render, on each scene, and on the backend it
// picked; where that is an OpenCL backend tracing with the BVH, its film is
// the OpenCL estimator's, so the checkpoint resumes on the other one too.
TEST_F(AutoBackendCli, CheckpointsResumeUnderAutoAndOnTheBackendItPicked) {
    struct Case {
        std::string scene;
        bool meshes;
    };
    for (const Case& c : {Case{kSmallRoomScene, false}, Case{mesh_scene(), true}}) {
        SCOPED_TRACE(c.scene);
        const std::string whole = out_ / "whole.pfm", checkpoint = out_ / "c.wpfilm";
        auto render = [&](const std::string& out, int spp, std::vector<std::string> extra) {
            std::vector<std::string> args{"render", c.scene, "-o", out, "--spp", std::to_string(spp), "-q"};
            args.insert(args.end(), extra.begin(), extra.end());
            return run(args).exit_code;
        };
        ASSERT_EQ(render(whole, 6, {}), 0);
        ASSERT_EQ(render(out_ / "part.pfm", 3, {"--checkpoint", checkpoint}), 0);
        EXPECT_FALSE(same_bytes(out_ / "part.pfm", whole));  // the comparison can tell images apart
        // Under auto, and on the backend it picked; on either OpenCL backend when it picked one tracing with
        // the OpenCL BVH (the megakernel's only intersector).
        const cli::Ranked& picked = cli::rule_for({cli::DeviceKind::Cpu, c.meshes}).ranking[0];
        std::vector<std::vector<std::string>> resumes{{}, {"--backend", picked.backend}};
        if (std::string(picked.backend) != "reference" && std::string(picked.intersector) == "bvh")
            resumes.push_back({"--backend", std::string(picked.backend) == "wavefront" ? "megakernel" : "wavefront"});
        for (std::vector<std::string> resume : resumes) {
            SCOPED_TRACE(resume.empty() ? "auto" : resume.back());
            const std::string resumed = out_ / "resumed.pfm", stats = out_ / "stats.json";
            resume.insert(resume.end(), {"--resume", checkpoint, "--stats-json", stats});
            ASSERT_EQ(render(resumed, 6, resume), 0);
            EXPECT_TRUE(same_bytes(resumed, whole));
            const json figures = json::parse(read_text(stats));
            EXPECT_EQ(figures["samples"].get<std::uint64_t>() * 2,
                      figures["width"].get<std::uint64_t>() * figures["height"].get<std::uint64_t>() * 6);
        }
    }
}

}  // namespace
}  // namespace wp::test
