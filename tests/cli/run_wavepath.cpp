#include "cli/run_wavepath.h"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <fstream>
#include <sstream>
#include <stdexcept>

extern char** environ;

namespace wp::test {

namespace fs = std::filesystem;

CommandResult run_wavepath(const std::vector<std::string>& args, const fs::path& scratch) {
    const fs::path out_file = scratch / "stdout.txt", err_file = scratch / "stderr.txt";
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, out_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, err_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);

    std::vector<std::string> argv_strings{WAVEPATH_BINARY};
    argv_strings.insert(argv_strings.end(), args.begin(), args.end());
    std::vector<char*> argv;
    for (std::string& arg : argv_strings) argv.push_back(arg.data());
    argv.push_back(nullptr);

    pid_t pid = 0;
    const int spawn_error = posix_spawn(&pid, WAVEPATH_BINARY, &actions, nullptr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    if (spawn_error != 0) throw std::runtime_error("cannot start " WAVEPATH_BINARY);
    int status = 0;
    waitpid(pid, &status, 0);

    CommandResult result;
    result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    result.out = read_text(out_file);
    result.err = read_text(err_file);
    fs::remove(out_file);
    fs::remove(err_file);
    return result;
}

TempDirectory::TempDirectory(const std::string& label) {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    std::string test_name = info ? std::string(info->test_suite_name()) + "-" + info->name() : "none";
    std::replace(test_name.begin(), test_name.end(), '/', '_');  // parameterised names contain '/'
    path_ = fs::temp_directory_path() / ("wavepath-cli-" + std::to_string(::getpid()) + "-" + test_name + "-" + label);
    fs::remove_all(path_);
    fs::create_directories(path_);
}

TempDirectory::~TempDirectory() {
    std::error_code ignored;
    fs::remove_all(path_, ignored);
}

std::vector<std::string> TempDirectory::entries() const {
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(path_)) names.push_back(entry.path().filename());
    std::sort(names.begin(), names.end());
    return names;
}

std::string read_text(const fs::path& file) {
    std::ifstream in(file);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
}

void write_text(const fs::path& file, const std::string& text) { std::ofstream(file) << text; }

}  // namespace wp::test
