#include "import/import_process.h"

#include <fcntl.h>
#include <poll.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/syscall.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstring>
#include <utility>
#include <variant>
#include <vector>

#include "core/number_text.h"
#include "import/answer.h"

extern char** environ;

namespace wp {
namespace {

using Clock = std::chrono::steady_clock;

[[noreturn]] void fail(ImportProcessFailure failure, const std::string& message) {
    throw ImportProcessError(failure, std::string(kImportHelperName) + " " + message);
}

std::string errno_text(int error) { return std::strerror(error); }

// A file descriptor, closed when it goes out of scope.
class Descriptor {
 public:
    explicit Descriptor(int fd = -1) : fd_(fd) {}
    ~Descriptor() { reset(); }
    Descriptor(const Descriptor&) = delete;
    Descriptor& operator=(const Descriptor&) = delete;
    int get() const { return fd_; }
    void reset() {
        if (fd_ >= 0) ::close(fd_);
        fd_ = -1;
    }

 private:
    int fd_;
};

// Milliseconds to `deadline` for poll, rounded up so that it never wakes early; 0 once past.
int milliseconds_until(Clock::time_point deadline) {
    const auto left = std::chrono::ceil<std::chrono::milliseconds>(deadline - Clock::now()).count();
    return static_cast<int>(std::clamp<long long>(left, 0, 1 << 30));
}

// Waits until `fd` is readable or `deadline` passes (false).
bool wait_readable(int fd, Clock::time_point deadline) {
    pollfd entry{fd, POLLIN, 0};
    for (;;) {
        const int ready = ::poll(&entry, 1, milliseconds_until(deadline));
        if (ready > 0) return true;
        if (ready == 0) return false;
        if (errno != EINTR)
            throw ImportHelperUnavailable("poll on " + std::string(kImportHelperName) +
                                          "'s answer: " + errno_text(errno));
    }
}

// The running helper. Its answer pipe is its descriptor 3; stdin, stdout and
// stderr are /dev/null (what assimp, or a crash, prints must not reach
// wavepath's one error line), every other descriptor closed. If it is still
// running when this goes out of scope, it is killed and reaped.
class HelperProcess {
 public:
    HelperProcess(const std::filesystem::path& helper, const std::filesystem::path& file,
                  const MeshImportLimits& limits)
        : HelperProcess(make_pipe(), helper, file, limits) {}
    ~HelperProcess() {
        if (running_) {
            ::kill(pid_, SIGKILL);
            reap();
        }
    }
    HelperProcess(const HelperProcess&) = delete;
    HelperProcess& operator=(const HelperProcess&) = delete;

    int answer_fd() const { return answer_.get(); }
    void kill() { ::kill(pid_, SIGKILL); }

    // Blocks until it exits or `deadline` passes (false, still running).
    bool wait_exit(Clock::time_point deadline) {
        // A pidfd becomes readable when the process exits.
        Descriptor process(static_cast<int>(::syscall(SYS_pidfd_open, pid_, 0)));
        if (process.get() < 0) return true;  // no pidfd (Linux before 5.3): reap() blocks instead
        return wait_readable(process.get(), deadline);
    }
    // Waits for it to exit: its status and the CPU time it used.
    std::pair<int, double> reap() {
        int status = 0;
        rusage usage{};
        while (::wait4(pid_, &status, 0, &usage) < 0 && errno == EINTR) {
        }
        running_ = false;
        const auto seconds = [](const timeval& t) { return double(t.tv_sec) + 1e-6 * double(t.tv_usec); };
        return {status, seconds(usage.ru_utime) + seconds(usage.ru_stime)};
    }

 private:
    struct PipeEnds {
        int read, write;
    };
    static PipeEnds make_pipe() {
        int fds[2];
        if (::pipe2(fds, O_CLOEXEC) != 0)
            throw ImportHelperUnavailable("cannot make a pipe for " + std::string(kImportHelperName) + ": " +
                                          errno_text(errno));
        return {fds[0], fds[1]};
    }
    HelperProcess(PipeEnds pipe, const std::filesystem::path& helper, const std::filesystem::path& file,
                  const MeshImportLimits& limits)
        : answer_(pipe.read) {
        const Descriptor write_end(pipe.write);  // the helper's copy stays open in it
        spawn(helper, file, limits, write_end.get());
    }

    void spawn(const std::filesystem::path& helper, const std::filesystem::path& file, const MeshImportLimits& limits,
               int write_end) {
        posix_spawn_file_actions_t actions;
        posix_spawn_file_actions_init(&actions);
        posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
        posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
        posix_spawn_file_actions_addopen(&actions, 2, "/dev/null", O_WRONLY, 0);
        posix_spawn_file_actions_adddup2(&actions, write_end, kAnswerFd);
        posix_spawn_file_actions_addclosefrom_np(&actions, kAnswerFd + 1);
        // Signals at their defaults (SIGXCPU ends it at its CPU limit) and none blocked.
        posix_spawnattr_t attributes;
        posix_spawnattr_init(&attributes);
        sigset_t signals;
        sigfillset(&signals);
        sigdelset(&signals, SIGKILL);
        sigdelset(&signals, SIGSTOP);
        posix_spawnattr_setsigdefault(&attributes, &signals);
        sigemptyset(&signals);
        posix_spawnattr_setsigmask(&attributes, &signals);
        posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETSIGDEF | POSIX_SPAWN_SETSIGMASK);

