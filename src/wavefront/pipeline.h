// The wavefront's device objects: the program built for the scene, the stage
// kernels, the scene, the path state, the queues and the film, and the
// operations the scheduler (and the stage tests) compose. Compaction
// (wavefront/queue_set.h) and profiling (wavefront/profiling.h) are pieces of
// their own.
#pragma once

#include <CL/opencl.hpp>
#include <cstdint>
#include <glm/vec3.hpp>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/render.h"
#include "interface/queues.h"
#include "opencl/device.h"
#include "opencl/film.h"
#include "opencl/launcher.h"
#include "opencl/profile.h"
#include "opencl/program_cache.h"
#include "opencl/scene_upload.h"
#include "scene/scene.h"
#include "wavefront/compaction.h"
#include "wavefront/host_trace.h"
#include "wavefront/path_state.h"
#include "wavefront/profiling.h"
#include "wavefront/queue_set.h"
#include "wavefront/sppm_pass.h"
#include "wavefront/stage.h"

namespace wp {

struct PipelineOptions {
    bool profile = false;  // time every kernel with OpenCL events and count rays per depth (count_depths.cl)
    Compaction compaction = kDefaultCompaction;
    unsigned lanes = 0;         // paths per work item in the stage kernels (1, 4, 8 or 16); 0: resolve_lanes' choice
    Progress progress;          // told when the kernels are compiled (a program cache miss)
    bool film_squares = false;  // the film keeps sums of squares (per-pixel variance)
};

static_assert(WP_NONFINITE_STAGE_COUNT == nonfinite_stage_names.size());

// The program a Pipeline builds for `scene` on `device` (only its type and
// preferred vector width count: opencl/lanes.h) with kernels for
// `kernel_features`: every kernel file (wavefront_kernel_files()), the
// options for those features, the options' compaction and film, and the
// lanes resolve_lanes gives. Throws std::invalid_argument for lanes the
// compaction cannot take.
KernelProgram pipeline_program(const Scene& scene, const DeviceInfo& device, const FeatureSet& kernel_features,
                               const PipelineOptions& options);

class Pipeline {
 public:
    // capacity: paths in flight; pass_capacity: most work items per pass.
    // The kernels are compiled for `kernel_features`, normally scene.features()
    // (a superset also renders the scene, only slower); with
    // kernel_features.host_traced the host traces the stages' rays
    // (wavefront/host_trace.h).
    Pipeline(const Scene& scene, const DeviceInfo& device, std::size_t capacity, std::size_t pass_capacity,
             const FeatureSet& kernel_features, const PipelineOptions& options = {});
    // Waits for the device's commands: its kernels may read the host tracer's triangles in place.
    ~Pipeline();

    // The program (every kernel file, built with -DWP_LANES=lanes()).
    const BuiltProgram& program() const { return program_; }
    unsigned lanes() const { return lanes_; }
    const PathState& state() const { return state_; }
    const DeviceScene& device_scene() const { return scene_; }
    // The host's tracer, where kernel_features.host_traced; else null.
    const HostTrace* host_trace() const { return host_trace_.get(); }
    std::size_t capacity() const { return capacity_; }
    std::size_t pass_capacity() const { return pass_capacity_; }
    QueueSet& queues() { return queues_; }
    // The stages an iteration of the camera pass runs, in order (iteration_stages of the kernel features).
    const std::vector<Stage>& iteration() const { return iteration_; }
    // Those of SPPM's photon pass (none without the sppm integrator).
    const std::vector<Stage>& photon_iteration() const { return photon_iteration_; }
    // SPPM's state and kernels besides the stages (the sppm integrator only).
    SppmPass* sppm() { return sppm_ ? &*sppm_ : nullptr; }
    // SPPM: the photons of an iteration's photon pass (0 without a light to emit them).
    std::uint32_t photons_per_iteration() const { return photons_per_iteration_; }
    KernelLauncher& launcher() { return launcher_; }

