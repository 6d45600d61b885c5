#include "wavefront/path_state.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <sstream>
#include <stdexcept>

#include "opencl/kernel_arguments.h"

namespace wp {
namespace path_state_types {
using uint = std::uint32_t;
using vec3 = std::array<float, 3>;  // three planes of floats on the device
}  // namespace path_state_types

#include "interface/path_state.h"

const std::vector<PathStateField>& path_state_fields() {
    using path_state_types::uint;
    using path_state_types::vec3;
#define WP_PATH_STATE_ENTRY(type, name, feature, writers, readers) \
    {#type, #name, PathFeature::feature, sizeof(type), writers, readers},
    static const std::vector<PathStateField> fields{WP_PATH_STATE(WP_PATH_STATE_ENTRY)};
#undef WP_PATH_STATE_ENTRY
    return fields;
}

bool path_feature_compiled(PathFeature feature, const FeatureSet& features) {
    switch (feature) {
        case PathFeature::ALWAYS:
            return true;
        case PathFeature::SPECULAR:
            return features.specular();
        case PathFeature::REFRACTION:
            return features.refraction();
        case PathFeature::NEE:
            return features.nee;
        case PathFeature::MIS:
            return features.mis;
        case PathFeature::SHADOW_STAGE:
            return features.nee && features.shadow_stage;
        case PathFeature::HOST_SHADOWS:
            return features.nee && features.host_traced;
        case PathFeature::HIT_STAGE:
            return !features.intersect_and_shade;
        case PathFeature::INTERSECT_AND_SHADE:
            return features.intersect_and_shade;
        case PathFeature::SPPM:
            return features.sppm;
    }
    return false;
}

std::string path_state_table_markdown() {
    static const char* feature_names[] = {"always",
                                          "specular (a material with a delta lobe)",
                                          "refraction (glass or roughdielectric)",
                                          "nee (next-event estimation runs)",
                                          "mis (next-event estimation with multiple importance sampling)",
                                          "nee with the shadow rays traced in their own stage (intersect_shadow)",
                                          "nee with the shadow rays traced on the host (--intersector embree)",
                                          "intersect and shade apart",
                                          "intersect and shade as one kernel",
                                          "sppm (the sppm integrator)"};
    std::ostringstream table;
    table << "| field | type | bytes/path | exists when | written by | read by |\n"
          << "|---|---|---|---|---|---|\n";
    for (const PathStateField& f : path_state_fields()) {
        table << "| `" << f.name << "` | " << f.type << " | " << f.bytes << " | "
              << feature_names[static_cast<int>(f.feature)] << " | " << f.writers << " | " << f.readers << " |\n";
    }
    return table.str();
}

std::size_t PathState::bytes_per_path(const FeatureSet& features) {
    std::size_t bytes = 0;
    for (const PathStateField& f : path_state_fields())
        if (path_feature_compiled(f.feature, features)) bytes += f.bytes;
    return bytes;
}

PathState::PathState(const cl::Context& context, std::size_t capacity, const FeatureSet& features) {
    // Where the host traces, it maps the rays and hits: memory the runtime
    // allocates for the host to reach without a copy (on PoCL's CPU device
    // a map is then the buffer's own address).
    const cl_mem_flags flags = CL_MEM_READ_WRITE | (features.host_traced ? CL_MEM_ALLOC_HOST_PTR : 0);
    for (const PathStateField& f : path_state_fields()) {
        if (!path_feature_compiled(f.feature, features)) continue;
        buffers_.emplace_back(context, flags, f.bytes * capacity);
        names_.emplace_back(f.name);
        bytes_per_path_ += f.bytes;
    }
}

void PathState::bind(cl::Kernel& stage) const {
    for (std::size_t i = 0; i < buffers_.size(); ++i) stage.setArg(arg::Stage::count + cl_uint(i), buffers_[i]);
}

bool PathState::has_field(const std::string& name) const {
    return std::find(names_.begin(), names_.end(), name) != names_.end();
}

const cl::Buffer& PathState::field(const std::string& name) const {
    auto it = std::find(names_.begin(), names_.end(), name);
    if (it == names_.end()) throw std::out_of_range("path state field not compiled in: " + name);
    return buffers_[it - names_.begin()];
}

}  // namespace wp
