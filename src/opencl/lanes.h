// Lanes: the paths a work item of a program runs at once, as vector code
// (-DWP_LANES; docs/architecture.md, "Lanes"). Both OpenCL backends compile
// 1, 4, 8 or 16; which they take by default is each one's own policy, stated
// side by side in resolve_lanes.
#pragma once

#include <string>

#include "opencl/device.h"

namespace wp {

// The program whose lanes are chosen: its backend, and what decides there.
struct LaneProgram {
    enum class Backend { Wavefront, Megakernel };
    Backend backend;
    bool scan_compaction = false;  // the wavefront's: its queues filled by scans, not atomic pushes
    bool meshes = false;           // the scene has triangle meshes

    static LaneProgram wavefront(bool scan_compaction, bool meshes) {
        return {Backend::Wavefront, scan_compaction, meshes};
    }
    static LaneProgram megakernel(bool meshes) { return {Backend::Megakernel, false, meshes}; }
};

// Whether the kernels compile for `lanes` paths per work item
// (kernels/shared/prelude.h, "Lanes").
inline constexpr bool lanes_compiled(unsigned lanes) { return lanes == 1 || lanes == 4 || lanes == 8 || lanes == 16; }

// Why `program` cannot run `lanes` paths per work item, or "" when it can.
std::string lanes_problem(unsigned lanes, const LaneProgram& program);

// The lanes `program` uses on `device`: `requested` (1, 4, 8 or 16), or when 0 the
// backend's default there. Throws std::invalid_argument with lanes_problem's words.
unsigned resolve_lanes(unsigned requested, const LaneProgram& program, const DeviceInfo& device);

}  // namespace wp
