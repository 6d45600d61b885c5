// The host side of kernels/interface/path_state.h: one device buffer per path
// state field whose feature the scene uses, in the order the kernels take them.
#pragma once

#include <CL/opencl.hpp>
#include <cstddef>
#include <string>
#include <vector>

#include "scene/scene.h"

namespace wp {

// A field's or a stage's condition (kernels/interface/path_state.h); HIT_STAGE
// and INTERSECT_AND_SHADE are stages' only (kernels/interface/stages.h).
enum class PathFeature {
    ALWAYS,
    SPECULAR,
    REFRACTION,
    NEE,
    MIS,
    SHADOW_STAGE,
    HOST_SHADOWS,
    HIT_STAGE,
    INTERSECT_AND_SHADE,
    SPPM
};

struct PathStateField {
    const char* type;
    const char* name;
    PathFeature feature;
    std::size_t bytes;    // per path (a vec3 field: 3 floats, as three planes of `capacity` floats)
    const char* writers;  // stages, space-separated
    const char* readers;
};

// Every field of the X-macro list, in order.
const std::vector<PathStateField>& path_state_fields();

// Whether the kernels compiled for `features` have the feature's fields.
bool path_feature_compiled(PathFeature feature, const FeatureSet& features);

// The markdown table of docs/architecture.md: field, type, bytes per path,
// feature, written by, read by.
std::string path_state_table_markdown();

class PathState {
 public:
    // With features.host_traced, buffers the host maps without a copy (CL_MEM_ALLOC_HOST_PTR).
    PathState(const cl::Context& context, std::size_t capacity, const FeatureSet& features);

    // Sets a stage kernel's path state arguments (after WP_STAGE_PARAMETERS, in X-macro order).
    void bind(cl::Kernel& stage) const;
    // The buffer of a compiled field; throws std::out_of_range otherwise.
    const cl::Buffer& field(const std::string& name) const;
    bool has_field(const std::string& name) const;
    // The compiled fields: the stage kernels' arguments after them start at
    // arg::Stage::count plus this.
    cl_uint field_count() const { return cl_uint(buffers_.size()); }
    std::size_t bytes_per_path() const { return bytes_per_path_; }

    // The bytes per path the kernels for this scene need, without allocating.
    static std::size_t bytes_per_path(const FeatureSet& features);

 private:
    std::vector<cl::Buffer> buffers_;
    std::vector<std::string> names_;
    std::size_t bytes_per_path_ = 0;
};

}  // namespace wp
