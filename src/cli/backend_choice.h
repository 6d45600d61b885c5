// --backend auto, the default: the backend chosen for the device and the
// scene from the bench's figures. The policy is the table in
// backend_choice.cpp, one rule per kind of device and scene, each citing
// the bench/results file its figures come from (tests/cli check them
// against that file). The intersector and the lanes, once they are
// choices, become columns of the same table: a field in Situation for
// what they depend on, one in ChoiceRule and BackendChoice for what is
// picked.
#pragma once

#include <optional>
#include <span>
#include <string>

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

// One row of the table: the situations it covers (unset: any), what it
// picks, and the measured evidence.
struct ChoiceRule {
    std::optional<DeviceKind> device;
    std::optional<bool> meshes;
    const char* backend;
    // Against the runner-up: its efficiency ratio, lowest and highest over
    // the scenes named, as measured in `source` ("": nothing measured, and
    // `unmeasured` says why the pick stands).
    const char* runner_up;
    double ratio_low, ratio_high;
    const char* scenes;  // "room, cornell": bench scenes of this situation
    const char* source;
    const char* unmeasured;
};

std::span<const ChoiceRule> backend_choice_rules();

struct BackendChoice {
    std::string backend;
    std::string situation;  // "CPU device, no meshes", or the flags that decided
    std::string evidence;   // "1.9-2.1x the wavefront's efficiency on room, cornell in bench/results/efficiency.md"
};

// The first rule covering `situation` (the table ends with one covering all).
const ChoiceRule& rule_for(const Situation& situation);

// rule_for's pick and why.
BackendChoice choose_backend(const Situation& situation);

// "auto: CPU device, no meshes: 1.9-2.1x ...".
std::string explain_choice(const BackendChoice& choice);

}  // namespace wp::cli
