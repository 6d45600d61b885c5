/* The math shared by the OpenCL kernels and the C++ reference renderer.
 * Kernels include this file once; C++ includes it through
 * src/core/shared_math.h, once per precision. */
#ifndef WP_SHARED_MATH_H
#define WP_SHARED_MATH_H
#include "prelude.h"
#include "rng.h"
#include "geometry.h"
#include "offset.h"
#include "sampling.h"
#include "fresnel.h"
#endif
