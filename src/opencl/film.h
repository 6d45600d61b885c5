// The film both OpenCL backends accumulate into: per-pixel exact sums
// (kernels/shared/film_sum.h) on the device, added by kernels/accumulate.cl
// from a drained pass's entries, read back into and loaded from a host Film.
#pragma once

#include <CL/opencl.hpp>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/film.h"
#include "opencl/launcher.h"

namespace wp {

class DeviceFilm {
 public:
    // `program` holds accumulate.cl, built with -DWP_FILM_SQUARES exactly
    // when `squares` (film_build_options). The sums start at zero.
    DeviceFilm(const cl::Context& context, cl::CommandQueue& queue, const cl::Program& program, int width, int height,
               bool squares);

    // The pixels the work items sample from now on (Film::round_pixels; empty:
    // every pixel), for accumulate and for the kernels that map work items to
    // pixels (bind_round).
    void set_round_pixels(cl::CommandQueue& queue, const std::vector<std::uint32_t>& pixels);
    // Sets `kernel`'s round_pixels and round_pixel_count arguments.
    void bind_round(cl::Kernel& kernel, cl_uint pixels_index, cl_uint count_index) const;

    // Adds the pass [pass_start, pass_start + pass_size) from its entries (3 floats each).
    void accumulate(KernelLauncher& launcher, std::uint64_t pass_start, std::uint32_t pass_size,
                    const cl::Buffer& pass_radiance);
    // The sums so far, as the film of `items`.
    Film read(cl::CommandQueue& queue, const ItemRange& items) const;
    // Replaces the sums with `film`'s (same size and squares, else std::invalid_argument).
    void load(cl::CommandQueue& queue, const Film& film);

 private:
    int width_, height_;
    bool squares_;
    cl::Buffer sums_;  // WP_FILM_LIMBS limbs per channel and pixel: the sums, then (squares_) the squares
    cl::Buffer round_pixels_;
    std::uint32_t round_pixel_count_;
    cl::Kernel accumulate_;
};

// " -DWP_FILM_SQUARES" when the film keeps squares, else "".
const char* film_build_options(bool squares);

}  // namespace wp
