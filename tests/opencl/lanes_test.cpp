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

// The measured defaults (bench/results/defaults.md, lanes_megakernel.md,
// lanes_wavefront.md): without meshes, 16 on CPUs whose preferred float
// vector holds 16 (AVX-512), 8 on other CPUs; one on GPUs.
TEST(ResolveLanes, TheVectorWidthOnCpusWithoutMeshesOneOnGpusByDefault) {
    const DeviceInfo gpu = device_of_type("GPU");
    for (unsigned width : {4u, 8u, 16u}) {
        const DeviceInfo cpu = device_of_type("CPU", width);
        EXPECT_EQ(resolve_lanes(0, LaneProgram::wavefront(true, false), cpu), width == 16u ? 16u : 8u)
            << "vector width " << width;
        EXPECT_EQ(resolve_lanes(0, LaneProgram::megakernel(false), cpu), width == 16u ? 16u : 8u)
            << "vector width " << width;
    }
    EXPECT_EQ(resolve_lanes(0, LaneProgram::wavefront(true, false), gpu), 1u);
    EXPECT_EQ(resolve_lanes(0, LaneProgram::megakernel(false), gpu), 1u);
}

TEST(ResolveLanes, EachBackendsExceptionsToTheVectorWidthOnCpus) {
    for (unsigned width : {8u, 16u}) {
        const DeviceInfo cpu = device_of_type("CPU", width);
        EXPECT_EQ(resolve_lanes(0, LaneProgram::wavefront(false, false), cpu), 1u) << "atomic pushes are per work item";
        EXPECT_EQ(resolve_lanes(0, LaneProgram::wavefront(true, true), cpu), 8u) << "meshes in the wavefront";
        EXPECT_EQ(resolve_lanes(0, LaneProgram::megakernel(true), cpu), 1u) << "meshes in the megakernel";
        EXPECT_EQ(resolve_lanes(1, LaneProgram::wavefront(true, false), cpu), 1u);
    }
}

// Every count the kernels compile, on either kind of device, overrides the default.
TEST(ResolveLanes, RequestsOfEveryCompiledCountOverrideTheDefault) {
    for (const char* type : {"CPU", "GPU"})
        for (unsigned lanes : {1u, 4u, 8u, 16u}) {
            const DeviceInfo device = device_of_type(type);
            EXPECT_EQ(resolve_lanes(lanes, LaneProgram::wavefront(true, false), device), lanes) << type;
            EXPECT_EQ(resolve_lanes(lanes, LaneProgram::megakernel(false), device), lanes) << type;
            EXPECT_EQ(resolve_lanes(lanes, LaneProgram::megakernel(true), device), lanes) << type << ", meshes";
        }
}

TEST(ResolveLanes, RefusesWhatTheProgramCannotRun) {
    EXPECT_EQ(lanes_problem(2, LaneProgram::wavefront(true, false)), "wavefront lanes must be 1, 4, 8 or 16, not 2");
    EXPECT_EQ(lanes_problem(32, LaneProgram::megakernel(false)), "megakernel lanes must be 1, 4, 8 or 16, not 32");
    EXPECT_EQ(lanes_problem(16, LaneProgram::wavefront(false, false)),
              "--lanes 16 needs --compaction scan (atomic pushes are per work item)");
    for (unsigned lanes : {1u, 4u, 8u, 16u}) {
        EXPECT_EQ(lanes_problem(lanes, LaneProgram::megakernel(true)), "");
        EXPECT_EQ(lanes_problem(lanes, LaneProgram::wavefront(true, false)), "");
    }
    EXPECT_EQ(lanes_problem(1, LaneProgram::wavefront(false, false)), "");
    for (unsigned lanes : {4u, 8u})
        EXPECT_THROW(resolve_lanes(lanes, LaneProgram::wavefront(false, false), device_of_type("CPU")),
                     std::invalid_argument);
    EXPECT_THROW(resolve_lanes(12, LaneProgram::megakernel(false), device_of_type("CPU")), std::invalid_argument);
    for (unsigned lanes : {1u, 4u, 8u, 16u}) EXPECT_TRUE(lanes_compiled(lanes)) << lanes;
    for (unsigned lanes : {0u, 2u, 3u, 12u, 32u}) EXPECT_FALSE(lanes_compiled(lanes)) << lanes;
}

}  // namespace
}  // namespace wp
