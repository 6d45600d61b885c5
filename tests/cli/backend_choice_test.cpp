// --backend auto's table (cli/backend_choice.h): the situations it tells
// apart, what it says, and its figures against the bench run they cite
// (bench/results/efficiency.json, written by bench/efficiency.py).
#include "cli/backend_choice.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <map>
#include <nlohmann/json.hpp>
#include <vector>

#include "reference/reference_renderer.h"
#include "support/temp_directory.h"
#include "wavefront/intersector_choice.h"

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

// What the table says of `ranked` against the backend after it, on a CPU.
std::string measured_evidence(const Ranked& ranked, const Ranked& next, const std::string& scenes) {
    return "with " + std::string(ranked.intersector) + ": " +
           (ranked.over_next_low == ranked.over_next_high
                ? two_digits(ranked.over_next_low)
                : two_digits(ranked.over_next_low) + "-" + two_digits(ranked.over_next_high)) +
           "x the efficiency of the " + next.backend + " with " + next.intersector + " on " + scenes +
           " in bench/results/efficiency.md" +
           (ranked.clear_lead ? "" : ", a tie, which the bench's order for ties settles");
}

// On a CPU the first of the measured ranking, with its figures over the
// second; elsewhere the wavefront, with why nothing was measured.
TEST(BackendChoice, PicksAndStatements) {
    for (const bool meshes : {false, true}) {
        const ChoiceRule& rule = rule_for({DeviceKind::Cpu, meshes});
        const BackendChoice cpu = choose_backend({DeviceKind::Cpu, meshes});
        EXPECT_EQ(cpu.backend, rule.ranking[0].backend);
        EXPECT_EQ(explain_choice(cpu),
                  "auto: " + describe({DeviceKind::Cpu, meshes}) + ": " +
                      measured_evidence(rule.ranking[0], rule.ranking[1], meshes ? "bunny" : "room, cornell"));
    }
    const BackendChoice gpu = choose_backend({DeviceKind::Gpu, true});
    EXPECT_EQ(gpu.backend, "wavefront");
    EXPECT_EQ(explain_choice(gpu),
              "auto: GPU device, meshes: not measured on other devices yet: the wavefront, the design meant for GPUs");
}

// Flags only some backends take pass over the higher-ranked ones that do
// not: --profile takes the first OpenCL backend of the ranking, saying so
// when the reference is ranked before it; a flag one backend alone takes
// picks it; flags no backend takes together are refused.
TEST(BackendChoice, FlagsNarrowTheRanking) {
    for (const bool meshes : {false, true}) {
        const ChoiceRule& rule = rule_for({DeviceKind::Cpu, meshes});
        const auto opencl = std::find_if(rule.ranking.begin(), rule.ranking.end(), [](const Ranked& ranked) {
            return std::string(ranked.backend) != "reference";
        });
        ASSERT_NE(opencl + 1, rule.ranking.end()) << "the two OpenCL backends are ranked";
        const BackendChoice profiled = choose_backend({DeviceKind::Cpu, meshes}, kProfile);
        EXPECT_EQ(profiled.backend, opencl->backend);
        EXPECT_EQ(profiled.situation, describe({DeviceKind::Cpu, meshes}) + ", --profile given");
        std::string evidence = measured_evidence(*opencl, *(opencl + 1), meshes ? "bunny" : "room, cornell");
        if (opencl != rule.ranking.begin())
            evidence += "; the reference with " + std::string(rule.ranking[0].intersector) +
                        ", ranked first, does not take --profile";
        EXPECT_EQ(profiled.evidence, evidence);
    }
    const BackendChoice precise = choose_backend({DeviceKind::Gpu, false}, kPrecision);
    EXPECT_EQ(precise.backend, "reference");
    EXPECT_EQ(explain_choice(precise),
              "auto: GPU device, no meshes, --precision given: only the reference with embree takes it");
    std::vector<LimitingFlag> both = kProfile;
    both.push_back(kPrecision.front());
    EXPECT_THROW(choose_backend({DeviceKind::Cpu, false}, both), NoBackendTakesTheFlags);
}

