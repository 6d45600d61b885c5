// What the fuzzers do with a mesh import that failed in wavepath-import's
// process (a crash, its memory, CPU or wall-time limit, a malformed answer):
// wavepath turned it into its one error, so it is no finding for libFuzzer,
// but it is what the fuzzers' runs count (docs/bad-input.md). Each is one
// line on stderr, "import failure: <message>", and its input is kept in the
// directory $WAVEPATH_FUZZ_IMPORT_FAILURES names, if set.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <string_view>

#include "import/import_limits.h"
#include "import/import_process.h"

namespace wp::fuzz {

// Small enough for two fuzzers side by side, and for a file that spins in
// assimp to end under run_fuzzer.sh's 15 s -timeout: it can run into the
// limits twice (an importer that had read other files fails it, then a
// fresh one alone: docs/bad-input.md, "The mesh import"), 2 CPU s or 4 s of
// wall time each, 8 s at most, with the helpers' starts under ASan.
inline const MeshImportLimits kImportLimits{1024, 2, 4.0};

// What an error line says just before wavepath-import's own words: ": wavepath-import ".
inline const std::string& import_helper_mark() {
    static const std::string mark = std::string(": ") + kImportHelperName + " ";
    return mark;
}

// Whether wavepath-import's words in an error line (what follows
// import_helper_mark) say its process failed, rather than the file.
inline bool is_process_failure(std::string_view helper_words) {
    for (std::string_view verb :
         {"crashed", "ran out of memory", "used its", "did not finish", "sent a malformed", "exited with status"}) {
        if (helper_words.starts_with(verb)) return true;
    }
    return false;
}

inline void note_import_failure(const std::string& message, const std::uint8_t* data, std::size_t size) {
    std::fprintf(stderr, "import failure: %s\n", message.c_str());
    const char* directory = std::getenv("WAVEPATH_FUZZ_IMPORT_FAILURES");
    if (directory == nullptr) return;
    const std::string_view input(reinterpret_cast<const char*>(data), size);
    char name[40];
    std::snprintf(name, sizeof name, "import-failure-%016zx", std::hash<std::string_view>{}(input));
    std::ofstream(std::filesystem::path(directory) / name, std::ios::binary).write(input.data(), input.size());
}

}  // namespace wp::fuzz
