#include "opencl/film.h"

#include <cmath>

#include "opencl/kernel_arguments.h"

namespace wp {

namespace {

// The largest power of two at most 1/spp: exact to multiply by, and spp
// floats times it sum to at most FLT_MAX.
double float_film_scale(int spp) {
    int exponent = 0;
    std::frexp(double(spp), &exponent);  // spp = m 2^exponent, m in [0.5, 1)
    return std::ldexp(1.0, -exponent);
}

}  // namespace

Film::Film(const cl::Context& context, cl::CommandQueue& queue, const cl::Program& program, std::size_t pixel_count,
           int spp, bool film_double)
    : pixel_count_(pixel_count),
      double_(film_double),
      scale_(film_double ? 1.0 : float_film_scale(spp)),
      sums_(context, CL_MEM_READ_WRITE,
            film_double ? sizeof(double) * 3 * pixel_count : sizeof(float) * 6 * pixel_count),
      accumulate_(program, "accumulate") {
    queue.enqueueFillBuffer(sums_, std::uint8_t(0), 0, sums_.getInfo<CL_MEM_SIZE>());
    accumulate_.setArg(arg::Accumulate::pixel_count, cl_uint(pixel_count));
    accumulate_.setArg(arg::Accumulate::film_scale, cl_float(scale_));
    accumulate_.setArg(arg::Accumulate::film, sums_);
}

void Film::accumulate(KernelLauncher& launcher, std::uint64_t pass_start, std::uint32_t pass_size,
                      const cl::Buffer& pass_radiance) {
    accumulate_.setArg(arg::Accumulate::pass_start, cl_ulong(pass_start));
    accumulate_.setArg(arg::Accumulate::pass_size, cl_uint(pass_size));
    accumulate_.setArg(arg::Accumulate::pass_radiance, pass_radiance);
    launcher.launch(accumulate_, "accumulate", pixel_count_);
}

std::vector<double> Film::read_sums(cl::CommandQueue& queue) const {
    std::vector<double> sums(3 * pixel_count_);
    if (double_) {
        queue.enqueueReadBuffer(sums_, CL_TRUE, 0, sizeof(double) * sums.size(), sums.data());
    } else {
        std::vector<float> values(6 * pixel_count_);  // sums, then Kahan compensations
        queue.enqueueReadBuffer(sums_, CL_TRUE, 0, sizeof(float) * values.size(), values.data());
        for (std::size_t i = 0; i < sums.size(); ++i)
            sums[i] = (double(values[i]) - double(values[sums.size() + i])) / scale_;
    }
    return sums;
}

Image film_to_image(const std::vector<double>& sums, int width, int height, int spp) {
    Image image;
    image.width = width;
    image.height = height;
    image.rgb.resize(sums.size());
    for (std::size_t i = 0; i < sums.size(); ++i) image.rgb[i] = static_cast<float>(sums[i] / spp);
    return image;
}

}  // namespace wp