// The sppm integrator runs on the wavefront with our BVH only: where the
// wavefront is ranked with Embree (its figures then do not hold) the choice
// passes it over for the next backend that runs SPPM, and says why. The
// rule here ranks the wavefront first whatever the shipped table says (the
// bench's order for ties does today: the wavefront and the reference with
// Embree tie on meshes).
TEST(BackendChoice, TheSppmIntegratorPassesOverTheWavefrontRankedWithEmbree) {
    const std::vector<LimitingFlag> sppm{{"the sppm integrator", {"wavefront", "reference"}, {"wavefront"}}};
    const ChoiceRule wavefront_first{DeviceKind::Cpu,
                                     true,
                                     {{{"wavefront", "embree", 1.1, 1.1, true},
                                       {"reference", "embree", 1.2, 1.2, true},
                                       {"megakernel", "bvh", 0.0, 0.0, false}}},
                                     "bunny",
                                     "bench/results/efficiency.md",
                                     ""};
    const BackendChoice choice = choose_backend(wavefront_first, {DeviceKind::Cpu, true}, sppm);
    EXPECT_EQ(choice.backend, "reference");
    EXPECT_EQ(explain_choice(choice),
              "auto: CPU device, meshes, the sppm integrator given: only the reference with embree takes it");
    // Ranked with our BVH, the wavefront takes it.
    ChoiceRule with_bvh = wavefront_first;
    with_bvh.ranking[0].intersector = "bvh";
    EXPECT_EQ(choose_backend(with_bvh, {DeviceKind::Cpu, true}, sppm).backend, "wavefront");
    // And the shipped table: the first of its ranking that runs SPPM with what it is ranked with.
    for (const bool meshes : {false, true}) {
        const ChoiceRule& rule = rule_for({DeviceKind::Cpu, meshes});
        const auto runs_sppm = [](const Ranked& ranked) {
            const std::string backend = ranked.backend;
            return backend == "reference" || (backend == "wavefront" && std::string(ranked.intersector) == "bvh");
        };
        const auto expected = std::find_if(rule.ranking.begin(), rule.ranking.end(), runs_sppm);
        ASSERT_NE(expected, rule.ranking.end());
        EXPECT_EQ(choose_backend({DeviceKind::Cpu, meshes}, sppm).backend, expected->backend) << "meshes " << meshes;
    }
}

// Each backend is ranked with the intersector it traces with by default in
// the rule's situation (the wavefront's by the device and the scene's
// meshes, the reference's in float), so that what auto runs is what the
// figures measured.
TEST(BackendChoice, RankedIntersectorsAreTheBackendsDefaults) {
    for (const ChoiceRule& rule : backend_choice_rules())
        for (const bool meshes : {false, true}) {
            if (rule.meshes && *rule.meshes != meshes) continue;
            DeviceInfo device;
            device.type = rule.device == DeviceKind::Cpu ? "CPU" : "GPU";
            FeatureSet features;
            features.meshes = meshes;
            const std::map<std::string, Intersector> defaults{
                {"wavefront", default_intersector(device, features).intersector},
                {"megakernel", Intersector::Bvh},
                {"reference", fastest_reference_intersector(false)}};
            for (const Ranked& ranked : rule.ranking) {
                SCOPED_TRACE(std::string(ranked.backend) + " on a " + device.type + (meshes ? ", meshes" : ""));
                EXPECT_EQ(ranked.intersector, intersector_name(defaults.at(ranked.backend)));
            }
        }
}

// Each measured rule restates the bench's ranking for its situation (scenes
// with meshes or without; bench/efficiency.py ranks by the geometric mean
// over the situation's scenes of each backend's efficiency over Mitsuba's):
// the same order, each backend's efficiency over the next's in the range the
// bench found over those scenes (per-repetition medians, side by side), and
// the scenes it names; no measured situation falls to a rule without figures.
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
        ASSERT_TRUE(rule.meshes.has_value());
        const auto situation = std::find_if(bench["situations"].begin(), bench["situations"].end(),
                                            [&](const json& s) { return s["meshes"] == *rule.meshes; });
        ASSERT_NE(situation, bench["situations"].end()) << "meshes " << *rule.meshes;
        std::string scenes;
        for (const std::string name : (*situation)["scenes"])
            scenes += (scenes.empty() ? "" : ", ") + name.substr(0, name.rfind(".json"));
        EXPECT_EQ(scenes, rule.scenes);
        const json& ranking = (*situation)["ranking"];
        ASSERT_EQ(ranking.size(), rule.ranking.size());
        for (std::size_t i = 0; i < ranking.size(); ++i) {
            EXPECT_EQ(ranking[i]["backend"], rule.ranking[i].backend) << "place " << i;
            EXPECT_EQ(ranking[i]["intersector"], rule.ranking[i].intersector) << "place " << i;
            if (i + 1 == ranking.size()) continue;
            const json& over_next = ranking[i]["over_next_per_scene_median"];
            EXPECT_EQ(two_digits(rule.ranking[i].over_next_low), two_digits(over_next["low"])) << "place " << i;
            EXPECT_EQ(two_digits(rule.ranking[i].over_next_high), two_digits(over_next["high"])) << "place " << i;
            EXPECT_EQ(rule.ranking[i].clear_lead, ranking[i]["clear_lead_over_next"].get<bool>()) << "place " << i;
        }
    }
}

}  // namespace
}  // namespace wp::cli
