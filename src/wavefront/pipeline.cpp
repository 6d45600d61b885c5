#include "wavefront/pipeline.h"

#include <algorithm>
#include <limits>
#include <numeric>
#include <stdexcept>

#include "wavefront/kernel_options.h"

namespace wp {
namespace {

std::size_t round_up(std::size_t n, std::size_t multiple) { return (n + multiple - 1) / multiple * multiple; }

std::string stage_options(const Scene& scene, const DeviceInfo& device, const FeatureSet& kernel_features,
                          Compaction compaction) {
    return kernel_build_options(kernel_features, uses_nee(scene), device.fp64, scene.render) +
           shape_count_options(scene) + (compaction == Compaction::Scan ? " -DWP_COMPACT_SCAN" : "");
}

unsigned checked_lanes(unsigned lanes, Compaction compaction) {
    if ((lanes != 1 && lanes != 8) || (lanes != 1 && compaction != Compaction::Scan))
        throw std::invalid_argument("wavefront lanes must be 1, or 8 with scan compaction");
    return lanes;
}

}  // namespace

const std::vector<std::string>& wavefront_kernel_files() {
    static const std::vector<std::string> files{"generate.cl",         "intersect.cl",    "shade_direct.cl",
                                                "intersect_shadow.cl", "scatter.cl",      "compact.cl",
                                                "accumulate.cl",       "count_depths.cl", "intersect_bound.cl"};
    return files;
}

unsigned automatic_lanes(const DeviceInfo& device, Compaction compaction) {
    return device.type == "CPU" && compaction == Compaction::Scan ? 8u : 1u;
}

Pipeline::Pipeline(const Scene& scene, const DeviceInfo& device, std::size_t capacity, std::size_t pass_capacity,
                   const FeatureSet& kernel_features, const PipelineOptions& options)
    : capacity_(capacity),
      pass_capacity_(pass_capacity),
      pixel_count_(std::size_t(scene.camera.width) * scene.camera.height),
      film_double_(device.fp64),
      lanes_(checked_lanes(options.lanes != 0 ? options.lanes : automatic_lanes(device, options.compaction),
                           options.compaction)),
      context_(device.device),
      queue_(context_, device.device, options.profile ? cl_command_queue_properties(CL_QUEUE_PROFILING_ENABLE) : 0),
      program_(build_program(
          context_, device, wavefront_kernel_files(),
          stage_options(scene, device, kernel_features, options.compaction) + " -DWP_LANES=" + std::to_string(lanes_),
          options.progress)),
      scene_(context_, flatten_scene(scene)),
      state_(context_, capacity, kernel_features, uses_nee(scene)),
      queues_(context_, CL_MEM_READ_WRITE,
              sizeof(std::uint32_t) * WP_QUEUE_COUNT * capacity * (options.compaction == Compaction::Scan ? 2 : 1)),
      counts_(context_, CL_MEM_READ_WRITE, sizeof(std::uint32_t) * WP_COUNTS_PROFILED_SIZE),
      pass_radiance_(context_, CL_MEM_READ_WRITE, sizeof(float) * 3 * pass_capacity),
      slot_nonfinite_(context_, CL_MEM_READ_WRITE, sizeof(std::uint32_t) * WP_NONFINITE_STAGE_COUNT * capacity),
      film_(make_film(context_, queue_, pixel_count_, film_double_)),
      profiling_(options.profile),
      compaction_(options.compaction),
      block_counts_(context_, CL_MEM_READ_WRITE,
                    sizeof(std::uint32_t) * WP_QUEUE_COUNT * ((capacity + WP_COMPACT_BLOCK - 1) / WP_COMPACT_BLOCK)) {
    std::vector<std::uint32_t> identity(capacity);
    std::iota(identity.begin(), identity.end(), 0u);
    identity_slots_ = cl::Buffer(context_, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, sizeof(std::uint32_t) * capacity,
                                 identity.data());
    queue_.enqueueFillBuffer(counts_, std::uint32_t(0), 0, counts_.getInfo<CL_MEM_SIZE>());
    for (const char* name : stage_kernel_names) {
        cl::Kernel kernel(program_.program, name);
        cl_uint arg = 0;
        for (const cl::Buffer& b : scene_.buffers) kernel.setArg(arg++, b);
        kernel.setArg(arg++, queues_);
        kernel.setArg(arg++, counts_);
        kernel.setArg(arg++, cl_uint(capacity_));
        kernel.setArg(arg++, cl_ulong(0));
        kernel.setArg(arg++, cl_uint(0));
        kernel.setArg(arg++, pass_radiance_);
        kernel.setArg(arg++, slot_nonfinite_);
        for (const cl::Buffer& b : state_.buffers()) kernel.setArg(arg++, b);
        stages_.push_back(kernel);
    }
    accumulate_ = cl::Kernel(program_.program, "accumulate");
    compact_count_ = cl::Kernel(program_.program, "compact_count");
    compact_scan_ = cl::Kernel(program_.program, "compact_scan");
    compact_write_ = cl::Kernel(program_.program, "compact_write");
    for (cl::Kernel* k : {&compact_count_, &compact_write_}) {
        k->setArg(0, queues_);
        k->setArg(1, cl_uint(capacity_));
        k->setArg(3, block_counts_);
    }
    compact_scan_.setArg(0, cl_uint(capacity_));
    compact_scan_.setArg(2, block_counts_);
    compact_scan_.setArg(3, counts_);
    count_depths_ = cl::Kernel(program_.program, "count_depths");
    count_depths_.setArg(0, queues_);
    count_depths_.setArg(1, counts_);
    count_depths_.setArg(2, cl_uint(capacity_));
    count_depths_.setArg(5, state_.field("depth"));
    queue_.enqueueFillBuffer(slot_nonfinite_, std::uint32_t(0), 0, slot_nonfinite_.getInfo<CL_MEM_SIZE>());
    if (compaction_ == Compaction::Scan)
        queue_.enqueueFillBuffer(queues_, std::uint32_t(0), 0, queues_.getInfo<CL_MEM_SIZE>());
}

// Argument positions of the pass in WP_STAGE_PARAMS.
constexpr cl_uint kPassStartArg = 10, kPassSizeArg = 11;

void Pipeline::begin_pass(std::uint64_t start, std::uint32_t size) {
    pass_start_ = start;
    pass_size_ = size;
    for (cl::Kernel& k : stages_) {
        k.setArg(kPassStartArg, cl_ulong(start));
        k.setArg(kPassSizeArg, cl_uint(size));
    }
    if (compaction_ == Compaction::Scan)  // no marks left from the last pass
        queue_.enqueueFillBuffer(queues_, std::uint32_t(0), WP_QUEUE_COUNT * capacity_ * sizeof(std::uint32_t),
                                 WP_QUEUE_COUNT * capacity_ * sizeof(std::uint32_t));
    queue_.enqueueCopyBuffer(identity_slots_, queues_, 0, WP_QUEUE_FREE * capacity_ * sizeof(std::uint32_t),
                             capacity_ * sizeof(std::uint32_t));
    DeviceCounts counts{};
    counts[WP_QUEUE_FREE] = static_cast<std::uint32_t>(capacity_);
    queue_.enqueueWriteBuffer(counts_, CL_TRUE, 0, sizeof counts, counts.data());
}

void Pipeline::enqueue(cl::Kernel& kernel, const char* name, std::size_t items, std::size_t group) {
    cl::Event event;
    queue_.enqueueNDRangeKernel(kernel, cl::NullRange, cl::NDRange(group ? round_up(items, group) : items),
                                group ? cl::NDRange(group) : cl::NullRange, nullptr, profiling_ ? &event : nullptr);
    if (profiling_) pending_events_.emplace_back(name, event);
}

void Pipeline::set_issued(std::uint32_t issued) {
    issued_ = issued;
    queue_.enqueueWriteBuffer(counts_, CL_FALSE, WP_COUNTER_WORK * sizeof(std::uint32_t), sizeof issued_, &issued_);
}

void Pipeline::run(Stage stage) {
    if (profiling_ && stage == Stage::Intersect) count_depths(WP_QUEUE_RAY, WP_PROFILE_EXTENSION_BY_DEPTH);
    if (profiling_ && stage == Stage::IntersectShadow) count_depths(WP_QUEUE_SHADOW, WP_PROFILE_SHADOW_BY_DEPTH);
    int index = static_cast<int>(stage);
    enqueue(stages_[index], stage_kernel_names[index], (capacity_ + lanes_ - 1) / lanes_);
}

void Pipeline::count_depths(std::uint32_t queue, std::uint32_t histogram_offset) {
    count_depths_.setArg(3, cl_uint(queue));
    count_depths_.setArg(4, cl_uint(histogram_offset));
    enqueue(count_depths_, "count_depths", capacity_);
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

void Pipeline::finish_stage(Stage stage) {
    auto bit = [](std::uint32_t queue) { return 1u << queue; };
    if (compaction_ == Compaction::Atomic) {
        if (stage == Stage::Generate) clear_counts(WP_QUEUE_FREE, 2);  // FREE consumed; HIT filled next
        if (stage == Stage::Intersect) clear_counts(WP_QUEUE_RAY, 3);  // RAY consumed; SHADOW, SCATTER filled next
        return;
    }
    switch (stage) {
        case Stage::Generate:
            clear_marks(WP_QUEUE_FREE);
            compact(bit(WP_QUEUE_RAY));  // continuing paths and new camera rays
            break;
        case Stage::Intersect:
            clear_marks(WP_QUEUE_RAY);
            compact(bit(WP_QUEUE_HIT));
            break;
        case Stage::ShadeDirect:
            clear_marks(WP_QUEUE_HIT);
            compact(bit(WP_QUEUE_SHADOW) | bit(WP_QUEUE_SCATTER));
            break;
        case Stage::IntersectShadow:
            clear_marks(WP_QUEUE_SHADOW);
            break;
        case Stage::Scatter:
            clear_marks(WP_QUEUE_SCATTER);
            compact(bit(WP_QUEUE_FREE) | bit(WP_QUEUE_RAY));
            break;
    }
}

void Pipeline::clear_marks(std::uint32_t queue) {
    queue_.enqueueFillBuffer(queues_, std::uint32_t(0), WP_QUEUE_MARKS(queue) * capacity_ * sizeof(std::uint32_t),
                             capacity_ * sizeof(std::uint32_t));
}

void Pipeline::compact(std::uint32_t queue_mask) {
    std::size_t blocks = (capacity_ + WP_COMPACT_BLOCK - 1) / WP_COMPACT_BLOCK;
    compact_count_.setArg(2, cl_uint(queue_mask));
    compact_scan_.setArg(1, cl_uint(queue_mask));
    compact_write_.setArg(2, cl_uint(queue_mask));
    enqueue(compact_count_, "compact_count", blocks, 0);
    enqueue(compact_scan_, "compact_scan", WP_QUEUE_COUNT, 0);
    enqueue(compact_write_, "compact_write", blocks, 0);
}

void Pipeline::time_finished_kernels() {
    for (auto& [name, event] : pending_events_) {
        cl_ulong start = event.getProfilingInfo<CL_PROFILING_COMMAND_START>();
        cl_ulong end = event.getProfilingInfo<CL_PROFILING_COMMAND_END>();
        KernelProfile& k = profile_.kernel(name);
        ++k.launches;
        k.device_s += double(end - start) * 1e-9;
        if (last_kernel_end_ != 0 && start > last_kernel_end_)
            profile_.gaps_s += double(start - last_kernel_end_) * 1e-9;
        last_kernel_end_ = std::max(last_kernel_end_, end);
    }
    pending_events_.clear();
}

IntersectBound Pipeline::measure_intersect_bound(std::uint32_t rays) {
    if (!profiling_) throw std::logic_error("measure_intersect_bound needs a pipeline built with profiling");
    std::size_t items = round_up((rays + lanes_ - 1) / lanes_, WP_GROUP_SIZE);
    cl::Buffer hit_t(context_, CL_MEM_WRITE_ONLY, sizeof(float) * rays);
    cl::Kernel kernel(program_.program, "intersect_bound");
    cl_uint arg = 0;
    for (const cl::Buffer& b : scene_.buffers) kernel.setArg(arg++, b);
    kernel.setArg(arg++, cl_uint(rays));
    kernel.setArg(arg++, hit_t);
    // Launch 0 is not timed: PoCL compiles the kernel for its launch geometry then.
    double best_s = std::numeric_limits<double>::infinity();
    for (int launch = 0; launch <= 3; ++launch) {
        cl::Event event;
        queue_.enqueueNDRangeKernel(kernel, cl::NullRange, cl::NDRange(items), cl::NDRange(WP_GROUP_SIZE), nullptr,
                                    &event);
        event.wait();
        double seconds = double(event.getProfilingInfo<CL_PROFILING_COMMAND_END>() -
                                event.getProfilingInfo<CL_PROFILING_COMMAND_START>()) *
                         1e-9;
        if (launch > 0) best_s = std::min(best_s, seconds);
    }
    std::vector<float> distances(rays);
    queue_.enqueueReadBuffer(hit_t, CL_TRUE, 0, sizeof(float) * rays, distances.data());
    return {double(rays) / best_s, std::accumulate(distances.begin(), distances.end(), 0.0)};
}

void Pipeline::read_rays_by_depth(WavefrontProfile& profile) {
    std::vector<std::uint32_t> histograms(2 * WP_PROFILE_DEPTHS);
    queue_.enqueueReadBuffer(counts_, CL_TRUE, WP_PROFILE_EXTENSION_BY_DEPTH * sizeof(std::uint32_t),
                             histograms.size() * sizeof(std::uint32_t), histograms.data());
    profile.extension_rays_by_depth.assign(histograms.begin(), histograms.begin() + WP_PROFILE_DEPTHS);
    profile.shadow_rays_by_depth.assign(histograms.begin() + WP_PROFILE_DEPTHS, histograms.end());
}

void Pipeline::clear_counts(std::uint32_t first, std::uint32_t n) {
    queue_.enqueueFillBuffer(counts_, std::uint32_t(0), first * sizeof(std::uint32_t), n * sizeof(std::uint32_t));
}

DeviceCounts Pipeline::read_counts() {
    DeviceCounts counts;
    queue_.enqueueReadBuffer(counts_, CL_TRUE, 0, sizeof counts, counts.data());
    if (profiling_) time_finished_kernels();
    return counts;
}

void Pipeline::accumulate() {
    set_accumulate_args(accumulate_, pass_start_, pass_size_, pixel_count_, pass_radiance_, film_);
    enqueue(accumulate_, "accumulate", pixel_count_);
}

std::vector<double> Pipeline::read_film() {
    std::vector<double> sums = read_film_sums(queue_, film_, pixel_count_, film_double_);
    if (profiling_) time_finished_kernels();
    return sums;
}

std::vector<double> read_film_sums(cl::CommandQueue& queue, const cl::Buffer& film, std::size_t pixel_count,
                                   bool film_double) {
    std::vector<double> sums(3 * pixel_count);
    if (film_double) {
        queue.enqueueReadBuffer(film, CL_TRUE, 0, sizeof(double) * sums.size(), sums.data());
    } else {
        std::vector<float> values(6 * pixel_count);  // sums, then Kahan compensations
        queue.enqueueReadBuffer(film, CL_TRUE, 0, sizeof(float) * values.size(), values.data());
        for (std::size_t i = 0; i < sums.size(); ++i) sums[i] = double(values[i]) - double(values[sums.size() + i]);
    }
    return sums;
}

cl::Buffer make_film(const cl::Context& context, cl::CommandQueue& queue, std::size_t pixel_count, bool film_double) {
    cl::Buffer film(context, CL_MEM_READ_WRITE,
                    film_double ? sizeof(double) * 3 * pixel_count : sizeof(float) * 6 * pixel_count);
    queue.enqueueFillBuffer(film, std::uint8_t(0), 0, film.getInfo<CL_MEM_SIZE>());
    return film;
}

void set_accumulate_args(cl::Kernel& accumulate, std::uint64_t pass_start, std::uint32_t pass_size,
                         std::size_t pixel_count, const cl::Buffer& pass_radiance, const cl::Buffer& film) {
    accumulate.setArg(0, cl_ulong(pass_start));
    accumulate.setArg(1, cl_uint(pass_size));
    accumulate.setArg(2, cl_uint(pixel_count));
    accumulate.setArg(3, pass_radiance);
    accumulate.setArg(4, film);
}

void Pipeline::set_queue(std::uint32_t queue, const std::vector<std::uint32_t>& slots) {
    queue_.enqueueWriteBuffer(queues_, CL_TRUE, queue * capacity_ * sizeof(std::uint32_t),
                              slots.size() * sizeof(std::uint32_t), slots.data());
    std::uint32_t length = static_cast<std::uint32_t>(slots.size());
    queue_.enqueueWriteBuffer(counts_, CL_TRUE, queue * sizeof(std::uint32_t), sizeof length, &length);
}

std::vector<std::uint32_t> Pipeline::read_queue(std::uint32_t queue) {
    std::vector<std::uint32_t> slots(read_counts()[queue]);
    if (!slots.empty())
        queue_.enqueueReadBuffer(queues_, CL_TRUE, queue * capacity_ * sizeof(std::uint32_t),
                                 slots.size() * sizeof(std::uint32_t), slots.data());
    return slots;
}

std::vector<float> Pipeline::read_pass_radiance() {
    std::vector<float> values(3 * pass_capacity_);
    queue_.enqueueReadBuffer(pass_radiance_, CL_TRUE, 0, sizeof(float) * values.size(), values.data());
    return values;
}

}  // namespace wp
