// wavepath-import: reads mesh files with assimp for wavepath
// (import/import_process.h), which trusts nothing it sends.
//
// Usage: wavepath-import MEMORY_MIB CPU_S
// It dies with its parent. It forks an importer, which reads requests on
// descriptor 0 (kRequestFd), each a u32 length and that many bytes of a
// file's name, until end of file, and answers each on descriptor 3
// (kAnswerFd, import/answer.h). Before each file the importer limits
// itself, counted from there: MEMORY_MIB more address space than it has
// then (RLIMIT_AS; an allocation beyond it ends it with status
// kHelperOutOfMemoryStatus) and CPU_S more seconds of CPU time (RLIMIT_CPU:
// SIGXCPU); no core files, and death with this process. After each answer
// this process writes a status on descriptor 4 (kStatusFd): the file's CPU
// time and how many files the importer had answered before. An importer
// that ends on a file (a crash, a limit) is reported with its wait status,
// and the next request goes to a new one: wavepath imports a file that
// failed in an importer that had read others again in a fresh one
// (import/import_process.h), so that a failure is the file's own. One start
// (the dynamic loader, assimp's relocations) and one importer for the files
// of a scene that import cleanly (bench/results/big_scenes.md).
#include <fcntl.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <new>
#include <string>
#include <string_view>

#include "import/answer.h"
#include "import/helper/assimp_import.h"
#include "import/mesh_file_error.h"

