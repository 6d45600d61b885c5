#include "opencl/lanes.h"

#include <stdexcept>

namespace wp {
namespace {

const char* backend_name(LaneProgram::Backend backend) {
    return backend == LaneProgram::Backend::Wavefront ? "wavefront" : "megakernel";
}

unsigned default_lanes(const LaneProgram& program, const DeviceInfo& device) {
    // A GPU runs work items in SIMD already; on a CPU a work item's vector
    // code is the only SIMD PoCL gives (kernels/shared/prelude.h). The
    // kernels also compile 4 and 16 lanes (--lanes); the defaults stay at the
    // 8 measured (bench/results/defaults.md) until bench/run.py --series lanes
    // shows another count faster.
    if (device.type != "CPU") return 1;
    switch (program.backend) {
        case LaneProgram::Backend::Wavefront:
            // Atomic pushes are per work item. Meshes get 8 lanes too: the
            // stages that trace lose less than the others gain
            // (docs/architecture.md, "Meshes and their BVH").
            return program.scan_compaction ? 8 : 1;
        case LaneProgram::Backend::Megakernel:
            // Not for meshes: a lane's BVH traversal diverges from the
            // others' at every node, and a work item waits for its longest
            // path, so whole paths of 8 such lanes ran slower than one lane
            // (bench/results/analysis.md, "Lanes with meshes").
            return program.meshes ? 1 : 8;
    }
    return 1;
}

}  // namespace

std::string lanes_problem(unsigned lanes, const LaneProgram& program) {
    if (!lanes_compiled(lanes))
        return std::string(backend_name(program.backend)) + " lanes must be 1, 4, 8 or 16, not " +
               std::to_string(lanes);
    if (lanes != 1 && program.backend == LaneProgram::Backend::Wavefront && !program.scan_compaction)
        return "--lanes " + std::to_string(lanes) + " needs --compaction scan (atomic pushes are per work item)";
    return "";
}

unsigned resolve_lanes(unsigned requested, const LaneProgram& program, const DeviceInfo& device) {
    const unsigned lanes = requested != 0 ? requested : default_lanes(program, device);
    if (std::string problem = lanes_problem(lanes, program); !problem.empty()) throw std::invalid_argument(problem);
    return lanes;
}

}  // namespace wp
