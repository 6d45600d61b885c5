// wavepath-import: reads mesh files with assimp for wavepath
// (import/import_process.h), which trusts nothing it sends.
//
// Usage: wavepath-import MEMORY_MIB CPU_S
// It dies with its parent. It reads requests on descriptor 0
// (kRequestFd), each a u32 length and that many bytes of a file's name,
// until end of file. For each it forks an importer, which limits itself
// before it opens the file: MEMORY_MIB more address space than it has then
// (RLIMIT_AS; an allocation beyond it ends it with status
// kHelperOutOfMemoryStatus), CPU_S seconds of CPU time (RLIMIT_CPU:
// SIGXCPU), no core files, and death with this process. The importer
// answers on descriptor 3 (kAnswerFd, import/answer.h) and exits; then this
// process writes its wait status and CPU time on descriptor 4
// (kStatusFd). One process per file, so what a malformed file does to an
// importer's memory ends with it; one start (the dynamic loader, assimp's
// relocations) for all the files of a scene.
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
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

bool limit_importer(std::uint64_t memory_mib, std::uint64_t cpu_s) {
    const rlim_t address_space = mapped_bytes() + (memory_mib << 20);
    return lower_limit(RLIMIT_CORE, 0, 0) && lower_limit(RLIMIT_CPU, cpu_s, cpu_s + 1) &&
           lower_limit(RLIMIT_AS, address_space, address_space);
}

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

// The importer: never returns.
[[noreturn]] void import_file(pid_t server, const std::string& file, std::uint64_t memory_mib, std::uint64_t cpu_s) {
    // The requests and statuses are the server's alone.
    ::close(wp::kRequestFd);
    ::close(wp::kStatusFd);
    if (!die_with_parent(server) || !limit_importer(memory_mib, cpu_s)) ::_exit(wp::kHelperUsageStatus);
    std::set_new_handler([] { ::_exit(wp::kHelperOutOfMemoryStatus); });
    std::string answer;
    try {
        answer = wp::encode_answer(wp::import_with_assimp(file));
    } catch (const wp::MeshFileError& error) {
        answer = wp::encode_answer(wp::ImportFailure{error.what()});
    }
    // No destructors: the answer is all that is left to do, and freeing a large scene takes time.
    ::_exit(write_all(wp::kAnswerFd, answer) ? 0 : 1);
}

// Imports `file` in a process of its own and reports how that process ended; false if it could not be started.
bool serve(const std::string& file, std::uint64_t memory_mib, std::uint64_t cpu_s) {
    const pid_t server = ::getpid();
    const pid_t importer = ::fork();
    if (importer < 0) return false;
    if (importer == 0) import_file(server, file, memory_mib, cpu_s);
    wp::ImporterStatus status{};
    rusage usage{};
    while (::wait4(importer, &status.wait_status, 0, &usage) < 0) {
        if (errno != EINTR) return false;
    }
    const auto seconds = [](const timeval& t) { return double(t.tv_sec) + 1e-6 * double(t.tv_usec); };
    status.cpu_s = seconds(usage.ru_utime) + seconds(usage.ru_stime);
    return write_all(wp::kStatusFd, std::string_view(reinterpret_cast<const char*>(&status), sizeof status));
}

}  // namespace

int main(int argc, char** argv) {
    std::uint64_t memory_mib = 0, cpu_s = 0;
    if (argc != 3 || !parse_count(argv[1], memory_mib) || !parse_count(argv[2], cpu_s) || memory_mib > (1ull << 40) ||
        ::prctl(PR_SET_PDEATHSIG, SIGKILL) != 0 || !lower_limit(RLIMIT_CORE, 0, 0))
        return wp::kHelperUsageStatus;
    std::string file;
    while (read_request(file)) {
        if (!serve(file, memory_mib, cpu_s)) return wp::kHelperUsageStatus;
    }
    return 0;
}
