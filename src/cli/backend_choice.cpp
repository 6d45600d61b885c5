#include "cli/backend_choice.h"

#include <algorithm>
#include <cstdio>
#include <string_view>

namespace wp::cli {

namespace {

// The efficiency ratios are those of bench/results/efficiency.json (python3
// bench/efficiency.py), to two digits: BackendChoice.RulesAgreeWithTheBench
// fails when they no longer are.
constexpr std::array<ChoiceRule, 3> kRules{{
    {DeviceKind::Cpu,
     false,
     {{{"wavefront", "bvh", 1.03, 1.03, false},
       {"megakernel", "bvh", 3.0, 3.1, true},
       {"reference", "embree", 0.0, 0.0, false}}},
     "room, cornell",
     "bench/results/efficiency.md",
     ""},
    {DeviceKind::Cpu,
     true,
     {{{"wavefront", "embree", 1.0, 1.0, true},
       {"reference", "embree", 1.3, 1.3, true},
       {"megakernel", "bvh", 0.0, 0.0, false}}},
     "bunny",
     "bench/results/efficiency.md",
     ""},
    {std::nullopt,
     std::nullopt,
     {{{"wavefront", "bvh", 0.0, 0.0, false},
       {"megakernel", "bvh", 0.0, 0.0, false},
       {"reference", "embree", 0.0, 0.0, false}}},
     "",
     "",
     "not measured on other devices yet: the wavefront, the design meant for GPUs"},
}};

bool covers(const ChoiceRule& rule, const Situation& situation) {
    return (!rule.device || *rule.device == situation.device) && (!rule.meshes || *rule.meshes == situation.meshes);
}

bool takes(const LimitingFlag& flag, const Ranked& ranked) {
    auto among = [&](const std::vector<std::string>& backends) {
        return std::find(backends.begin(), backends.end(), ranked.backend) != backends.end();
    };
    return among(flag.backends) && (std::string_view(ranked.intersector) == "bvh" || !among(flag.bvh_only));
}

bool takes_all(const std::vector<LimitingFlag>& flags, const Ranked& ranked) {
    return std::all_of(flags.begin(), flags.end(), [&](const LimitingFlag& flag) { return takes(flag, ranked); });
}

std::string joined(const std::vector<LimitingFlag>& flags) {
    std::string text;
    for (const LimitingFlag& flag : flags) text += (text.empty() ? "" : ", ") + flag.flag;
    return text;
}

std::string ratio_text(const Ranked& ranked) {
    char text[32];
    if (ranked.over_next_low == ranked.over_next_high)
        std::snprintf(text, sizeof text, "%.2gx", ranked.over_next_low);
    else
        std::snprintf(text, sizeof text, "%.2g-%.2gx", ranked.over_next_low, ranked.over_next_high);
    return text;
}

// "with bvh: 1.9-2.1x the efficiency of the wavefront with bvh on room, cornell in ...": the figures of
// `ranked` over `next`.
std::string measured(const ChoiceRule& rule, const Ranked& ranked, const Ranked& next) {
    return "with " + std::string(ranked.intersector) + ": " + ratio_text(ranked) + " the efficiency of the " +
           next.backend + " with " + next.intersector + " on " + rule.scenes + " in " + rule.source +
           (ranked.clear_lead ? "" : ", a tie, which the bench's order for ties settles");
}

// Why the backend at `at` in the rule's ranking was chosen under `flags`.
std::string evidence(const ChoiceRule& rule, std::size_t at, const std::vector<LimitingFlag>& flags) {
    const auto taken = std::count_if(rule.ranking.begin(), rule.ranking.end(),
                                     [&](const Ranked& ranked) { return takes_all(flags, ranked); });
    if (taken == 1)
        return "only the " + std::string(rule.ranking[at].backend) + " with " + rule.ranking[at].intersector +
               " takes " + (flags.size() == 1 ? "it" : "them all");
    // More than one takes the flags, so one is ranked after the pick.
    std::string text =
        *rule.source == '\0' ? std::string(rule.unmeasured) : measured(rule, rule.ranking[at], rule.ranking[at + 1]);
    if (at > 0)
        text += std::string("; the ") + rule.ranking[0].backend + " with " + rule.ranking[0].intersector +
                ", ranked first, does not take " + joined(flags);
    return text;
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

BackendChoice choose_backend(const Situation& situation, const std::vector<LimitingFlag>& flags) {
    return choose_backend(rule_for(situation), situation, flags);
}

BackendChoice choose_backend(const ChoiceRule& rule, const Situation& situation,
                             const std::vector<LimitingFlag>& flags) {
    const auto pick = std::find_if(rule.ranking.begin(), rule.ranking.end(),
                                   [&](const Ranked& ranked) { return takes_all(flags, ranked); });
    if (pick == rule.ranking.end())
        throw NoBackendTakesTheFlags(joined(flags) + ": no backend takes all of these together");
    const std::string given = flags.empty() ? "" : ", " + joined(flags) + " given";
    return {pick->backend, describe(situation) + given,
            evidence(rule, std::size_t(pick - rule.ranking.begin()), flags)};
}

std::string explain_choice(const BackendChoice& choice) { return "auto: " + choice.situation + ": " + choice.evidence; }

}  // namespace wp::cli
