// The host side of kernels/interface/sppm_state.h: one device buffer per
// entry of SPPM's state, sized for the image, in the order the kernels take
// them (after the path state in the stage kernels, after their own
// parameters in the grid and update kernels).
#pragma once

#include <CL/opencl.hpp>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace wp {

enum class SppmSize { PIXELS, DEPOSITS, BUCKETS, BLOCKS, ENTRIES, FRAME };

struct SppmStateField {
    const char* type;
    const char* name;
    SppmSize size;
    std::size_t element_bytes;  // a vec3 entry's element: 3 floats, as three planes
    const char* writers;        // kernel files, space-separated
    const char* readers;
};

// Every entry of the X-macro list, in order.
const std::vector<SppmStateField>& sppm_state_fields();

// The markdown table of docs/architecture.md: entry, type, size, written by, read by.
std::string sppm_state_table_markdown();

class SppmState {
 public:
    SppmState(const cl::Context& context, std::uint64_t pixels);

    // Sets a kernel's SPPM state arguments from index `first` on, in X-macro order.
    void bind(cl::Kernel& kernel, cl_uint first) const;
    // An entry's buffer (std::out_of_range for a name the list lacks).
    const cl::Buffer& field(const std::string& name) const;
    // Elements of an entry of `size` (a vec3 entry holds three times as many floats).
    std::uint64_t elements(SppmSize size) const;
    std::uint32_t buckets() const { return buckets_; }
    std::uint64_t pixels() const { return pixels_; }

 private:
    std::uint64_t pixels_;
    std::uint32_t buckets_;
    std::vector<cl::Buffer> buffers_;
};

}  // namespace wp