        std::vector<std::string> arguments{helper.string(), std::to_string(limits.memory_mib),
                                           std::to_string(limits.cpu_s), file.string()};
        std::vector<char*> argv;
        for (std::string& argument : arguments) argv.push_back(argument.data());
        argv.push_back(nullptr);
        const int error = ::posix_spawn(&pid_, argv[0], &actions, &attributes, argv.data(), environ);
        posix_spawn_file_actions_destroy(&actions);
        posix_spawnattr_destroy(&attributes);
        if (error != 0)
            throw ImportHelperUnavailable("cannot start the mesh import helper " + helper.string() + ": " +
                                          errno_text(error));
        running_ = true;
    }

    Descriptor answer_;
    pid_t pid_ = -1;
    bool running_ = false;
};

// Reads the answer until the helper closes the pipe. Returns false if
// `deadline` passed first; throws if it sends more than `max_bytes`.
bool read_answer(int fd, Clock::time_point deadline, std::size_t max_bytes, std::string& answer) {
    std::vector<char> chunk(1 << 16);
    for (;;) {
        if (!wait_readable(fd, deadline)) return false;
        const ssize_t count = ::read(fd, chunk.data(), chunk.size());
        if (count == 0) return true;
        if (count < 0) {
            if (errno == EINTR) continue;
            throw ImportHelperUnavailable("reading " + std::string(kImportHelperName) +
                                          "'s answer: " + errno_text(errno));
        }
        if (answer.size() + std::size_t(count) > max_bytes)
            fail(ImportProcessFailure::Malformed,
                 "sent a malformed answer: more than " + std::to_string(max_bytes) + " bytes");
        answer.append(chunk.data(), std::size_t(count));
    }
}

std::string signal_text(int signal) { return "signal " + std::to_string(signal) + ": " + ::strsignal(signal); }

// What its exit status says, when it did not answer.
[[noreturn]] void fail_on_status(int status, double cpu_s, const MeshImportLimits& limits) {
    if (WIFEXITED(status)) {
        if (WEXITSTATUS(status) == kHelperOutOfMemoryStatus)
            fail(ImportProcessFailure::OutOfMemory, "ran out of memory importing it (limit " +
                                                        std::to_string(limits.memory_mib) +
                                                        " MiB, --mesh-import-memory)");
        fail(ImportProcessFailure::ExitStatus, "exited with status " + std::to_string(WEXITSTATUS(status)));
    }
    const int signal = WTERMSIG(status);
    // SIGXCPU at its soft CPU limit, SIGKILL at the hard one a second later.
    if (signal == SIGXCPU || (signal == SIGKILL && cpu_s >= double(limits.cpu_s)))
        fail(ImportProcessFailure::CpuTime,
             "used its " + std::to_string(limits.cpu_s) + " s of CPU time importing it (--mesh-import-cpu)");
    fail(ImportProcessFailure::Crashed, "crashed importing it (" + signal_text(signal) + ")");
}

}  // namespace

std::filesystem::path import_helper_path() {
    std::error_code error;
    const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", error);
    if (error) throw ImportHelperUnavailable("cannot find the running executable (/proc/self/exe): " + error.message());
    return self.parent_path() / kImportHelperName;
}

ImportedScene import_in_child(const std::filesystem::path& file, const MeshImportLimits& limits,
                              const std::filesystem::path& helper) {
    const Clock::time_point deadline =
        Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(limits.wall_s));
    HelperProcess process(helper, file, limits);
    std::string bytes;
    // The answer cannot be larger than the memory the helper may use.
    const bool answered = read_answer(process.answer_fd(), deadline, std::size_t(limits.memory_mib) << 20, bytes);
    if (!answered || !process.wait_exit(deadline)) {
        process.kill();
        process.reap();
        fail(ImportProcessFailure::WallTime,
             "did not finish within " + format_number(limits.wall_s) + " s and was stopped (--mesh-import-time)");
    }
    const auto [status, cpu_s] = process.reap();
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) fail_on_status(status, cpu_s, limits);
    ImportAnswer answer;
    try {
        answer = decode_answer(bytes);
    } catch (const MalformedAnswer& error) {
        fail(ImportProcessFailure::Malformed, std::string("sent a malformed answer: ") + error.what());
    }
    if (const ImportFailure* failure = std::get_if<ImportFailure>(&answer)) throw MeshFileError(failure->message);
    return std::move(std::get<ImportedScene>(answer));
}

}  // namespace wp
