#include "wavefront/sppm_state.h"

#include <algorithm>
#include <array>
#include <sstream>
#include <stdexcept>

#include "core/shared_math.h"
#include "interface/sppm_state.h"
#include "shared/film_sum.h"

namespace wp {
namespace sppm_state_types {
using uint = std::uint32_t;
using vec3 = std::array<float, 3>;  // three planes of floats on the device
}  // namespace sppm_state_types

const std::vector<SppmStateField>& sppm_state_fields() {
    using sppm_state_types::uint;
    using sppm_state_types::vec3;
#define WP_SPPM_STATE_ENTRY(type, name, size, feature, writers, readers) \
    {#type, #name, SppmSize::size, SppmFeature::feature, sizeof(type), writers, readers},
    static const std::vector<SppmStateField> fields{WP_SPPM_STATE(WP_SPPM_STATE_ENTRY)};
#undef WP_SPPM_STATE_ENTRY
    return fields;
}

bool sppm_feature_compiled(SppmFeature feature, const FeatureSet& features) {
    switch (feature) {
        case SppmFeature::ALWAYS:
            return true;
        case SppmFeature::GLOSSY:
            return features.glossy();
        case SppmFeature::GLOSSY_TEXTURES:
            return features.glossy() && features.textures;
    }
    return false;
}

std::string sppm_state_table_markdown() {
    static const char* size_names[] = {"1 per pixel",       "3 x 8 words per pixel (exact flux sums)",
                                       "1 per bucket, + 1", "1 per 256 buckets, + 1",
                                       "8 per pixel",       "4"};
    static const char* feature_names[] = {"always", "glossy (a non-specular material other than diffuse)",
                                          "glossy and textures"};
    std::ostringstream table;
    table << "| entry | type | elements | when | written by | read by |\n|---|---|---|---|---|---|\n";
    for (const SppmStateField& f : sppm_state_fields())
        table << "| `" << f.name << "` | " << f.type << " | " << size_names[static_cast<int>(f.size)] << " | "
              << feature_names[static_cast<int>(f.feature)] << " | " << f.writers << " | " << f.readers << " |\n";
    return table.str();
}

SppmState::SppmState(const cl::Context& context, std::uint64_t pixels, const FeatureSet& features)
    : pixels_(pixels), buckets_(SharedMath<float>::photon_grid_buckets(static_cast<std::uint32_t>(pixels))) {
    for (const SppmStateField& f : sppm_state_fields()) {
        if (!sppm_feature_compiled(f.feature, features)) continue;
        compiled_.push_back(&f);
        buffers_.emplace_back(context, CL_MEM_READ_WRITE, f.element_bytes * elements(f.size));
    }
}

std::uint64_t SppmState::elements(SppmSize size) const {
    switch (size) {
        case SppmSize::PIXELS:
            return pixels_;
        case SppmSize::DEPOSITS:
            return pixels_ * 3 * WP_FILM_WORDS;
        case SppmSize::BUCKETS:
            return std::uint64_t(buckets_) + 1;
        case SppmSize::BLOCKS:
            return (std::uint64_t(buckets_) + WP_GRID_SCAN_BLOCK - 1) / WP_GRID_SCAN_BLOCK + 1;
        case SppmSize::ENTRIES:
            return pixels_ * WP_GRID_CELLS_PER_SPHERE;
        case SppmSize::FRAME:
            return 4;
    }
    return 0;
}

void SppmState::bind(cl::Kernel& kernel, cl_uint first) const {
    for (std::size_t i = 0; i < buffers_.size(); ++i) kernel.setArg(first + cl_uint(i), buffers_[i]);
}

const cl::Buffer& SppmState::field(const std::string& name) const {
    auto it =
        std::find_if(compiled_.begin(), compiled_.end(), [&](const SppmStateField* f) { return f->name == name; });
    if (it == compiled_.end()) throw std::out_of_range("no SPPM state entry " + name);
    return buffers_[std::size_t(it - compiled_.begin())];
}

}  // namespace wp
