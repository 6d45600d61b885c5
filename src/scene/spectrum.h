// Spectra given as wavelength:value lists, as Mitsuba 3's RGB variants read them.
#pragma once

#include <glm/vec3.hpp>
#include <vector>

namespace wp {

// How Mitsuba 3 reads a spectrum of each kind of property in its RGB variants.
enum class SpectrumKind {
    Reflectance,  // weighted by the D65 illuminant (a flat 1 is white), clamped to [0, 1]
    Index,        // a conductor's eta or k: weighted by D65, clamped to >= 0
    Emission,     // a radiance or irradiance: as it is (a flat spectrum is the equal-energy white, not grey), >= 0
};

// The linear sRGB colour of the piecewise-linear spectrum through
// (wavelengths[i], values[i]) (wavelengths increasing, at least two), as
// Mitsuba 3's spectrum_list_to_srgb gives it for a property of that kind.
// The data are Mitsuba's (cie_table.h, scripts/cie_table.py).
glm::dvec3 spectrum_to_srgb(const std::vector<double>& wavelengths, const std::vector<double>& values,
                            SpectrumKind kind);

}  // namespace wp
