// The lanes each OpenCL backend takes (opencl/lanes.h): by default, and the
// requests it refuses, with the words the command line prints.
#include "opencl/lanes.h"

#include <gtest/gtest.h>

#include <stdexcept>

namespace wp {
namespace {

// A device of `type` whose preferred float vectors hold `width` floats
// (PoCL on an AVX-512 CPU: 16).
DeviceInfo device_of_type(const char* type, unsigned width = 16) {
    DeviceInfo device;
    device.type = type;
    device.preferred_float_vector_width = width;
    return device;
}

TEST(ResolveLanes, TheCpusVectorWidthOnCpusOneOnGpusByDefault) {
    const DeviceInfo avx512 = device_of_type("CPU"), avx2 = device_of_type("CPU", 8), gpu = device_of_type("GPU");
    EXPECT_EQ(resolve_lanes(0, LaneProgram::wavefront(true), avx512), 16u);
    EXPECT_EQ(resolve_lanes(0, LaneProgram::wavefront(true), avx2), 8u);
    EXPECT_EQ(resolve_lanes(0, LaneProgram::wavefront(true), gpu), 1u);
    EXPECT_EQ(resolve_lanes(0, LaneProgram::megakernel(false), avx512), 16u);
    EXPECT_EQ(resolve_lanes(0, LaneProgram::megakernel(false), avx2), 8u);
    EXPECT_EQ(resolve_lanes(0, LaneProgram::megakernel(false), gpu), 1u);
}

TEST(ResolveLanes, EachBackendsExceptionsToTheVectorWidthOnCpus) {
    const DeviceInfo cpu = device_of_type("CPU");
    EXPECT_EQ(resolve_lanes(0, LaneProgram::wavefront(false), cpu), 1u) << "atomic pushes are per work item";
    EXPECT_EQ(resolve_lanes(0, LaneProgram::megakernel(true), cpu), 1u) << "meshes in the megakernel";
    EXPECT_EQ(resolve_lanes(8, LaneProgram::megakernel(true), cpu), 8u) << "a request overrides the default";
    EXPECT_EQ(resolve_lanes(1, LaneProgram::wavefront(true), cpu), 1u);
}

TEST(ResolveLanes, RefusesWhatTheProgramCannotRun) {
    EXPECT_EQ(lanes_problem(2, LaneProgram::wavefront(true)), "wavefront lanes must be 1, 4, 8 or 16, not 2");
    EXPECT_EQ(lanes_problem(32, LaneProgram::megakernel(false)), "megakernel lanes must be 1, 4, 8 or 16, not 32");
    EXPECT_EQ(lanes_problem(8, LaneProgram::wavefront(false)),
              "--lanes 8 needs --compaction scan (atomic pushes are per work item)");
    for (unsigned lanes : {1u, 4u, 8u, 16u}) {
        EXPECT_EQ(lanes_problem(lanes, LaneProgram::megakernel(true)), "");
        EXPECT_EQ(lanes_problem(lanes, LaneProgram::wavefront(true)), "");
    }
    EXPECT_EQ(lanes_problem(1, LaneProgram::wavefront(false)), "");
    EXPECT_THROW(resolve_lanes(8, LaneProgram::wavefront(false), device_of_type("CPU")), std::invalid_argument);
}

// The lanes a device's vectors hold: a CPU's preferred float vector width
// (rounded down to a count the kernels compile), at most the backend's widest;
// one lane on GPUs, which run work items in SIMD themselves.
TEST(ResolveLanes, VectorLanesFollowTheDevicesPreferredFloatWidth) {
    EXPECT_EQ(vector_lanes(device_of_type("CPU", 16), 16), 16u) << "AVX-512";
    EXPECT_EQ(vector_lanes(device_of_type("CPU", 8), 16), 8u) << "AVX2";
    EXPECT_EQ(vector_lanes(device_of_type("CPU", 4), 16), 4u) << "SSE, NEON";
    EXPECT_EQ(vector_lanes(device_of_type("CPU", 1), 16), 1u) << "a runtime that vectorises across work items";
    EXPECT_EQ(vector_lanes(device_of_type("CPU", 2), 16), 1u) << "2 lanes are not compiled";
    EXPECT_EQ(vector_lanes(device_of_type("CPU", 32), 16), 16u);
    EXPECT_EQ(vector_lanes(device_of_type("CPU", 16), 8), 8u) << "the backend's widest";
    EXPECT_EQ(vector_lanes(device_of_type("CPU", 16), 1), 1u);
    EXPECT_EQ(vector_lanes(device_of_type("GPU", 4), 16), 1u);
    for (unsigned lanes : {1u, 4u, 8u, 16u}) EXPECT_TRUE(lanes_compiled(lanes)) << lanes;
    for (unsigned lanes : {0u, 2u, 3u, 12u, 32u}) EXPECT_FALSE(lanes_compiled(lanes)) << lanes;
}

}  // namespace
}  // namespace wp
