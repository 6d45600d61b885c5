// Runs the real wavepath binary and captures what it says and returns.
#pragma once

#include <sys/types.h>

#include <filesystem>
#include <string>
#include <vector>

#include "support/temp_directory.h"

namespace wp::test {

struct CommandResult {
    int exit_code = -1;
    std::string out, err;
};

// Runs `binary` (WAVEPATH_BINARY: the build's wavepath) with `args`, stdout
// and stderr captured through files in `scratch` (which must exist and is
// left as it was). A `launcher` (a program and its flags, such as mpirun -n
// 2) runs the binary when given.
CommandResult run_wavepath(const std::vector<std::string>& args, const std::filesystem::path& scratch,
                           const std::vector<std::string>& launcher = {},
                           const std::filesystem::path& binary = WAVEPATH_BINARY);

// A wavepath process started with `args` (output captured as run_wavepath
// does) and not yet waited for: for signals.
class RunningWavepath {
 public:
    RunningWavepath(const std::vector<std::string>& args, const std::filesystem::path& scratch,
                    const std::vector<std::string>& launcher = {},
                    const std::filesystem::path& binary = WAVEPATH_BINARY);
    ~RunningWavepath();  // kills and reaps the process if wait() was not called
    RunningWavepath(const RunningWavepath&) = delete;
    RunningWavepath& operator=(const RunningWavepath&) = delete;
    void send(int signal);
    CommandResult wait();

 private:
    std::filesystem::path scratch_;
    pid_t pid_ = -1;
};

}  // namespace wp::test
