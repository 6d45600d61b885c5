#include "scene/spectrum.h"

#include <algorithm>
#include <cstddef>
#include <glm/common.hpp>
#include <iterator>

#include "scene/cie_table.h"

namespace wp {

glm::dvec3 spectrum_to_srgb(const std::vector<double>& wavelengths, const std::vector<double>& values,
                            SpectrumKind kind) {
    const bool d65 = kind != SpectrumKind::Emission;
    using namespace cie_detail;
    glm::dvec3 xyz(0.0);
    for (const CieSample& s : kCieSamples) {
        if (s.wavelength < wavelengths.front() || s.wavelength > wavelengths.back()) continue;
        // the segment [w0, w1] around the sample (the last one at the last wavelength itself)
        const auto above = std::upper_bound(wavelengths.begin(), wavelengths.end(), s.wavelength);
        const std::size_t i =
            std::min<std::size_t>(std::size_t(std::distance(wavelengths.begin(), above)), wavelengths.size() - 1) - 1;
        const double w0 = wavelengths[i], w1 = wavelengths[i + 1];
        const double value = ((s.wavelength - w1) * values[i] + (w0 - s.wavelength) * values[i + 1]) / (w0 - w1);
        const double weight = value * (d65 ? s.d65 : 1.0);
        xyz += glm::dvec3(s.x, s.y, s.z) * weight;
    }
    xyz *= (kCieMax - kCieMin) / double(std::size(kCieSamples)) * kCieYNormalization;
    glm::dvec3 rgb;
    for (int r = 0; r < 3; ++r) rgb[r] = kXyzToSrgb[r][0] * xyz.x + kXyzToSrgb[r][1] * xyz.y + kXyzToSrgb[r][2] * xyz.z;
    rgb = glm::max(rgb, glm::dvec3(0.0));
    return kind == SpectrumKind::Reflectance ? glm::min(rgb, glm::dvec3(1.0)) : rgb;
}

}  // namespace wp
