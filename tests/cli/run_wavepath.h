// Runs the real wavepath binary and captures what it says and returns.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace wp::test {

struct CommandResult {
    int exit_code = -1;
    std::string out, err;
};

// Runs WAVEPATH_BINARY with `args`, stdout and stderr captured through files
// in `scratch` (which must exist and is left as it was).
CommandResult run_wavepath(const std::vector<std::string>& args, const std::filesystem::path& scratch);

// A fresh, empty directory for the running test, named after it and
// `label`, removed by the destructor.
class TempDirectory {
 public:
    explicit TempDirectory(const std::string& label);
    ~TempDirectory();
    TempDirectory(const TempDirectory&) = delete;
    TempDirectory& operator=(const TempDirectory&) = delete;
    const std::filesystem::path& path() const { return path_; }
    std::string operator/(const std::string& name) const { return (path_ / name).string(); }
    // File names in the directory, sorted (hidden temporaries included).
    std::vector<std::string> entries() const;

 private:
    std::filesystem::path path_;
};

std::string read_text(const std::filesystem::path& file);
void write_text(const std::filesystem::path& file, const std::string& text);

}  // namespace wp::test
