// --backend auto's table (cli/backend_choice.h): the situations it tells
// apart, what it says, and its figures against the bench run they cite
// (bench/results/efficiency.json, written by bench/efficiency.py).
#include "cli/backend_choice.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <vector>

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

const std::vector<LimitingFlag> kProfile{{"--profile", {"wavefront", "megakernel"}}};
const std::vector<LimitingFlag> kPrecision{{"--precision", {"reference"}}};

// What the bench measured on a CPU, and what stands where nothing was measured.
TEST(BackendChoice, PicksAndStatements) {
    EXPECT_EQ(choose_backend({DeviceKind::Cpu, false}).backend, "megakernel");
    EXPECT_EQ(choose_backend({DeviceKind::Cpu, true}).backend, "reference");
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

// Flags only some backends take pass over the higher-ranked ones that do not.
TEST(BackendChoice, FlagsNarrowTheRanking) {
    const BackendChoice profiled = choose_backend({DeviceKind::Cpu, true}, kProfile);
    EXPECT_EQ(profiled.backend, "megakernel");
    EXPECT_EQ(profiled.situation, "CPU device, meshes, --profile given");
    EXPECT_NE(profiled.evidence.find("x the wavefront's efficiency on bunny in bench/results/efficiency.md; the "
                                     "reference, ranked first, does not take --profile"),
              std::string::npos)
        << profiled.evidence;
    const BackendChoice precise = choose_backend({DeviceKind::Gpu, false}, kPrecision);
    EXPECT_EQ(precise.backend, "reference");
    EXPECT_EQ(explain_choice(precise), "auto: GPU device, no meshes, --precision given: only the reference takes it");
    std::vector<LimitingFlag> both = kProfile;
    both.push_back(kPrecision.front());
    EXPECT_THROW(choose_backend({DeviceKind::Cpu, false}, both), NoBackendTakesTheFlags);
}

// Each measured rule holds for every bench scene of its situation: its
// ranking is the bench's there, each backend's efficiency over the next's
// is within the range it states (the median over the repetitions, side by
// side), and it names those scenes; no measured situation falls to a rule
// without figures.
TEST(BackendChoice, RulesAgreeWithTheBench) {
    const json bench = json::parse(test::read_text(WAVEPATH_SOURCE_DIR "/bench/results/efficiency.json"));
    ASSERT_EQ(bench["device_type"], "CPU") << "the rules below read the bench as a CPU's";
    for (const json& scene : bench["scenes"])
        EXPECT_NE(*rule_for({DeviceKind::Cpu, scene["meshes"].get<bool>()}).source, '\0') << scene["scene"];
    for (const ChoiceRule& rule : backend_choice_rules()) {
        SCOPED_TRACE(std::string(rule.ranking[0].backend) + " first, for " + rule.scenes);
        if (*rule.source == '\0') {
            EXPECT_NE(*rule.unmeasured, '\0');
            continue;
        }
        EXPECT_STREQ(rule.source, "bench/results/efficiency.md");
        std::string scenes;
        std::vector<double> low(rule.ranking.size(), 1e300), high(rule.ranking.size(), 0.0);
        for (const json& scene : bench["scenes"]) {
            if (&rule_for({DeviceKind::Cpu, scene["meshes"].get<bool>()}) != &rule) continue;
            const std::string name = scene["scene"];
            scenes += (scenes.empty() ? "" : ", ") + name.substr(0, name.rfind(".json"));
            const json& ranking = scene["ranking"];
            ASSERT_EQ(ranking.size(), rule.ranking.size()) << name;
            for (std::size_t i = 0; i < ranking.size(); ++i) {
                EXPECT_EQ(ranking[i]["backend"], rule.ranking[i].backend) << name << ", place " << i;
                if (i + 1 == ranking.size()) continue;
                const double ratio = ranking[i]["over_next"]["per_repetition"]["median"];
                low[i] = std::min(low[i], ratio);
                high[i] = std::max(high[i], ratio);
            }
        }
        EXPECT_EQ(scenes, rule.scenes);
        for (std::size_t i = 0; i + 1 < rule.ranking.size(); ++i) {
            EXPECT_EQ(two_digits(rule.ranking[i].over_next_low), two_digits(low[i])) << rule.ranking[i].backend;
            EXPECT_EQ(two_digits(rule.ranking[i].over_next_high), two_digits(high[i])) << rule.ranking[i].backend;
        }
    }
}

}  // namespace
}  // namespace wp::cli
