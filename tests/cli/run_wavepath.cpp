#include "cli/run_wavepath.h"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <stdexcept>

extern char** environ;

namespace wp::test {

namespace fs = std::filesystem;

RunningWavepath::RunningWavepath(const std::vector<std::string>& args, const fs::path& scratch,
                                 const std::vector<std::string>& launcher, const fs::path& binary)
    : scratch_(scratch) {
    const fs::path out_file = scratch / "stdout.txt", err_file = scratch / "stderr.txt";
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, out_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, err_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);

    std::vector<std::string> argv_strings = launcher;
    argv_strings.push_back(binary);
    argv_strings.insert(argv_strings.end(), args.begin(), args.end());
    std::vector<char*> argv;
    for (std::string& arg : argv_strings) argv.push_back(arg.data());
    argv.push_back(nullptr);

    const int spawn_error = posix_spawn(&pid_, argv[0], &actions, nullptr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    if (spawn_error != 0) throw std::runtime_error("cannot start " + argv_strings[0]);
}

RunningWavepath::~RunningWavepath() {
    if (pid_ <= 0) return;
    ::kill(pid_, SIGKILL);
    waitpid(pid_, nullptr, 0);
}

void RunningWavepath::send(int signal) { ::kill(pid_, signal); }

CommandResult RunningWavepath::wait() {
    int status = 0;
    waitpid(pid_, &status, 0);
    pid_ = -1;
    const fs::path out_file = scratch_ / "stdout.txt", err_file = scratch_ / "stderr.txt";
    CommandResult result;
    result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    result.out = read_text(out_file);
    result.err = read_text(err_file);
    fs::remove(out_file);
    fs::remove(err_file);
    return result;
}

CommandResult run_wavepath(const std::vector<std::string>& args, const fs::path& scratch,
                           const std::vector<std::string>& launcher, const fs::path& binary) {
    return RunningWavepath(args, scratch, launcher, binary).wait();
}

}  // namespace wp::test
