#include "import/import_process.h"

#include <fcntl.h>
#include <poll.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/socket.h>
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
    Descriptor& operator=(Descriptor&& other) noexcept {
        std::swap(fd_, other.fd_);
        return *this;
    }
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

// A descriptor at 5 or above, close-on-exec: the helper's are dup2'd onto
// 0, 3 and 4 in the child, which must not overwrite one not yet moved.
int above_helper_descriptors(int fd) {
    const int moved = ::fcntl(fd, F_DUPFD_CLOEXEC, kStatusFd + 1);
    const int error = errno;
    ::close(fd);
    if (moved < 0)
        throw ImportHelperUnavailable("cannot make a pipe for " + std::string(kImportHelperName) + ": " +
                                      errno_text(error));
    return moved;
}

struct Channel {
    int ours, helpers;
};

// A pipe (the helper writes) or a socket pair (wavepath writes: a send to a helper that is gone is an error,
// not SIGPIPE).
Channel make_channel(bool to_helper) {
    int fds[2];
    const int made = to_helper ? ::socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, fds) : ::pipe2(fds, O_CLOEXEC);
    if (made != 0)
        throw ImportHelperUnavailable("cannot make a pipe for " + std::string(kImportHelperName) + ": " +
                                      errno_text(errno));
    return {fds[0], above_helper_descriptors(fds[1])};
}

// Reads what `fd` (non-blocking) holds now into `bytes`; false at end of file.
bool read_available(int fd, std::size_t max_bytes, std::string& bytes) {
    char chunk[1 << 16];
    for (;;) {
        const ssize_t count = ::read(fd, chunk, sizeof chunk);
        if (count == 0) return false;
        if (count < 0) {
            if (errno == EINTR) continue;
            if (errno == EAGAIN) return true;
            throw ImportHelperUnavailable("reading " + std::string(kImportHelperName) +
                                          "'s answer: " + errno_text(errno));
        }
        if (bytes.size() + std::size_t(count) > max_bytes)
            fail(ImportProcessFailure::Malformed,
                 "sent a malformed answer: more than " + std::to_string(max_bytes) + " bytes");
        bytes.append(chunk, std::size_t(count));
    }
}

void set_non_blocking(int fd) { ::fcntl(fd, F_SETFL, ::fcntl(fd, F_GETFL) | O_NONBLOCK); }

// A null-terminated array of the strings' characters, for posix_spawn.
std::vector<char*> pointers(std::vector<std::string>& strings) {
    std::vector<char*> result;
    for (std::string& text : strings) result.push_back(text.data());
    result.push_back(nullptr);
    return result;
}

}  // namespace

// How the importer of one request ended, and its answer.
struct MeshImporter::Outcome {
    ImporterStatus status;
    std::string answer;
    bool helper_ended = false;  // the helper ended instead (`status` is its own): start another
};

// The running helper: its requests on its descriptor 0, its importers'
// answers on 3, their statuses on 4; stdout and stderr are /dev/null (what
// assimp, or a crash, prints must not reach wavepath's one error line),
// every other descriptor closed. If it is still running when this goes out
// of scope, it is killed (its importer with it) and reaped.
class MeshImporter::Helper {
 public:
    Helper(const std::filesystem::path& helper, const MeshImportLimits& limits) {
        const Channel requests = make_channel(true), answers = make_channel(false), statuses = make_channel(false);
        requests_ = Descriptor(requests.ours);
        answers_ = Descriptor(answers.ours);
        statuses_ = Descriptor(statuses.ours);
        set_non_blocking(answers_.get());
        // The helper's copies stay open in it.
        const Descriptor request_end(requests.helpers), answer_end(answers.helpers), status_end(statuses.helpers);
        spawn(helper, limits, request_end.get(), answer_end.get(), status_end.get());
    }
    ~Helper() {
        if (running_) {
            ::kill(pid_, SIGKILL);
            reap();
        }
    }
    Helper(const Helper&) = delete;
    Helper& operator=(const Helper&) = delete;

    // Ends its requests: with no file under way, it and its importer exit on
    // their own (and are reaped, each by its parent, so that their resource
    // usage counts where their parent's does); killed if not within `grace`.
    void finish(Clock::duration grace) {
        requests_.reset();
        if (!wait_exit(Clock::now() + grace)) ::kill(pid_, SIGKILL);
        reap();
    }

