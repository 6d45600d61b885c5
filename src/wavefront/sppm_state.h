// The host side of kernels/interface/sppm_state.h: one device buffer per
// entry of SPPM's state that the scene's features compile in, sized for the
// image, in the order the kernels take them (after the path state in the
// stage kernels, after their own parameters in the grid and update kernels).
#pragma once

#include <CL/opencl.hpp>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "scene/scene.h"

namespace wp {

enum class SppmSize { PIXELS, DEPOSITS, BUCKETS, BLOCKS, ENTRIES, FRAME };
enum class SppmFeature { ALWAYS, GLOSSY, GLOSSY_TEXTURES };

struct SppmStateField {
    const char* type;
    const char* name;
    SppmSize size;
    SppmFeature feature;
    std::size_t element_bytes;  // a vec3 entry's element: 3 floats, as three planes
    const char* writers;        // kernel files, space-separated
    const char* readers;
};

// Every entry of the X-macro list, in order.
const std::vector<SppmStateField>& sppm_state_fields();

// Whether the kernels built for `features` take an entry of `feature`.
bool sppm_feature_compiled(SppmFeature feature, const FeatureSet& features);

// The markdown table of docs/architecture.md: entry, type, size, when, written by, read by.
std::string sppm_state_table_markdown();

class SppmState {
 public:
    SppmState(const cl::Context& context, std::uint64_t pixels, const FeatureSet& features);

    // Sets a kernel's SPPM state arguments from index `first` on, in X-macro order (the compiled entries).
    void bind(cl::Kernel& kernel, cl_uint first) const;
    // An entry's buffer (std::out_of_range for a name the list or the build lacks).
    const cl::Buffer& field(const std::string& name) const;
    // Elements of an entry of `size` (a vec3 entry holds three times as many floats).
    std::uint64_t elements(SppmSize size) const;
    std::uint32_t buckets() const { return buckets_; }
    std::uint64_t pixels() const { return pixels_; }

 private:
    std::uint64_t pixels_;
    std::uint32_t buckets_;
    std::vector<const SppmStateField*> compiled_;  // the entries the kernels take, in order
    std::vector<cl::Buffer> buffers_;              // theirs
};

}  // namespace wp
