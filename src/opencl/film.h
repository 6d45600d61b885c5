// The film both OpenCL backends accumulate into: per-pixel RGB sums over the
// passes, in double, or in compensated float where the device has no fp64,
// added by kernels/accumulate.cl from a drained pass's entries in sample order.
#pragma once

#include <CL/opencl.hpp>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/render.h"
#include "opencl/launcher.h"

namespace wp {

class Film {
 public:
    // `program` holds accumulate.cl, built with -DWP_FILM_DOUBLE exactly when
    // `film_double`; each pixel will get `spp` samples.
    Film(const cl::Context& context, cl::CommandQueue& queue, const cl::Program& program, std::size_t pixel_count,
         int spp, bool film_double);

    // Adds the pass [pass_start, pass_start + pass_size) from its entries (3 floats each).
    void accumulate(KernelLauncher& launcher, std::uint64_t pass_start, std::uint32_t pass_size,
                    const cl::Buffer& pass_radiance);
    // Per-pixel RGB sums so far.
    std::vector<double> read_sums(cl::CommandQueue& queue) const;

 private:
    std::size_t pixel_count_;
    bool double_;
    double scale_;     // what the film's sums are multiplied by (compensated float: a power of two <= 1/spp)
    cl::Buffer sums_;  // 3 per pixel, then (compensated float only) 3 compensations per pixel
    cl::Kernel accumulate_;
};

// The image of a film's per-pixel sums over `spp` samples.
Image film_to_image(const std::vector<double>& sums, int width, int height, int spp);

}  // namespace wp
