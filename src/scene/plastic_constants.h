// The constants that Mitsuba's plastic and roughplastic precompute per
// material (kernels/shared/materials/plastic.h and roughplastic.h),
// computed once on the host in double; the device and the reference read
// them rounded to their precision, so that both compute with the same values.
#pragma once

#include <cstdint>
#include <vector>

#include "scene/scene.h"

namespace wp {

struct PlasticConstants {
    double inv_eta_2 = 0.0;                  // 1 / eta^2
    double internal_reflectance = 0.0;       // plastic: fdr_int; roughplastic: R_int
    double specular_sampling_weight = 0.0;   // plastic_specular_sampling_weight
    std::uint32_t transmittance_offset = 0;  // roughplastic: where its table starts in PlasticTables::transmittance
};

struct PlasticTables {
    std::vector<PlasticConstants> materials;  // one per material of the scene (zeros where not a plastic)
    // WP_ROUGHPLASTIC_TABLE_SIZE entries of t (rough_interface_transmittance) per roughplastic
    std::vector<double> transmittance;
};

// The constants of every plastic and roughplastic among `materials`, whose
// textured parameters are `textures`' (a textured reflectance's sampling
// weight takes the texture's mean, as Mitsuba's: texture_mean). A
// roughplastic's R_int and table take about 64 x 64^2 + 64 x 32^2 visible
// normals; they are computed once per distribution, alpha and eta in a
// process and kept for the next call (the backends of one run each flatten
// the scene).
PlasticTables plastic_tables(const std::vector<Material>& materials, const std::vector<Texture>& textures);

}  // namespace wp
