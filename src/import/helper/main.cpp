// wavepath-import: reads one mesh file with assimp and answers on descriptor
// 3 (import/answer.h), for wavepath, which starts it for each mesh file
// (import/import_process.h) and trusts nothing it sends.
//
// Usage: wavepath-import MEMORY_MIB CPU_S FILE
// Before it opens FILE it limits itself: MEMORY_MIB more address space than
// it has at its start (RLIMIT_AS; an allocation beyond it ends it with
// status kHelperOutOfMemoryStatus), CPU_S seconds of CPU time (RLIMIT_CPU:
// SIGXCPU), no core files, and death with its parent.
#include <sys/prctl.h>
#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
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

bool limit_self(std::uint64_t memory_mib, std::uint64_t cpu_s) {
    const rlim_t address_space = mapped_bytes() + (memory_mib << 20);
    return ::prctl(PR_SET_PDEATHSIG, SIGKILL) == 0 && lower_limit(RLIMIT_CORE, 0, 0) &&
           lower_limit(RLIMIT_CPU, cpu_s, cpu_s + 1) && lower_limit(RLIMIT_AS, address_space, address_space);
}

bool write_all(int fd, std::string_view bytes) {
    while (!bytes.empty()) {
        const ssize_t written = ::write(fd, bytes.data(), bytes.size());
        if (written < 0) return false;
        bytes.remove_prefix(std::size_t(written));
    }
    return true;
}

}  // namespace

int main(int argc, char** argv) {
    std::uint64_t memory_mib = 0, cpu_s = 0;
    if (argc != 4 || !parse_count(argv[1], memory_mib) || !parse_count(argv[2], cpu_s) || memory_mib > (1ull << 40) ||
        !limit_self(memory_mib, cpu_s))
        return wp::kHelperUsageStatus;
    std::set_new_handler([] { ::_exit(wp::kHelperOutOfMemoryStatus); });

    std::string answer;
    try {
        answer = wp::encode_answer(wp::import_with_assimp(argv[3]));
    } catch (const wp::MeshFileError& error) {
        answer = wp::encode_answer(wp::ImportFailure{error.what()});
    }
    // No destructors: the answer is all that is left to do, and freeing a large scene takes time.
    ::_exit(write_all(wp::kAnswerFd, answer) ? 0 : 1);
}
