#include "opencl/lanes.h"

#include <algorithm>
#include <stdexcept>

namespace wp {
namespace {

const char* backend_name(LaneProgram::Backend backend) {
    return backend == LaneProgram::Backend::Wavefront ? "wavefront" : "megakernel";
}

unsigned default_lanes(const LaneProgram& program, const DeviceInfo& device) {
    // As many lanes as the device's vectors hold (vector_lanes), up to the
    // most each backend takes (measured by bench/run.py --series lanes).
    switch (program.backend) {
        case LaneProgram::Backend::Wavefront:
            // Atomic pushes are per work item. Meshes get as many lanes as
            // the others: the stages that trace lose less than the others
            // gain (docs/architecture.md, "Meshes and their BVH").
            return program.scan_compaction ? vector_lanes(device, 16) : 1;
        case LaneProgram::Backend::Megakernel:
            // Not for meshes: a lane's BVH traversal diverges from the
            // others' at every node, and a work item waits for its longest
            // path, so whole paths of several such lanes ran slower than one.
            return vector_lanes(device, program.meshes ? 1 : 16);
    }
    return 1;
}

}  // namespace

unsigned vector_lanes(const DeviceInfo& device, unsigned widest) {
    if (device.type != "CPU") return 1;
    unsigned lanes = 1;
    for (unsigned wider = 2; wider <= std::min(widest, device.preferred_float_vector_width); wider *= 2)
        if (lanes_compiled(wider)) lanes = wider;
    return lanes;
}

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
