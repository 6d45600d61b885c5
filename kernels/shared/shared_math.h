/* All the math shared by the OpenCL kernels and the C++ reference renderer,
 * for C++: src/core/shared_math.h includes it once per precision. Kernels
 * include the headers they use one by one. */
#ifndef WP_SHARED_MATH_H
#define WP_SHARED_MATH_H

#include "shared/bvh.h"
#include "shared/camera.h"
#include "shared/direct_light.h"
#include "shared/environment_map.h"
#include "shared/estimator.h"
#include "shared/fresnel.h"
#include "shared/geometry.h"
#include "shared/hit_point.h"
#include "shared/lights.h"
#include "shared/materials/bsdf.h"
#include "shared/materials/conductor.h"
#include "shared/materials/diffuse.h"
#include "shared/materials/glass.h"
#include "shared/materials/mask.h"
#include "shared/materials/microfacet.h"
#include "shared/materials/mirror.h"
#include "shared/materials/plastic.h"
#include "shared/materials/roughconductor.h"
#include "shared/materials/roughdielectric.h"
#include "shared/materials/roughplastic.h"
#include "shared/materials/thindielectric.h"
#include "shared/normal_map.h"
#include "shared/offset.h"
#include "shared/photon_grid.h"
#include "shared/photons.h"
#include "shared/pixel_filter.h"
#include "shared/prelude.h"
#include "shared/rng.h"
#include "shared/sampler.h"
#include "shared/sampling.h"
#include "shared/special_functions.h"
#include "shared/sppm.h"
#include "shared/surface_tangents.h"
#include "shared/texture.h"
#include "shared/triangle.h"

#endif
