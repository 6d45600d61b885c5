#include "scene/plastic_constants.h"

#include <map>
#include <mutex>
#include <tuple>

#include "core/shared_math.h"
#include "scene/microfacet_code.h"
#include "scene/texture_section.h"

namespace wp {
namespace {
namespace plastic_constants {

using D = SharedMath<double>;

D::vec3 dvec(const glm::dvec3& v) { return D::vec3(v.x, v.y, v.z); }

// A roughplastic's R_int and table of t, which depend on its distribution, alpha and eta alone.
struct RoughCoat {
    double internal_reflectance;
    std::vector<double> transmittance;
};

const RoughCoat& rough_coat(const Material& m) {
    static std::mutex mutex;
    static std::map<std::tuple<Microfacet, double, double>, RoughCoat> computed;
    std::lock_guard<std::mutex> lock(mutex);
    const auto key = std::make_tuple(m.distribution, m.alpha_u, m.ior);
    auto found = computed.find(key);
    if (found != computed.end()) return found->second;
    const D::Microfacet microfacet{microfacet_code(m), m.alpha_u, m.alpha_u};
    RoughCoat coat{D::roughplastic_internal_reflectance(microfacet, m.ior), {}};
    for (int k = 0; k < WP_ROUGHPLASTIC_TABLE_SIZE; ++k) {
        coat.transmittance.push_back(
            D::rough_interface_transmittance(microfacet, m.ior, D::roughplastic_table_cosine(k)));
    }
    return computed.emplace(key, std::move(coat)).first->second;
}

}  // namespace plastic_constants
}  // namespace

PlasticTables plastic_tables(const std::vector<Material>& materials, const std::vector<Texture>& textures) {
    using namespace plastic_constants;
    PlasticTables tables;
    for (const Material& m : materials) {
        PlasticConstants c;
        if (m.type == MaterialType::Plastic || m.type == MaterialType::RoughPlastic) {
            c.inv_eta_2 = 1.0 / (m.ior * m.ior);
            auto mean = [&](TexturedParameter p, const glm::dvec3& constant) {
                return m.texture(p) == kNoTexture ? D::plastic_channel_mean(dvec(constant))
                                                  : texture_mean(textures[std::size_t(m.texture(p))]);
            };
            c.specular_sampling_weight = D::plastic_specular_sampling_weight(
                mean(TexturedParameter::Albedo, m.albedo),
                mean(TexturedParameter::SpecularReflectance, m.specular_reflectance));
        }
        if (m.type == MaterialType::Plastic) c.internal_reflectance = D::fresnel_diffuse_reflectance(1.0 / m.ior);
        if (m.type == MaterialType::RoughPlastic) {
            const RoughCoat& coat = rough_coat(m);
            c.internal_reflectance = coat.internal_reflectance;
            c.transmittance_offset = static_cast<std::uint32_t>(tables.transmittance.size());
            tables.transmittance.insert(tables.transmittance.end(), coat.transmittance.begin(),
                                        coat.transmittance.end());
        }
        tables.materials.push_back(c);
    }
    return tables;
}

}  // namespace wp
