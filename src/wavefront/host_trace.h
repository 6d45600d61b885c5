// The wavefront's tracing stages traced on the host (--intersector embree,
// CPU devices): before the kernel of a stage that traces (StageTrace,
// kernels/interface/stages.h), the host maps the queue the stage consumes,
// its length and the path state its rays live in, traces the queue with the
// Embree intersector (accel/embree_intersector.h) on its worker threads,
// writes each ray's hit or verdict by slot into the path state, and unmaps;
// the kernel, built with WP_HOST_TRACED, reads those and does the rest of
// the stage (the background, ended paths, pushes, the light's
// contribution). The queue graph is the declared one; only who computes
// the hits changes.
//
// The buffers are allocated for the host (CL_MEM_ALLOC_HOST_PTR), so that
// on a CPU device a map is the buffer's own memory, without a copy. A map
// waits for the device's earlier commands: each traced stage is a point
// where host and device take turns.
#pragma once

#include <CL/opencl.hpp>
#include <cstddef>
#include <string>
#include <vector>

#include "accel/embree_intersector.h"
#include "wavefront/path_state.h"
#include "wavefront/queue_set.h"
#include "wavefront/stage.h"

namespace wp {

// The path state fields the host reads (the rays: origin and direction, and
// for any hit the segment's length) and writes (the results) in tracing a
// stage's rays; none for NO_RAYS.
struct HostTraceFields {
    std::vector<std::string> reads, writes;
};
HostTraceFields host_trace_fields(StageTrace traces);

// "embree:intersect": the profile's row of the host's part of a stage.
std::string host_trace_row(const StageDeclaration& stage);

class HostTrace {
 public:
    // `triangles`: the scene's mesh triangles in the kernels' order (the scene's: no BVH is built where the host
    // traces).
    HostTrace(const Scene& scene, std::vector<SharedMath<float>::MeshTriangle> triangles);

    // Traces the rays of the queue `stage` consumes (a stage that traces),
    // after the device has finished every command before; returns the
    // host's seconds from then until the unmaps are enqueued.
    double trace(cl::CommandQueue& queue, const QueueSet& queues, const PathState& state, std::size_t capacity,
                 Stage stage);

    const EmbreeIntersector& intersector() const { return embree_; }

 private:
    EmbreeIntersector embree_;
};

}  // namespace wp
