#include "wavefront/pipeline.h"

#include <numeric>
#include <stdexcept>

#include "opencl/kernel_arguments.h"
#include "opencl/kernel_options.h"

namespace wp {
namespace {

// The kernel of a declared stage, or a DeviceError naming the stage whose file defines no such kernel.
cl::Kernel stage_kernel(const cl::Program& program, const StageDeclaration& stage) {
    try {
        return cl::Kernel(program, stage.kernel);
    } catch (const cl::Error&) {
        throw DeviceError(std::string("stage ") + stage.kernel + " (kernels/interface/stages.h) has no kernel " +
                          stage.kernel + " in kernels/" + stage.kernel + ".cl");
    }
}

}  // namespace

const std::vector<std::string>& wavefront_kernel_files() {
    static const std::vector<std::string> files = [] {
        std::vector<std::string> names;
        for (const StageDeclaration& stage : stage_declarations) names.push_back(std::string(stage.kernel) + ".cl");
        for (const char* other : {"compact.cl", "accumulate.cl", "count_depths.cl", "intersect_bound.cl",
                                  "photon_grid.cl", "sppm_update.cl"})
            names.push_back(other);
        return names;
    }();
    return files;
}

KernelProgram pipeline_program(const Scene& scene, const DeviceInfo& device, const FeatureSet& kernel_features,
                               const PipelineOptions& options) {
    KernelProgram program;
    program.files = wavefront_kernel_files();
    program.lanes = resolve_lanes(options.lanes, wavefront_lanes(options.compaction, scene.features().meshes), device);
    program.options = program_build_options(scene, kernel_features, options.film_squares,
                                            compaction_build_option(options.compaction), program.lanes);
    return program;
}

Pipeline::Pipeline(const Scene& scene, const DeviceInfo& device, std::size_t capacity, std::size_t pass_capacity,
                   const FeatureSet& kernel_features, const PipelineOptions& options)
    : Pipeline(scene, flatten_scene(scene, kernel_features.host_traced ? Intersector::Embree : Intersector::Bvh),
               device, capacity, pass_capacity, kernel_features, options,
               pipeline_program(scene, device, kernel_features, options)) {}

Pipeline::Pipeline(const Scene& scene, SceneLayout layout, const DeviceInfo& device, std::size_t capacity,
                   std::size_t pass_capacity, const FeatureSet& kernel_features, const PipelineOptions& options,
                   const KernelProgram& program)
    : capacity_(capacity),
      pass_capacity_(pass_capacity),
      lanes_(program.lanes),
      iteration_(iteration_stages(kernel_features, StageLoop::CAMERA)),
      photon_iteration_(iteration_stages(kernel_features, StageLoop::PHOTON)),
      context_(device.device),
      queue_(context_, device.device, options.profile ? cl_command_queue_properties(CL_QUEUE_PROFILING_ENABLE) : 0),
      launcher_(queue_, options.profile),
      program_(build_program(context_, device, program.files, program.options, options.progress)),
      host_trace_(kernel_features.host_traced ? std::make_unique<HostTrace>(scene, std::move(layout.triangles))
                                              : nullptr),
      scene_(context_, layout,
             host_trace_ ? host_trace_->intersector().triangle_bytes() : std::span<const std::byte>()),
      state_(context_, capacity, kernel_features),
      queues_(context_, queue_, program_.program, capacity, options.compaction,
              plan_queues(std::vector<std::vector<Stage>>{iteration_, photon_iteration_},
                          options.profile ? RayDepthCounter::kQueuesRead : 0u),
              kernel_features.host_traced),
      film_(context_, queue_, program_.program, scene.camera.width, scene.camera.height, options.film_squares),
      pass_radiance_(context_, CL_MEM_READ_WRITE, sizeof(float) * 3 * pass_capacity),
      slot_nonfinite_(context_, CL_MEM_READ_WRITE, sizeof(std::uint32_t) * WP_NONFINITE_STAGE_COUNT * capacity) {
    layout = SceneLayout{};  // the device buffers have their own
    if (kernel_features.sppm) {
        photons_per_iteration_ = scene.lights.empty() ? 0 : static_cast<std::uint32_t>(sppm_photons(scene));
        sppm_.emplace(context_, queue_, program_.program, scene_, queues_.counts(),
                      std::uint64_t(scene.camera.width) * std::uint64_t(scene.camera.height), lanes_, kernel_features);
    }
    for (const StageDeclaration& stage : stage_declarations) {
        cl::Kernel& kernel = stages_.emplace_back(stage_kernel(program_.program, stage));
        scene_.bind(kernel);
        kernel.setArg(arg::Stage::queues, queues_.queues());
        kernel.setArg(arg::Stage::counts, queues_.counts());
        kernel.setArg(arg::Stage::capacity, cl_uint(capacity_));
        kernel.setArg(arg::Stage::pass_radiance, pass_radiance_);
        kernel.setArg(arg::Stage::slot_nonfinite, slot_nonfinite_);
        state_.bind(kernel);
        if (sppm_) sppm_->state().bind(kernel, arg::Stage::count + state_.field_count());
    }
    bind_round();
    if (options.profile)
        ray_depths_.emplace(program_.program, queues_.queues(), queues_.counts(), capacity, state_.field("depth"),
                            kernel_features.nee);
    queue_.enqueueFillBuffer(slot_nonfinite_, std::uint32_t(0), 0, slot_nonfinite_.getInfo<CL_MEM_SIZE>());
}

Pipeline::~Pipeline() { clFinish(queue_()); }

void Pipeline::begin_pass(std::uint64_t start, std::uint32_t size) {
    pass_start_ = start;
    pass_size_ = size;
    for (cl::Kernel& k : stages_) {
        k.setArg(arg::Stage::pass_start, cl_ulong(start));
        k.setArg(arg::Stage::pass_size, cl_uint(size));
    }
    queues_.reset();
}

void Pipeline::begin_photon_pass(std::uint32_t iteration) {
    pass_start_ = std::uint64_t(iteration) * photons_per_iteration_;
    pass_size_ = photons_per_iteration_;
    for (Stage stage : photon_iteration_) {
        cl::Kernel& k = stages_[static_cast<std::size_t>(stage)];
        k.setArg(arg::Stage::pass_start, cl_ulong(pass_start_));
        k.setArg(arg::Stage::pass_size, cl_uint(pass_size_));
    }
    queues_.reset(WP_QUEUE_PHOTON_FREE);
}

std::uint32_t Pipeline::photon_deposits() { return queues_.read_counts()[WP_COUNTER_PHOTON_DEPOSITS]; }

void Pipeline::run(Stage stage, std::size_t entries) {
    if (entries == 0) return;
    if (ray_depths_ && declaration(stage).consumes == WP_QUEUE_RAY)
        ray_depths_->count_extension_rays(launcher_, entries);
    if (host_trace_ && declaration(stage).traces != StageTrace::NO_RAYS)
        launcher_.add_host_time(host_trace_row(declaration(stage)),
                                host_trace_->trace(queue_, queues_, state_, capacity_, stage));
    launcher_.launch(stages_[static_cast<std::size_t>(stage)], declaration(stage).kernel,
                     divide_rounding_up(entries, lanes_));
}

void Pipeline::finish_stage(Stage stage, std::size_t entries) {
    queues_.finish_stage(launcher_, stage);
    if (ray_depths_ && declaration(stage).pushes >> WP_QUEUE_SHADOW & 1u && entries > 0)
        ray_depths_->count_shadow_rays(launcher_, entries);
}

void Pipeline::start_paths(const std::vector<glm::vec3>& origins, const std::vector<glm::vec3>& directions,
                           std::uint32_t first_sample) {
    std::size_t n = origins.size();
    std::vector<std::uint32_t> slots(n), samples(n);
    std::iota(slots.begin(), slots.end(), 0u);
    std::iota(samples.begin(), samples.end(), first_sample);
    for (std::size_t a = 0; a < 3; ++a) {
        std::vector<float> origin(n), direction(n);
        for (std::size_t i = 0; i < n; ++i) origin[i] = origins[i][a], direction[i] = directions[i][a];
        write_field("origin", origin, a);
        write_field("direction", direction, a);
        write_field("radiance", std::vector<float>(n, 0.0f), a);
        write_field("throughput", std::vector<float>(n, 1.0f), a);
    }
    write_field("pixel", std::vector<std::uint32_t>(n, 0u));
    write_field("sample", samples);
    write_field("pass_item", slots);
    write_field("depth", std::vector<std::uint32_t>(n, 0u));
    if (state_.has_field("specular")) write_field("specular", std::vector<std::uint32_t>(n, 1u));
    begin_pass(0, std::uint32_t(n));
    queues_.set_queue(WP_QUEUE_FREE, {});  // misses and ended paths land there
    queues_.set_queue(WP_QUEUE_RAY, slots);
}

void Pipeline::run_alone(Stage stage) {
    queues_.empty_outputs(stage);
    run(stage, capacity_);
    queues_.compact_outputs(launcher_, stage);
}

DeviceCounts Pipeline::read_counts() {
    DeviceCounts counts = queues_.read_counts();
    launcher_.time_finished(profile_);
    return counts;
}

NonfiniteCounts Pipeline::take_nonfinite() {
    std::vector<std::uint32_t> by_slot(WP_NONFINITE_STAGE_COUNT * capacity_);
    queue_.enqueueReadBuffer(slot_nonfinite_, CL_TRUE, 0, sizeof(std::uint32_t) * by_slot.size(), by_slot.data());
    queue_.enqueueFillBuffer(slot_nonfinite_, std::uint32_t(0), 0, slot_nonfinite_.getInfo<CL_MEM_SIZE>());
    NonfiniteCounts by_stage{};
    for (std::size_t stage = 0; stage < by_stage.size(); ++stage)
        for (std::size_t slot = 0; slot < capacity_; ++slot) by_stage[stage] += by_slot[stage * capacity_ + slot];
    return by_stage;
}

void Pipeline::accumulate() { film_.accumulate(launcher_, pass_start_, pass_size_, pass_radiance_); }

Film Pipeline::read_film(const ItemRange& items) {
    Film film = film_.read(queue_, items);
    launcher_.time_finished(profile_);
    return film;
}

void Pipeline::load_film(const Film& film) { film_.load(queue_, film); }

void Pipeline::set_round_pixels(const std::vector<std::uint32_t>& pixels) {
    film_.set_round_pixels(queue_, pixels);
    bind_round();
}

void Pipeline::bind_round() {
    for (cl::Kernel& k : stages_) film_.bind_round(k, arg::Stage::round_pixels, arg::Stage::round_pixel_count);
}

void Pipeline::read_rays_by_depth(RenderProfile& profile) {
    if (ray_depths_) ray_depths_->read(queue_, profile);
}

IntersectBound Pipeline::measure_intersect_bound(std::uint32_t rays) {
    if (!launcher_.profiling()) throw std::logic_error("measure_intersect_bound needs a pipeline built with profiling");
    return wp::measure_intersect_bound(context_, queue_, program_.program, scene_, lanes_, rays);
}

CopyBandwidth Pipeline::measure_copy_bandwidth(std::uint64_t bytes) {
    if (!launcher_.profiling()) throw std::logic_error("measure_copy_bandwidth needs a pipeline built with profiling");
    return wp::measure_copy_bandwidth(context_, queue_, bytes);
}

std::vector<float> Pipeline::read_pass_radiance() {
    std::vector<float> values(3 * pass_capacity_);
    queue_.enqueueReadBuffer(pass_radiance_, CL_TRUE, 0, sizeof(float) * values.size(), values.data());
    return values;
}

}  // namespace wp