    // Imports `file`: its importer's answer (at most `max_bytes`) and status.
    // Throws ImportProcessError (WallTime) when `deadline` passes first.
    // Asks it to import `file`; receive() takes the outcome.
    void send_request(const std::string& file) {
        const auto length = static_cast<std::uint32_t>(file.size());
        std::string request(reinterpret_cast<const char*>(&length), sizeof length);
        request += file;
        for (std::string_view left = request; !left.empty();) {
            const ssize_t sent = ::send(requests_.get(), left.data(), left.size(), MSG_NOSIGNAL);
            if (sent < 0 && errno == EINTR) continue;
            if (sent < 0) return;  // the helper is gone: its status says how it ended
            left.remove_prefix(std::size_t(sent));
        }
    }

    // The importer's answer (at most `max_bytes`) and status for the request
    // sent. Throws ImportProcessError (WallTime) when `deadline` passes first.
    Outcome receive(Clock::time_point deadline, std::size_t max_bytes) {
        Outcome outcome;
        pollfd entries[2] = {{answers_.get(), POLLIN, 0}, {statuses_.get(), POLLIN, 0}};
        std::size_t status_bytes = 0;
        auto* status = reinterpret_cast<char*>(&outcome.status);
        for (;;) {
            wait_for(entries, deadline);
            if (entries[0].revents != 0 && !read_available(answers_.get(), max_bytes, outcome.answer))
                entries[0].fd = -1;  // closed (a helper that answers once and exits)
            if (entries[1].revents == 0) continue;
            const ssize_t count = ::read(statuses_.get(), status + status_bytes, sizeof outcome.status - status_bytes);
            if (count < 0 && errno == EINTR) continue;
            if (count <= 0) return helper_ended(std::move(outcome), entries[0].fd >= 0, deadline, max_bytes);
            status_bytes += std::size_t(count);
            if (status_bytes < sizeof outcome.status) continue;
            // The importer has exited: all it wrote is in the pipe.
            if (entries[0].fd >= 0) read_available(answers_.get(), max_bytes, outcome.answer);
            return outcome;
        }
    }

 private:
    // Waits until one of `entries` is ready; throws WallTime past `deadline`.
    void wait_for(pollfd* entries, Clock::time_point deadline) {
        for (;;) {
            const int ready = ::poll(entries, 2, milliseconds_until(deadline));
            if (ready > 0) return;
            if (ready == 0) fail_wall_time();
            if (errno != EINTR)
                throw ImportHelperUnavailable("poll on " + std::string(kImportHelperName) +
                                              "'s answer: " + errno_text(errno));
        }
    }

    [[noreturn]] void fail_wall_time() {
        ::kill(pid_, SIGKILL);
        reap();
        fail(ImportProcessFailure::WallTime,
             "did not finish within " + format_number(limits_wall_s_) + " s and was stopped (--mesh-import-time)");
    }

    // The helper closed its statuses: the rest of its answer, then how it ended.
    Outcome helper_ended(Outcome outcome, bool answer_open, Clock::time_point deadline, std::size_t max_bytes) {
        pollfd answer{answers_.get(), POLLIN, 0};
        while (answer_open) {
            if (::poll(&answer, 1, milliseconds_until(deadline)) == 0) fail_wall_time();
            answer_open = read_available(answers_.get(), max_bytes, outcome.answer);
        }
        if (!wait_exit(deadline)) fail_wall_time();
        const auto [status, cpu_s] = reap();
        outcome.status = {status, cpu_s};
        outcome.helper_ended = true;
        return outcome;
    }

    // Blocks until it exits or `deadline` passes (false, still running).
    bool wait_exit(Clock::time_point deadline) {
        // A pidfd becomes readable when the process exits.
        Descriptor process(static_cast<int>(::syscall(SYS_pidfd_open, pid_, 0)));
        if (process.get() < 0) return true;  // no pidfd (Linux before 5.3): reap() blocks instead
        pollfd entry{process.get(), POLLIN, 0};
        while (::poll(&entry, 1, milliseconds_until(deadline)) < 0 && errno == EINTR) {
        }
        return entry.revents != 0;
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

    void spawn(const std::filesystem::path& helper, const MeshImportLimits& limits, int request_end, int answer_end,
               int status_end) {
        limits_wall_s_ = limits.wall_s;
        posix_spawn_file_actions_t actions;
        posix_spawn_file_actions_init(&actions);
        posix_spawn_file_actions_adddup2(&actions, request_end, kRequestFd);
        posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
        posix_spawn_file_actions_addopen(&actions, 2, "/dev/null", O_WRONLY, 0);
        posix_spawn_file_actions_adddup2(&actions, answer_end, kAnswerFd);
        posix_spawn_file_actions_adddup2(&actions, status_end, kStatusFd);
        posix_spawn_file_actions_addclosefrom_np(&actions, kStatusFd + 1);
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
                                           std::to_string(limits.cpu_s)};
        const std::vector<char*> argv = pointers(arguments);
        const int error = ::posix_spawn(&pid_, argv[0], &actions, &attributes, argv.data(), environ);
        posix_spawn_file_actions_destroy(&actions);
        posix_spawnattr_destroy(&attributes);
        if (error != 0)
            throw ImportHelperUnavailable("cannot start the mesh import helper " + helper.string() + ": " +
                                          errno_text(error));
        running_ = true;
    }

