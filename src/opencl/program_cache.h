// Builds OpenCL programs from kernels/*.cl at run time, with the program
// binaries cached on disk so that scene-specialised builds are paid once.
#pragma once

#include <string>
#include <vector>

#include "core/render.h"
#include "opencl/device.h"

namespace wp {

// A kernel that does not compile: what() is one line naming the file and
// line of the first error; log() is the compiler's full output.
class KernelBuildError : public DeviceError {
 public:
    KernelBuildError(const std::string& first_error, std::string log)
        : DeviceError("kernel build failed: " + first_error), log_(std::move(log)) {}
    const std::string& log() const { return log_; }

 private:
    std::string log_;
};

// A program as a renderer builds it: its kernel files (names in
// kernel_directory()), compiled as one program, with `options` (build_program
// puts its own in front: compiler_options), for `lanes` paths per work item
// (-DWP_LANES, among the options).
struct KernelProgram {
    std::vector<std::string> files;
    std::string options;
    unsigned lanes = 1;
};

struct BuiltProgram {
    cl::Program program;
    std::string options;     // the full build options
    bool cache_hit = false;  // the binary came from the cache
    double build_seconds = 0.0;
    std::string cache_file;  // empty when the cache directory is unusable
};

// --explain's lines for a build: "build options: ...", then "program: cache
// hit in 0.01 s (FILE)" or "program: cache miss, compiled in 41.2 s (FILE)".
std::string explain_build(const std::string& options, bool cache_hit, double build_seconds,
                          const std::string& cache_file);

// $WAVEPATH_KERNEL_DIR, else the kernels/ directory of the source tree.
std::string kernel_directory();

// $WAVEPATH_CACHE_DIR, else $XDG_CACHE_HOME/wavepath, else ~/.cache/wavepath.
std::string program_cache_directory();

// What build_program gives the OpenCL compiler for a program built with
// `options`: -cl-std=CL1.2, correctly rounded divide and sqrt, -I for the
// kernel directory, then `options`.
std::string compiler_options(const std::string& options);

// Builds the concatenation of `files` (names in kernel_directory()) as one
// program for `device`, with compiler_options(options). The cache key hashes the platform, device, driver, options, the
// names in `files` and every file under the kernel directory (the headers included).
// On a cache miss, announces the compilation on `progress` before it starts.
BuiltProgram build_program(const cl::Context& context, const DeviceInfo& device, const std::vector<std::string>& files,
                           const std::string& options, const Progress& progress = {});

}  // namespace wp
