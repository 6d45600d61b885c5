// --backend auto's table (cli/backend_choice.h): the situations it tells
// apart, what it says, and its figures against the bench run they cite
// (bench/results/efficiency.json, written by bench/efficiency.py).
#include "cli/backend_choice.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "support/temp_directory.h"

namespace wp::cli {
namespace {

using nlohmann::json;

// As the table states its ratios: two significant digits.
std::string two_digits(double value) {
    char text[32];
    std::snprintf(text, sizeof text, "%.2g", value);
    return text;
}

TEST(BackendChoice, SituationOfTheDeviceAndTheScene) {
    Scene scene;
    DeviceInfo gpu;
    gpu.type = "GPU";
    EXPECT_EQ(describe(situation_of(gpu, scene)), "GPU device, no meshes");
    scene.meshes.emplace_back();
    DeviceInfo cpu;
    cpu.type = "CPU";
    EXPECT_EQ(describe(situation_of(cpu, scene)), "CPU device, meshes");
    DeviceInfo accelerator;
    accelerator.type = "accelerator";
    EXPECT_EQ(describe(situation_of(accelerator, scene)), "other device, meshes");
}

// What the bench measured on a CPU, and what stands where nothing was measured.
TEST(BackendChoice, PicksAndStatements) {
    EXPECT_EQ(choose_backend({DeviceKind::Cpu, false}).backend, "megakernel");
    EXPECT_EQ(choose_backend({DeviceKind::Cpu, true}).backend, "megakernel");
    const BackendChoice gpu = choose_backend({DeviceKind::Gpu, true});
    EXPECT_EQ(gpu.backend, "wavefront");
    EXPECT_EQ(explain_choice(gpu),
              "auto: GPU device, meshes: not measured on other devices yet: the wavefront, the design meant for GPUs");
    const std::string cpu = explain_choice(choose_backend({DeviceKind::Cpu, false}));
    EXPECT_EQ(cpu.rfind("auto: CPU device, no meshes: ", 0), 0u) << cpu;
    EXPECT_NE(cpu.find("x the wavefront's efficiency on room, cornell in bench/results/efficiency.md"),
              std::string::npos)
        << cpu;
}

// Each measured rule holds for every bench scene of its situation: its
// backend was the more efficient OpenCL backend there, by the ratios it
// states (the median over the repetitions), and it names those scenes; no measured situation falls to a rule
// without figures.
TEST(BackendChoice, RulesAgreeWithTheBench) {
    const json bench = json::parse(test::read_text(WAVEPATH_SOURCE_DIR "/bench/results/efficiency.json"));
    ASSERT_EQ(bench["device_type"], "CPU") << "the rules below read the bench as a CPU's";
    for (const ChoiceRule& rule : backend_choice_rules()) {
        SCOPED_TRACE(rule.backend + std::string(" for ") + rule.scenes);
        if (*rule.source == '\0') {
            EXPECT_NE(*rule.unmeasured, '\0');
            continue;
        }
        EXPECT_STREQ(rule.source, "bench/results/efficiency.md");
        std::string scenes;
        double low = 1e300, high = 0.0;
        for (const json& scene : bench["scenes"]) {
            const Situation situation{DeviceKind::Cpu, scene["meshes"].get<bool>()};
            EXPECT_NE(*rule_for(situation).source, '\0') << scene["scene"] << " was measured";
            if (&rule_for(situation) != &rule) continue;
            std::string name = scene["scene"];
            scenes += (scenes.empty() ? "" : ", ") + name.substr(0, name.rfind(".json"));
            const json& fastest = scene["fastest_opencl_backend"];
            EXPECT_EQ(fastest["backend"], rule.backend) << name;
            EXPECT_EQ(fastest["runner_up"], rule.runner_up) << name;
            const double ratio = fastest["per_repetition"]["median"];  // side by side, so the load's drift cancels
            low = std::min(low, ratio);
            high = std::max(high, ratio);
        }
        EXPECT_EQ(scenes, rule.scenes);
        EXPECT_EQ(two_digits(rule.ratio_low), two_digits(low));
        EXPECT_EQ(two_digits(rule.ratio_high), two_digits(high));
    }
}

}  // namespace
}  // namespace wp::cli
