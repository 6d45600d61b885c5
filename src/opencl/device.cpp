#include "opencl/device.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <sstream>

namespace wp {
namespace {

std::string type_name(cl_device_type type) {
    if (type & CL_DEVICE_TYPE_GPU) return "GPU";
    if (type & CL_DEVICE_TYPE_CPU) return "CPU";
    if (type & CL_DEVICE_TYPE_ACCELERATOR) return "accelerator";
    return "other";
}

std::string lowercase(std::string s) {
    std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
    return s;
}

DeviceInfo describe(const cl::Platform& platform, const cl::Device& device, int index) {
    DeviceInfo info;
    info.index = index;
    info.platform = platform.getInfo<CL_PLATFORM_NAME>();
    info.platform_version = platform.getInfo<CL_PLATFORM_VERSION>();
    info.name = device.getInfo<CL_DEVICE_NAME>();
    info.type = type_name(device.getInfo<CL_DEVICE_TYPE>());
    info.driver_version = device.getInfo<CL_DRIVER_VERSION>();
    info.opencl_c_version = device.getInfo<CL_DEVICE_OPENCL_C_VERSION>();
    info.compute_units = device.getInfo<CL_DEVICE_MAX_COMPUTE_UNITS>();
    info.global_memory_bytes = device.getInfo<CL_DEVICE_GLOBAL_MEM_SIZE>();
    info.max_allocation_bytes = device.getInfo<CL_DEVICE_MAX_MEM_ALLOC_SIZE>();
    info.fp64 = device.getInfo<CL_DEVICE_EXTENSIONS>().find("cl_khr_fp64") != std::string::npos;
    info.preferred_float_vector_width = device.getInfo<CL_DEVICE_PREFERRED_VECTOR_WIDTH_FLOAT>();
    info.native_float_vector_width = device.getInfo<CL_DEVICE_NATIVE_VECTOR_WIDTH_FLOAT>();
    info.device = device;
    return info;
}

}  // namespace

std::vector<DeviceInfo> list_devices() {
    std::vector<cl::Platform> platforms;
    // Without any installed ICD, the loader reports CL_PLATFORM_NOT_FOUND_KHR as an error.
    try {
        cl::Platform::get(&platforms);
    } catch (const cl::Error&) {
        platforms.clear();
    }
    std::vector<DeviceInfo> devices;
    for (const cl::Platform& platform : platforms) {
        std::vector<cl::Device> platform_devices;
        try {
            platform.getDevices(CL_DEVICE_TYPE_ALL, &platform_devices);
        } catch (const cl::Error&) {
            continue;  // a platform without devices
        }
        for (const cl::Device& device : platform_devices)
            devices.push_back(describe(platform, device, static_cast<int>(devices.size())));
    }
    if (devices.empty())
        throw DeviceError("no OpenCL device found (no platform installed, or none with a device; try `clinfo -l`)");
    return devices;
}

DeviceInfo choose_device(const std::string& choice) {
    std::vector<DeviceInfo> devices = list_devices();
    if (choice.empty()) {
        auto gpu = std::find_if(devices.begin(), devices.end(), [](const DeviceInfo& d) { return d.type == "GPU"; });
        return gpu != devices.end() ? *gpu : devices.front();
    }
    int index = -1;
    auto [end, error] = std::from_chars(choice.data(), choice.data() + choice.size(), index);
    if (error == std::errc() && end == choice.data() + choice.size()) {
        if (index < 0 || index >= static_cast<int>(devices.size()))
            throw DeviceError("--device " + choice + ": no such device (there are " + std::to_string(devices.size()) +
                              "; see `wavepath devices`)");
        return devices[index];
    }
    for (const DeviceInfo& d : devices) {
        if (lowercase(d.name + " " + d.platform).find(lowercase(choice)) != std::string::npos) return d;
    }
    throw DeviceError("--device " + choice + ": no device name or platform contains it (see `wavepath devices`)");
}

std::string describe_devices(const std::vector<DeviceInfo>& devices) {
    std::ostringstream out;
    for (const DeviceInfo& d : devices) {
        out << "[" << d.index << "] " << d.name << "\n"
            << "    platform: " << d.platform << " (" << d.platform_version << ")\n"
            << "    type: " << d.type << ", compute units: " << d.compute_units
            << ", memory: " << d.global_memory_bytes / (1024 * 1024) << " MiB"
            << ", " << d.opencl_c_version << (d.fp64 ? ", fp64" : "") << "\n"
            << "    float vector width: preferred " << d.preferred_float_vector_width << ", native "
            << d.native_float_vector_width << "\n"
            << "    driver: " << d.driver_version << "\n";
    }
    return out.str();
}

}  // namespace wp
