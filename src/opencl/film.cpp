#include "opencl/film.h"

#include <numeric>
#include <stdexcept>

#include "opencl/kernel_arguments.h"

namespace wp {

namespace {

std::size_t sums_per_film(int width, int height) { return std::size_t(kFilmChannels) * width * height; }

}  // namespace

const char* film_build_options(bool squares) { return squares ? " -DWP_FILM_SQUARES" : ""; }

DeviceFilm::DeviceFilm(const cl::Context& context, cl::CommandQueue& queue, const cl::Program& program, int width,
                       int height, bool squares)
    : width_(width),
      height_(height),
      squares_(squares),
      sums_(context, CL_MEM_READ_WRITE, sizeof(film_sum) * sums_per_film(width, height) * (squares ? 2 : 1)),
      round_pixels_(context, CL_MEM_READ_ONLY, sizeof(std::uint32_t) * std::size_t(width) * height),
      round_pixel_count_(std::uint32_t(std::size_t(width) * height)),
      accumulate_(program, "accumulate") {
    queue.enqueueFillBuffer(sums_, std::uint8_t(0), 0, sums_.getInfo<CL_MEM_SIZE>());
    accumulate_.setArg(arg::Accumulate::pixel_count, cl_uint(std::size_t(width) * height));
    accumulate_.setArg(arg::Accumulate::film, sums_);
    set_round_pixels(queue, {});
}

void DeviceFilm::set_round_pixels(cl::CommandQueue& queue, const std::vector<std::uint32_t>& pixels) {
    std::vector<std::uint32_t> every;
    if (pixels.empty()) {
        every.resize(std::size_t(width_) * height_);
        std::iota(every.begin(), every.end(), 0u);
    }
    const std::vector<std::uint32_t>& list = pixels.empty() ? every : pixels;
    round_pixel_count_ = std::uint32_t(list.size());
    queue.enqueueWriteBuffer(round_pixels_, CL_TRUE, 0, sizeof(std::uint32_t) * list.size(), list.data());
    bind_round(accumulate_, arg::Accumulate::round_pixels, arg::Accumulate::round_pixel_count);
}

void DeviceFilm::bind_round(cl::Kernel& kernel, cl_uint pixels_index, cl_uint count_index) const {
    kernel.setArg(pixels_index, round_pixels_);
    kernel.setArg(count_index, cl_uint(round_pixel_count_));
}

void DeviceFilm::accumulate(KernelLauncher& launcher, std::uint64_t pass_start, std::uint32_t pass_size,
                            const cl::Buffer& pass_radiance) {
    accumulate_.setArg(arg::Accumulate::pass_start, cl_ulong(pass_start));
    accumulate_.setArg(arg::Accumulate::pass_size, cl_uint(pass_size));
    accumulate_.setArg(arg::Accumulate::pass_radiance, pass_radiance);
    // Over every pixel whatever the round (work items past it return): PoCL
    // compiles a kernel for each new launch size, which rounds would otherwise pay.
    launcher.launch(accumulate_, "accumulate", std::size_t(width_) * height_);
}

Film DeviceFilm::read(cl::CommandQueue& queue, const ItemRange& items) const {
    Film film = Film::empty(width_, height_, items.begin, squares_);
    film.items = items;
    const std::size_t bytes = sizeof(film_sum) * film.sums.size();
    queue.enqueueReadBuffer(sums_, CL_TRUE, 0, bytes, film.sums.data());
    if (squares_) queue.enqueueReadBuffer(sums_, CL_TRUE, bytes, bytes, film.squares.data());
    return film;
}

void DeviceFilm::load(cl::CommandQueue& queue, const Film& film) {
    if (film.width != width_ || film.height != height_ || film.squares.empty() == squares_)
        throw std::invalid_argument("DeviceFilm::load: a film of another size or without the squares this one keeps");
    const std::size_t bytes = sizeof(film_sum) * film.sums.size();
    queue.enqueueWriteBuffer(sums_, CL_TRUE, 0, bytes, film.sums.data());
    if (squares_) queue.enqueueWriteBuffer(sums_, CL_TRUE, bytes, bytes, film.squares.data());
}

}  // namespace wp