    // Starts the pass of work items [start, start + size): every slot free,
    // every other queue empty, the work counter at 0.
    void begin_pass(std::uint64_t start, std::uint32_t size);
    // Starts SPPM's photon pass of iteration `iteration`: its photons are the
    // work items of the pass (emit_photons.cl), every slot is free for them.
    void begin_photon_pass(std::uint32_t iteration);
    // SPPM: the photons added to visible points since the last counter reset
    // (sppm_update.cl counts them; every pass's start resets the counters).
    std::uint32_t photon_deposits();
    // Tells the next generate how many work items of the pass earlier ones handed out.
    void set_issued(std::uint32_t issued) { queues_.set_issued(issued); }
    // An iteration runs each of its stages as start_stage, run, finish_stage.
    // The queue bookkeeping before `stage` (QueueSet::start_stage).
    void start_stage(Stage stage) { queues_.start_stage(stage); }
    // Enqueues a stage over the first `entries` positions of its input queue,
    // which must be at least the queue's length (the kernel reads the length
    // on the device, so the host never waits between stages; positions past
    // it compute and write nothing, but cost as much as live ones, so a
    // nearly drained pass launches only what it can hold); with profiling,
    // the rays of the stage that takes RAY counted by depth first. Where the
    // host traces, it traces a tracing stage's queue first (waiting for the
    // device), its time the profile's host_trace_row. Nothing when `entries`
    // is 0.
    void run(Stage stage, std::size_t entries);
    // The queue bookkeeping once `stage` has run over `entries`
    // (QueueSet::finish_stage); with profiling, after the stage that shades
    // (pushes to SHADOW), the count of the shadow rays by depth from the
    // SHADOW queue it leaves, whichever stage traces them
    // (kernels/interface/stages.h).
    void finish_stage(Stage stage, std::size_t entries);
    // Waits for the queue; with profiling, adds the finished kernels' times to profile().
    DeviceCounts read_counts();
    // The non-finite values the stages dropped since the last call, by stage.
    NonfiniteCounts take_nonfinite();
    // Adds the drained pass's entries to the film, per pixel in sample order.
    void accumulate();
    // The film so far, as the film of `items`; and replacing it.
    Film read_film(const ItemRange& items);
    void load_film(const Film& film);
    // The pixels work items sample from now on (Film::round_pixels; empty: every pixel).
    void set_round_pixels(const std::vector<std::uint32_t>& pixels);

    // Kernel launches and device times so far (profiling only; items are the scheduler's to fill in).
    RenderProfile& profile() { return profile_; }
    // Extension and shadow rays counted per depth (profiling only).
    void read_rays_by_depth(RenderProfile& profile);
    // The roofline (measure_intersect_bound); needs profiling. Not added to
    // profile(), so call it after the render.
    IntersectBound measure_intersect_bound(std::uint32_t rays);
    // The device's copy bandwidth (wp::measure_copy_bandwidth); needs profiling, and is not added to profile().
    CopyBandwidth measure_copy_bandwidth(std::uint64_t bytes);

    // For stage tests and benchmarks: puts fresh paths (depth 0, throughput 1,
    // no radiance, after a "specular" camera vertex) with these rays into
    // slots 0..n-1, path i being sample `first_sample + i` of pixel 0, and
    // queues them all for intersect, with no slot free.
    void start_paths(const std::vector<glm::vec3>& origins, const std::vector<glm::vec3>& directions,
                     std::uint32_t first_sample = 0);
    // For stage tests: runs `stage` alone over the whole capacity, its output
    // queues emptied first and readable after (QueueSet::read_queue).
    void run_alone(Stage stage);
    // For stage tests: a path state field's elements (a vec3 field's
    // `component`: 0, 1, 2 for x, y, z), and the pass entries.
    template <class T>
    void write_field(const std::string& name, const std::vector<T>& values, std::size_t component = 0) {
        queue_.enqueueWriteBuffer(state_.field(name), CL_TRUE, sizeof(T) * capacity_ * component,
                                  sizeof(T) * values.size(), values.data());
    }
    template <class T>
    std::vector<T> read_field(const std::string& name, std::size_t component = 0) {
        std::vector<T> values(capacity_);
        queue_.enqueueReadBuffer(state_.field(name), CL_TRUE, sizeof(T) * capacity_ * component,
                                 sizeof(T) * values.size(), values.data());
        return values;
    }
    std::vector<float> read_pass_radiance();

 private:
    // `layout`: the host's copies, emptied once the device has its own;
    // where the host traces, its triangles go to the host's tracer before.
    Pipeline(const Scene& scene, SceneLayout layout, const DeviceInfo& device, std::size_t capacity,
             std::size_t pass_capacity, const FeatureSet& kernel_features, const PipelineOptions& options,
             const KernelProgram& program);
    void bind_round();

    std::size_t capacity_, pass_capacity_;
    unsigned lanes_;
    std::vector<Stage> iteration_, photon_iteration_;
    cl::Context context_;
    cl::CommandQueue queue_;
    KernelLauncher launcher_;
    BuiltProgram program_;
    std::unique_ptr<HostTrace>
        host_trace_;  // kernel_features.host_traced only; before scene_, which uses its triangles
    DeviceScene scene_;
    PathState state_;
    QueueSet queues_;
    DeviceFilm film_;
    cl::Buffer pass_radiance_, slot_nonfinite_;
    std::optional<SppmPass> sppm_;               // the sppm integrator only
    std::vector<cl::Kernel> stages_;             // by Stage
    std::optional<RayDepthCounter> ray_depths_;  // profiling only
    RenderProfile profile_;
    std::uint64_t pass_start_ = 0;
    std::uint32_t pass_size_ = 0;
    std::uint32_t photons_per_iteration_ = 0;
};

// The kernel files of the program, in build order: the stages' (kernels/<stage>.cl), then the others.
const std::vector<std::string>& wavefront_kernel_files();

}  // namespace wp
