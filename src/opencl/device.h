// OpenCL platforms and devices: listing them for `wavepath devices` and
// choosing the one a render runs on.
#pragma once

#include <CL/opencl.hpp>
#include <stdexcept>
#include <string>
#include <vector>

namespace wp {

// One line naming what is wrong with the OpenCL setup or a device choice.
class DeviceError : public std::runtime_error {
 public:
    using std::runtime_error::runtime_error;
};

struct DeviceInfo {
    int index = 0;  // position in the list of all devices of all platforms
    std::string platform;
    std::string platform_version;
    std::string name;
    std::string type;  // GPU, CPU, accelerator, other
    std::string driver_version;
    std::string opencl_c_version;
    unsigned compute_units = 0;
    unsigned long long global_memory_bytes = 0;
    unsigned long long max_allocation_bytes = 0;
    bool fp64 = false;
    // Floats per vector: what the device wants kernels to write out as vectors
    // (preferred: 1 on GPUs and runtimes that vectorise across work items
    // themselves, 16 from PoCL on AVX-512) and its vector registers' (native).
    unsigned preferred_float_vector_width = 1;
    unsigned native_float_vector_width = 1;
    cl::Device device;
};

// Every device of every platform; throws DeviceError when there is none.
std::vector<DeviceInfo> list_devices();

// The device named by `choice`: empty picks the first GPU, else the first
// device; a number is an index into list_devices(); anything else is a
// case-insensitive substring of the device or platform name.
DeviceInfo choose_device(const std::string& choice);

// A table of list_devices() for `wavepath devices`.
std::string describe_devices(const std::vector<DeviceInfo>& devices);

}  // namespace wp