namespace {

bool parse_count(std::string_view text, std::uint64_t& value) {
    auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
    return error == std::errc() && end == text.data() + text.size() && value > 0;
}

// The address space mapped now (the executable, its libraries, its heap), from /proc/self/statm.
std::uint64_t mapped_bytes() {
    std::FILE* statm = std::fopen("/proc/self/statm", "r");
    unsigned long pages = 0;
    if (statm == nullptr || std::fscanf(statm, "%lu", &pages) != 1) pages = 0;
    if (statm != nullptr) std::fclose(statm);
    return std::uint64_t(pages) * std::uint64_t(::sysconf(_SC_PAGESIZE));
}

// Lowers a limit, never above the hard limit it was started with.
bool lower_limit(int resource, rlim_t soft, rlim_t hard) {
    rlimit limit{};
    if (::getrlimit(resource, &limit) != 0) return false;
    limit.rlim_cur = std::min(soft, limit.rlim_max);
    limit.rlim_max = std::min(hard, limit.rlim_max);
    return ::setrlimit(resource, &limit) == 0;
}

// Death with the parent; false if the parent is already gone (it is no longer `parent`).
bool die_with_parent(pid_t parent) { return ::prctl(PR_SET_PDEATHSIG, SIGKILL) == 0 && ::getppid() == parent; }

bool write_all(int fd, std::string_view bytes) {
    while (!bytes.empty()) {
        const ssize_t written = ::write(fd, bytes.data(), bytes.size());
        if (written < 0 && errno == EINTR) continue;
        if (written < 0) return false;
        bytes.remove_prefix(std::size_t(written));
    }
    return true;
}

// Fills `bytes` from `fd`; false at end of file or an error before it is full.
bool read_all(int fd, char* bytes, std::size_t count) {
    while (count > 0) {
        const ssize_t got = ::read(fd, bytes, count);
        if (got < 0 && errno == EINTR) continue;
        if (got <= 0) return false;
        bytes += got;
        count -= std::size_t(got);
    }
    return true;
}

// The next request's file name; false at end of file (wavepath is done) or a malformed request.
bool read_request(std::string& file) {
    std::uint32_t length = 0;
    if (!read_all(wp::kRequestFd, reinterpret_cast<char*>(&length), sizeof length) || length == 0 ||
        length > wp::kMaxRequestLength)
        return false;
    file.resize(length);
    return read_all(wp::kRequestFd, file.data(), length);
}

double cpu_seconds(int who) {
    rusage usage{};
    ::getrusage(who, &usage);
    const auto seconds = [](const timeval& t) { return double(t.tv_sec) + 1e-6 * double(t.tv_usec); };
    return seconds(usage.ru_utime) + seconds(usage.ru_stime);
}

// The limits of one file, counted from now: the memory and CPU time it has already used stay the importer's.
bool limit_file(std::uint64_t memory_mib, std::uint64_t cpu_s) {
    const rlim_t address_space = mapped_bytes() + (memory_mib << 20);
    const auto cpu_limit = rlim_t(std::ceil(cpu_seconds(RUSAGE_SELF))) + cpu_s;
    return lower_limit(RLIMIT_CPU, cpu_limit, RLIM_INFINITY) && lower_limit(RLIMIT_AS, address_space, RLIM_INFINITY);
}

// The importer: reads requests and answers them until the requests end; never returns. After each answer it
// tells the server (on `done`) the CPU time the file took.
[[noreturn]] void run_importer(pid_t server, int done, std::uint64_t memory_mib, std::uint64_t cpu_s) {
    ::close(wp::kStatusFd);  // the server's alone
    if (!die_with_parent(server) || !lower_limit(RLIMIT_CORE, 0, 0)) ::_exit(wp::kHelperUsageStatus);
    std::set_new_handler([] { ::_exit(wp::kHelperOutOfMemoryStatus); });
    std::string file;
    double cpu_before = cpu_seconds(RUSAGE_SELF);
    while (read_request(file)) {
        if (!limit_file(memory_mib, cpu_s)) ::_exit(wp::kHelperUsageStatus);
        std::string answer;
        try {
            answer = wp::encode_answer(wp::import_with_assimp(file));
        } catch (const wp::MeshFileError& error) {
            answer = wp::encode_answer(wp::ImportFailure{error.what()});
        }
        const double cpu = cpu_seconds(RUSAGE_SELF);
        const double file_cpu_s = cpu - cpu_before;
        cpu_before = cpu;
        if (!write_all(wp::kAnswerFd, answer) ||
            !write_all(done, std::string_view(reinterpret_cast<const char*>(&file_cpu_s), sizeof file_cpu_s)))
            ::_exit(1);
    }
    ::_exit(0);  // the requests ended: wavepath is done
}

bool write_status(const wp::ImporterStatus& status) {
    return write_all(wp::kStatusFd, std::string_view(reinterpret_cast<const char*>(&status), sizeof status));
}

enum class Served { RequestsEnded, ImporterEnded, Failed };

// Starts an importer and reports each file it answers, until the requests
// end or the importer ends on a file (reported with the files it had
// answered before; the next importer takes the next request).
Served serve(std::uint64_t memory_mib, std::uint64_t cpu_s) {
    const pid_t server = ::getpid();
    int done[2];
    if (::pipe2(done, O_CLOEXEC) != 0) return Served::Failed;
    const pid_t importer = ::fork();
    if (importer < 0) return Served::Failed;
    if (importer == 0) {
        ::close(done[0]);
        run_importer(server, done[1], memory_mib, cpu_s);
    }
    ::close(done[1]);
    wp::ImporterStatus status{};
    double answered_cpu_s = 0.0;
    while (read_all(done[0], reinterpret_cast<char*>(&status.cpu_s), sizeof status.cpu_s)) {
        if (!write_status(status)) return Served::Failed;
        ++status.files_before;
        answered_cpu_s += status.cpu_s;
    }
    ::close(done[0]);
    rusage usage{};
    while (::wait4(importer, &status.wait_status, 0, &usage) < 0) {
        if (errno != EINTR) return Served::Failed;
    }
    if (WIFEXITED(status.wait_status) && WEXITSTATUS(status.wait_status) == 0) return Served::RequestsEnded;
    const auto seconds = [](const timeval& t) { return double(t.tv_sec) + 1e-6 * double(t.tv_usec); };
    status.cpu_s = seconds(usage.ru_utime) + seconds(usage.ru_stime) - answered_cpu_s;  // the file's own
    return write_status(status) ? Served::ImporterEnded : Served::Failed;
}

}  // namespace

int main(int argc, char** argv) {
    std::uint64_t memory_mib = 0, cpu_s = 0;
    if (argc != 3 || !parse_count(argv[1], memory_mib) || !parse_count(argv[2], cpu_s) || memory_mib > (1ull << 40) ||
        ::prctl(PR_SET_PDEATHSIG, SIGKILL) != 0 || !lower_limit(RLIMIT_CORE, 0, 0))
        return wp::kHelperUsageStatus;
    for (;;) {
        switch (serve(memory_mib, cpu_s)) {
            case Served::RequestsEnded:
                return 0;
            case Served::ImporterEnded:
                continue;
            case Served::Failed:
                return wp::kHelperUsageStatus;
        }
    }
}
