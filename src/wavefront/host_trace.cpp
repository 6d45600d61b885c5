#include "wavefront/host_trace.h"

#include <chrono>
#include <span>
#include <stdexcept>

namespace wp {
namespace {

// A buffer's elements [first, first + count) mapped for the host, unmapped
// (an enqueued command, which later kernels wait for) when it goes.
template <class T>
class Mapped {
 public:
    Mapped(cl::CommandQueue& queue, const cl::Buffer& buffer, cl_map_flags flags, std::size_t first, std::size_t count)
        : queue_(queue), buffer_(buffer) {
        data_ = static_cast<T*>(queue.enqueueMapBuffer(buffer, CL_TRUE, flags, first * sizeof(T), count * sizeof(T)));
    }
    ~Mapped() { queue_.enqueueUnmapMemObject(buffer_, data_); }
    Mapped(const Mapped&) = delete;
    Mapped& operator=(const Mapped&) = delete;
    T* data() const { return data_; }

 private:
    cl::CommandQueue& queue_;
    const cl::Buffer& buffer_;
    T* data_;
};

// A vec3 field's three planes of `capacity` floats, mapped.
struct MappedPlanes {
    Mapped<float> planes;
    std::size_t capacity;
    MappedPlanes(cl::CommandQueue& queue, const cl::Buffer& buffer, cl_map_flags flags, std::size_t n)
        : planes(queue, buffer, flags, 0, 3 * n), capacity(n) {}
    std::array<const float*, 3> components() const {
        return {planes.data(), planes.data() + capacity, planes.data() + 2 * capacity};
    }
};

}  // namespace

HostTraceFields host_trace_fields(StageTrace traces) {
    switch (traces) {
        case StageTrace::CLOSEST_HIT:
            return {{"origin", "direction"}, {"hit_t", "hit_shape"}};
        case StageTrace::ANY_HIT:
            return {{"shadow_origin", "shadow_direction", "shadow_distance"}, {"shadow_occluded"}};
        case StageTrace::NO_RAYS:
            break;
    }
    return {};
}

std::string host_trace_row(const StageDeclaration& stage) { return std::string("embree:") + stage.kernel; }

HostTrace::HostTrace(const Scene& scene, std::vector<SharedMath<float>::MeshTriangle> triangles)
    : embree_(scene, std::move(triangles)) {}

double HostTrace::trace(cl::CommandQueue& queue, const QueueSet& queues, const PathState& state, std::size_t capacity,
                        Stage stage) {
    const StageDeclaration& declared = declaration(stage);
    if (declared.traces == StageTrace::NO_RAYS)
        throw std::logic_error(std::string(declared.kernel) + " traces no rays");
    const HostTraceFields fields = host_trace_fields(declared.traces);
    queue.finish();
    const auto start = std::chrono::steady_clock::now();
    {
        Mapped<std::uint32_t> counts(queue, queues.counts(), CL_MAP_READ, 0, WP_QUEUE_COUNT);
        const std::uint32_t length = counts.data()[declared.consumes];
        if (length > 0) {
            Mapped<std::uint32_t> slots(queue, queues.queues(), CL_MAP_READ, declared.consumes * capacity, length);
            const std::span<const std::uint32_t> queued(slots.data(), length);
            MappedPlanes origin(queue, state.field(fields.reads[0]), CL_MAP_READ, capacity);
            MappedPlanes direction(queue, state.field(fields.reads[1]), CL_MAP_READ, capacity);
            if (declared.traces == StageTrace::CLOSEST_HIT) {
                Mapped<float> t(queue, state.field(fields.writes[0]), CL_MAP_WRITE, 0, capacity);
                Mapped<std::uint32_t> shape(queue, state.field(fields.writes[1]), CL_MAP_WRITE, 0, capacity);
                embree_.closest({origin.components(), direction.components(), nullptr}, queued,
                                {t.data(), shape.data()});
            } else {
                Mapped<float> distance(queue, state.field(fields.reads[2]), CL_MAP_READ, 0, capacity);
                Mapped<std::uint32_t> occluded(queue, state.field(fields.writes[0]), CL_MAP_WRITE, 0, capacity);
                embree_.occluded({origin.components(), direction.components(), distance.data()}, queued,
                                 occluded.data());
            }
        }
    }
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace wp
