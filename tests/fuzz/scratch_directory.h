// Where a fuzzer that reads files by path (the mesh import, the glTF reader)
// writes each input, one folder per process, removed at exit.
#pragma once

#include <unistd.h>

#include <filesystem>
#include <string>
#include <system_error>

namespace wp::fuzz {

struct ScratchDirectory {
    explicit ScratchDirectory(const std::string& fuzzer)
        : path(std::filesystem::temp_directory_path() /
               ("wavepath-fuzz-" + fuzzer + "-" + std::to_string(::getpid()))) {
        std::filesystem::create_directories(path);
    }
    ~ScratchDirectory() {
        std::error_code ignored;
        std::filesystem::remove_all(path, ignored);
    }
    ScratchDirectory(const ScratchDirectory&) = delete;
    ScratchDirectory& operator=(const ScratchDirectory&) = delete;

    std::filesystem::path path;
};

}  // namespace wp::fuzz