    Descriptor requests_, answers_, statuses_;
    pid_t pid_ = -1;
    bool running_ = false;
    double limits_wall_s_ = 0.0;
};

namespace {

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

MeshImporter::MeshImporter(const MeshImportLimits& limits, std::filesystem::path helper)
    : limits_(limits), helper_path_(std::move(helper)) {}

MeshImporter::~MeshImporter() {
    drop_started();  // files under way: their helpers killed
    for (std::unique_ptr<Helper>& helper : helpers_) {
        if (helper) helper->finish(std::chrono::seconds(1));
    }
}

void MeshImporter::expect(std::vector<std::filesystem::path> files) {
    drop_started();
    expected_ = std::move(files);
    next_expected_ = 0;
    start_expected();
}

void MeshImporter::start(const std::filesystem::path& file) {
    std::size_t free = 0;
    while (std::any_of(started_.begin(), started_.end(), [&](const Started& s) { return s.helper == free; })) ++free;
    if (helper_path_.empty()) helper_path_ = import_helper_path();
    if (!helpers_[free]) helpers_[free] = std::make_unique<Helper>(helper_path_, limits_);
    const auto wall = std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(limits_.wall_s));
    started_.push_back({file, free, Clock::now() + wall});
    helpers_[free]->send_request(file.native());
}

void MeshImporter::start_expected() {
    while (started_.size() < kHelpers && next_expected_ < expected_.size()) {
        const std::filesystem::path& file = expected_[next_expected_++];
        // Names it cannot send are import()'s to refuse.
        if (file.native().empty() || file.native().size() > kMaxRequestLength) break;
        start(file);
    }
}

void MeshImporter::drop_started() {
    for (const Started& started : started_) helpers_[started.helper].reset();  // killed, with its importer
    // The files started were the expected ones before next_expected_: they start again.
    next_expected_ -= std::min(next_expected_, started_.size());
    started_.clear();
}

ImportedScene MeshImporter::import(const std::filesystem::path& file) {
    const std::string& name = file.native();
    if (name.empty()) throw MeshFileError(std::string("cannot open: ") + errno_text(ENOENT));
    if (name.size() > kMaxRequestLength) throw MeshFileError(std::string("cannot open: ") + errno_text(ENAMETOOLONG));
    if (started_.empty() || started_.front().file != file) {  // not the file expected: import it alone
        drop_started();
        expected_.clear();
        next_expected_ = 0;
        start(file);
    }
    Outcome outcome = take_front();
    if (outcome.status.files_before > 0) {
        try {
            return scene_of(outcome);
        } catch (const MeshFileError&) {
            // Its importer had read other files before, so the failure may be
            // theirs: the file again, in a fresh helper and importer, whose
            // answer is the file's own.
            drop_started();
            for (std::unique_ptr<Helper>& helper : helpers_) helper.reset();
            start(file);
            outcome = take_front();
        }
    }
    return scene_of(outcome);
}

MeshImporter::Outcome MeshImporter::take_front() {
    const Started current = started_.front();
    std::unique_ptr<Helper>& helper = helpers_[current.helper];
    Outcome outcome;
    try {
        // The answer cannot be larger than the memory the importer may use.
        outcome = helper->receive(current.deadline, std::size_t(limits_.memory_mib) << 20);
    } catch (...) {
        helper.reset();  // killed, with its importer
        started_.pop_front();
        throw;
    }
    if (outcome.helper_ended) helper.reset();
    started_.pop_front();  // its helper is free: the next file starts while this one is checked
    start_expected();
    return outcome;
}

ImportedScene MeshImporter::scene_of(const Outcome& outcome) const {
    const int status = outcome.status.wait_status;
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) fail_on_status(status, outcome.status.cpu_s, limits_);
    ImportAnswer answer;
    try {
        answer = decode_answer(outcome.answer);
    } catch (const MalformedAnswer& error) {
        fail(ImportProcessFailure::Malformed, std::string("sent a malformed answer: ") + error.what());
    }
    if (const ImportFailure* failure = std::get_if<ImportFailure>(&answer)) throw MeshFileError(failure->message);
    return std::move(std::get<ImportedScene>(answer));
}

ImportedScene import_in_child(const std::filesystem::path& file, const MeshImportLimits& limits,
                              const std::filesystem::path& helper) {
    return MeshImporter(limits, helper).import(file);
}

}  // namespace wp
