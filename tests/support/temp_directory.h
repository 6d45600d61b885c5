// A fresh, empty directory for the running test, and small file helpers.
#pragma once

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace wp::test {

// Named after the running test and `label`, removed by the destructor.
class TempDirectory {
 public:
    explicit TempDirectory(const std::string& label) {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        std::string test_name = info ? std::string(info->test_suite_name()) + "-" + info->name() : "none";
        std::replace(test_name.begin(), test_name.end(), '/', '_');  // parameterised names contain '/'
        path_ = std::filesystem::temp_directory_path() /
                ("wavepath-cli-" + std::to_string(::getpid()) + "-" + test_name + "-" + label);
        std::filesystem::remove_all(path_);
        std::filesystem::create_directories(path_);
    }
    ~TempDirectory() {
        std::error_code ignored;
        std::filesystem::remove_all(path_, ignored);
    }
    TempDirectory(const TempDirectory&) = delete;
    TempDirectory& operator=(const TempDirectory&) = delete;
    const std::filesystem::path& path() const { return path_; }
    std::string operator/(const std::string& name) const { return (path_ / name).string(); }
    // File names in the directory, sorted (hidden temporaries included).
    std::vector<std::string> entries() const {
        std::vector<std::string> names;
        for (const auto& entry : std::filesystem::directory_iterator(path_)) names.push_back(entry.path().filename());
        std::sort(names.begin(), names.end());
        return names;
    }

 private:
    std::filesystem::path path_;
};

inline std::string read_text(const std::filesystem::path& file) {
    std::ifstream in(file);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
}

inline void write_text(const std::filesystem::path& file, const std::string& text) { std::ofstream(file) << text; }

}  // namespace wp::test
