// The wavefront's device objects: the program built for the scene, the stage
// kernels, the path state, the scene buffers, the queues and the film, and
// the operations the scheduler (and the stage tests) compose.
#pragma once

#include <CL/opencl.hpp>
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "core/render.h"
#include "device/opencl_device.h"
#include "device/program_cache.h"
#include "scene/scene.h"
#include "wavefront/path_state.h"
#include "wavefront/profile.h"
#include "wavefront/scene_upload.h"

namespace wp {

namespace device_layout {
#include "common/queues.h"
}  // namespace device_layout

enum class Stage { Generate, Intersect, ShadeDirect, IntersectShadow, Scatter };
inline constexpr std::array<const char*, 5> stage_kernel_names{"generate", "intersect", "shade_direct",
                                                               "intersect_shadow", "scatter"};

// How the stages fill the next stage's queue.
enum class Compaction {
    Atomic,  // a push through a global atomic counter, aggregated per work group (queue order not stable)
    Scan,    // marks per slot, then a prefix sum over them (kernels/compact.cl): ascending slot order
};

struct PipelineOptions {
    bool profile = false;  // time every kernel with OpenCL events and count rays per depth (count_depths.cl)
    Compaction compaction = Compaction::Atomic;
    unsigned lanes = 0;  // paths per work item in the stage kernels (1 or 8); 0: automatic_lanes()
    Progress progress;   // told when the kernels are compiled (a program cache miss)
};

// The lanes the stage kernels use by default: 8 on CPU devices, where a work
// item's vector code is the only SIMD there is (kernels/common/prelude.h), 1
// elsewhere (GPUs run work items in SIMD already); 1 with atomic compaction,
// whose pushes are per work item.
unsigned automatic_lanes(const DeviceInfo& device, Compaction compaction);

// The roofline of the tracing stages, measured by kernels/intersect_bound.cl.
struct IntersectBound {
    double rays_per_s = 0.0;        // rays over the best of three launches' device time
    double hit_distance_sum = 0.0;  // over the rays that hit something: what the kernel computed, for tests
};

// Queue lengths then counters, as in kernels/common/queues.h.
using DeviceCounts = std::array<std::uint32_t, WP_COUNTS_SIZE>;

static_assert(WP_NONFINITE_STAGE_COUNT == nonfinite_stage_names.size());

// The per-stage non-finite counters among the device counters (the megakernel's).
inline NonfiniteCounts nonfinite_counts(const std::uint32_t* counts) {
    NonfiniteCounts by_stage{};
    for (std::size_t i = 0; i < by_stage.size(); ++i) by_stage[i] = counts[WP_COUNTER_NONFINITE_EMISSION + i];
    return by_stage;
}

class Pipeline {
 public:
    // capacity: paths in flight; pass_capacity: most work items per pass.
    // The kernels are compiled for `kernel_features`, normally scene.features()
    // (a superset also renders the scene, only slower).
    Pipeline(const Scene& scene, const DeviceInfo& device, std::size_t capacity, std::size_t pass_capacity,
             const FeatureSet& kernel_features, const PipelineOptions& options = {});
    Pipeline(const Scene& scene, const DeviceInfo& device, std::size_t capacity, std::size_t pass_capacity)
        : Pipeline(scene, device, capacity, pass_capacity, scene.features()) {}

    // The program (every kernel file, built with -DWP_LANES=lanes()).
    const BuiltProgram& program() const { return program_; }
    unsigned lanes() const { return lanes_; }
    const PathState& state() const { return state_; }
    std::size_t capacity() const { return capacity_; }
    std::size_t pass_capacity() const { return pass_capacity_; }
    cl::CommandQueue& queue() { return queue_; }

    // Starts the pass of work items [start, start + size): every slot free,
    // every other queue empty, the work counter at 0.
    void begin_pass(std::uint64_t start, std::uint32_t size);
    // Tells the next generate how many work items of the pass earlier ones handed out.
    void set_issued(std::uint32_t issued);
    // Enqueues a stage over the queues' capacity (it reads its queue's length on
    // the device); with profiling, the count of its rays by depth first.
    void run(Stage stage);
    // The queue bookkeeping once `stage` has run, so that the queues it filled
    // are ready for their consumers and the ones it consumed can refill.
    // Atomic: clears the lengths of the queues filled next. Scan: clears the
    // marks of the queue it consumed and compacts the queues it filled whose
    // consumer runs next (FREE and RAY after scatter, so that the iteration's
    // lengths can be read).
    void finish_stage(Stage stage);
    // Sets lengths [first, first + n) of `counts` to 0.
    void clear_counts(std::uint32_t first, std::uint32_t n);
    // Waits for the queue; with profiling, adds the finished kernels' times to profile().
    DeviceCounts read_counts();
    // The non-finite values the stages dropped since the last call, by stage.
    NonfiniteCounts take_nonfinite();
    // Adds the drained pass's entries to the film, per pixel in sample order.
    void accumulate();
    // Per-pixel RGB sums over all passes so far.
    std::vector<double> read_film();

