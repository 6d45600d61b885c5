// --backend auto, the default: the backend chosen for the device and the
// scene from the bench's figures. The policy is the table in
// backend_choice.cpp: one rule per kind of device and scene, ranking the
// backends by their measured efficiency and citing the bench/results file
// the figures come from (tests/cli/backend_choice_test.cpp checks them
// against it). Flags that only some backends take narrow the ranking.
// Each backend is ranked with the intersector it traces with by default in
// the situation (the table states it, the tests check it is the backend's
// default); the lanes are each OpenCL backend's own choice by the device's
// vector width.
#pragma once

#include <array>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "opencl/device.h"
#include "scene/scene.h"

namespace wp::cli {

enum class DeviceKind { Cpu, Gpu, Other };

// What the choice depends on.
struct Situation {
    DeviceKind device = DeviceKind::Cpu;
    bool meshes = false;
};

Situation situation_of(const DeviceInfo& device, const Scene& scene);

// "CPU device, no meshes".
std::string describe(const Situation& situation);

// A backend in a rule's ranking, with the intersector it traces with there
// (its default in the situation, which the bench ran: "embree" or "bvh"),
// and its efficiency over the next one's: the lowest and highest, over the
// rule's scenes, of the median over the bench's repetitions (0: not
// measured), and whether that lead is clear at the bench's confidence. Where
// it is not, the two tie and the bench's order for ties ranks them.
struct Ranked {
    const char* backend;
    const char* intersector;
    double over_next_low, over_next_high;
    bool clear_lead;
};

// One row of the table: the situations it covers (unset: any), every
// backend from the most efficient down, and where that was measured.
struct ChoiceRule {
    std::optional<DeviceKind> device;
    std::optional<bool> meshes;
    std::array<Ranked, 3> ranking;
    const char* scenes;      // "room, cornell": the bench's scenes of this situation
    const char* source;      // "bench/results/efficiency.md"; "": nothing measured
    const char* unmeasured;  // without a source: why the ranking stands
};

std::span<const ChoiceRule> backend_choice_rules();

// The first rule covering `situation` (the table ends with one covering all).
const ChoiceRule& rule_for(const Situation& situation);

// A flag given on the command line that only some backends take
// ("--profile": wavefront and megakernel).
struct LimitingFlag {
    std::string flag;
    std::vector<std::string> backends;
    // Of `backends`, those that take the flag only tracing with our BVH (the
    // wavefront's sppm integrator): where one is ranked with Embree, its
    // figures do not hold under the flag, so it does not take it there.
    std::vector<std::string> bvh_only = {};
};

struct BackendChoice {
    std::string backend;
    std::string situation;  // "CPU device, no meshes", then ", --profile given" for limiting flags
    std::string evidence;   // "with bvh: 1.9-2.1x the efficiency of the wavefront with bvh on room, cornell in ..."
};

// No backend takes every limiting flag given: one line naming them.
class NoBackendTakesTheFlags : public std::invalid_argument {
 public:
    using std::invalid_argument::invalid_argument;
};

// The highest-ranked backend of rule_for(situation) that takes every flag
// in `flags`, and why. Throws NoBackendTakesTheFlags.
BackendChoice choose_backend(const Situation& situation, const std::vector<LimitingFlag>& flags = {});

// The same choice by `rule`'s ranking (rule_for's, above), which covers `situation`.
BackendChoice choose_backend(const ChoiceRule& rule, const Situation& situation,
                             const std::vector<LimitingFlag>& flags = {});

// "auto: CPU device, no meshes: 1.9-2.1x ...".
std::string explain_choice(const BackendChoice& choice);

}  // namespace wp::cli
