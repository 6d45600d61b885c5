// The device film (kernels/accumulate.cl) against the host's exact sums
// (kernels/shared/film_sum.h compiled as C++, itself checked in
// tests/core/film_test.cpp): the same bits for any floats in any passes, and
// sums beyond float's range kept exactly.
#include "opencl/film.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>

#include "opencl/device.h"
#include "opencl/program_cache.h"
#include "support/analytic_scenes.h"
#include "support/film_sums.h"
#include "wavefront/wavefront_renderer.h"

namespace wp {
namespace {

// Floats of every magnitude float has (subnormals included) and both signs.
std::vector<float> wide_floats(std::size_t count, std::uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_int_distribution<std::uint32_t> bits;
    std::vector<float> values(count);
    for (float& v : values) {
        do {
            std::uint32_t b = bits(rng);
            std::memcpy(&v, &b, sizeof v);
        } while (!std::isfinite(v));
    }
    return values;
}

// 7 pixels, 3 passes of uneven sizes (a pass starting mid-round of the
// pixels): the device adds each entry to its pixel exactly as the host does.
TEST(DeviceFilm, AddsEveryFloatExactlyAsTheHostDoes) {
    DeviceInfo device = choose_device("");
    cl::Context context(device.device);
    cl::CommandQueue queue(context, device.device);
    KernelLauncher launcher(queue, false);
    const int width = 7, height = 1;
    for (bool squares : {false, true}) {
        SCOPED_TRACE(squares ? "with squares" : "sums only");
        BuiltProgram program = build_program(context, device, {"accumulate.cl"}, film_build_options(squares));
        DeviceFilm film(context, queue, program.program, width, height, squares);
        Film expected = Film::empty(width, height, 0, squares);
        std::uint64_t start = 0;
        for (std::uint32_t size : {10u, 23u, 5u}) {
            std::vector<float> entries = wide_floats(3 * size, std::uint32_t(start + squares));
            cl::Buffer pass(context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, sizeof(float) * entries.size(),
                            entries.data());
            film.accumulate(launcher, start, size, pass);
            for (std::uint32_t i = 0; i < size; ++i)
                for (int c = 0; c < 3; ++c) {
                    std::size_t at = 3 * ((start + i) % (width * height)) + c;
                    expected.sums[at] = film_sum_add(expected.sums[at], film_sum_from_float(entries[3 * i + c]));
                    if (squares)
                        expected.squares[at] =
                            film_sum_add(expected.squares[at], film_sum_from_float_squared(entries[3 * i + c]));
                }
            start += size;
        }
        Film got = film.read(queue, {0, start});
        EXPECT_TRUE(test::same_sums(got.sums, expected.sums));
        EXPECT_TRUE(test::same_sums(got.squares, expected.squares));
    }
}

// Every sample is 2e38, finite: a float sum of two overflows to Inf. The
// exact film holds 4e38 and the image is 2e38.
TEST(DeviceFilm, SumsBeyondFloatRangeStayExact) {
    test::RenderBlock block{.width = 8, .height = 8, .spp = 2, .max_depth = 0};
    Scene scene = test::inside_emissive_sphere(block, {0.5, 0.5, 0.5}, glm::dvec3(2e38));
    RenderResult result = render_wavefront(scene, {}, {});
    EXPECT_EQ(result.stats.nonfinite, 0u);
    for (float value : result.image.rgb) EXPECT_EQ(value, 2e38f);
}

}  // namespace
}  // namespace wp