    // Kernel launches and device times so far (profiling only; items are the scheduler's to fill in).
    WavefrontProfile& profile() { return profile_; }
    // Extension and shadow rays counted per depth (profiling only).
    void read_rays_by_depth(WavefrontProfile& profile);

    // Traces `rays` camera rays through pixel centres with nothing but the
    // ray-primitive tests (intersect_bound.cl): the bound the intersect stages'
    // rays/s is measured against. Needs profiling (it times with events); not
    // added to profile(), so call it after the render.
    IntersectBound measure_intersect_bound(std::uint32_t rays);

    // For stage tests: set a queue's slots and length, read the pass entries.
    void set_queue(std::uint32_t queue, const std::vector<std::uint32_t>& slots);
    std::vector<std::uint32_t> read_queue(std::uint32_t queue);
    std::vector<float> read_pass_radiance();
    template <class T>
    void write_field(const std::string& name, const std::vector<T>& values) {
        queue_.enqueueWriteBuffer(state_.field(name), CL_TRUE, 0, sizeof(T) * values.size(), values.data());
    }
    template <class T>
    std::vector<T> read_field(const std::string& name) {
        std::vector<T> values(capacity_);
        queue_.enqueueReadBuffer(state_.field(name), CL_TRUE, 0, sizeof(T) * values.size(), values.data());
        return values;
    }

 private:
    std::size_t capacity_, pass_capacity_, pixel_count_;
    bool film_double_;
    unsigned lanes_;
    cl::Context context_;
    cl::CommandQueue queue_;
    BuiltProgram program_;
    DeviceScene scene_;
    PathState state_;
    cl::Buffer queues_, counts_, pass_radiance_, slot_nonfinite_, film_, identity_slots_;
    std::vector<cl::Kernel> stages_;
    cl::Kernel accumulate_, compact_count_, compact_scan_, compact_write_, count_depths_;
    cl::Buffer block_counts_;

    void clear_marks(std::uint32_t queue);
    void compact(std::uint32_t queue_mask);
    void count_depths(std::uint32_t queue, std::uint32_t histogram_offset);
    std::uint32_t issued_ = 0;  // host copy of the last set_issued value, read by the queue
    std::uint64_t pass_start_ = 0;
    std::uint32_t pass_size_ = 0;
    bool profiling_;
    Compaction compaction_;
    WavefrontProfile profile_;
    std::vector<std::pair<const char*, cl::Event>> pending_events_;  // launched, not yet timed
    cl_ulong last_kernel_end_ = 0;

    // Launches `items` work items (rounded up to whole groups of `group`; 0: exactly, groups left to the driver).
    void enqueue(cl::Kernel& kernel, const char* name, std::size_t items, std::size_t group = WP_GROUP_SIZE);
    void time_finished_kernels();
};

// The film's per-pixel RGB sums (double, or compensated float without fp64),
// shared with the megakernel, which accumulates with the same accumulate.cl.
std::vector<double> read_film_sums(cl::CommandQueue& queue, const cl::Buffer& film, std::size_t pixel_count,
                                   bool film_double);
// A zeroed film buffer for `pixel_count` pixels.
cl::Buffer make_film(const cl::Context& context, cl::CommandQueue& queue, std::size_t pixel_count, bool film_double);
// Binds accumulate.cl's arguments for the pass [pass_start, pass_start + pass_size).
void set_accumulate_args(cl::Kernel& accumulate, std::uint64_t pass_start, std::uint32_t pass_size,
                         std::size_t pixel_count, const cl::Buffer& pass_radiance, const cl::Buffer& film);

// The kernel files of the program, in build order.
const std::vector<std::string>& wavefront_kernel_files();

}  // namespace wp
