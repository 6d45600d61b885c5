#include "opencl/lanes.h"

#include <stdexcept>

namespace wp {
namespace {

const char* backend_name(LaneProgram::Backend backend) {
    return backend == LaneProgram::Backend::Wavefront ? "wavefront" : "megakernel";
}

// As many lanes as the device's preferred float vector holds, 16 on AVX-512, else 8.
unsigned vector_lanes(const DeviceInfo& device) { return device.preferred_float_vector_width >= 16 ? 16 : 8; }

unsigned default_lanes(const LaneProgram& program, const DeviceInfo& device) {
    // A GPU runs work items in SIMD already; on a CPU a work item's vector
    // code is the only SIMD PoCL gives (kernels/shared/prelude.h). The counts
    // are bench/run.py --series lanes' (bench/results/lanes*.md).
    if (device.type != "CPU") return 1;
    switch (program.backend) {
        case LaneProgram::Backend::Wavefront:
            // Atomic pushes are per work item. Meshes get 8 lanes: the stages
            // that trace lose less than the others gain (docs/architecture.md,
            // "Meshes and their BVH"), and 16 measured no faster than 8 on
            // the bunny. Without meshes, vector_lanes: 16 measured faster than
            // 8 on AVX-512 since one kernel traces and shades
            // (lanes_wavefront.md).
            if (!program.scan_compaction) return 1;
            return program.meshes ? 8 : vector_lanes(device);
        case LaneProgram::Backend::Megakernel:
            // Not for meshes: a lane's BVH traversal diverges from the
            // others' at every node, and a work item waits for its longest
            // path, so whole paths of 8 such lanes ran slower than one lane
            // (bench/results/analysis.md, "Lanes with meshes"). Without
            // meshes, vector_lanes: 16 measured faster than 8 on AVX-512.
            return program.meshes ? 1 : vector_lanes(device);
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
