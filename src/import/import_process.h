// Mesh files are read by assimp in child processes: wavepath-import
// (import/helper/main.cpp), started once with posix_spawn (safe after
// MPI_Init: nothing of this process runs in the child) under
// MeshImportLimits, forks an importer, which reads the files one after
// another, each under the limits, and answers over a pipe
// (import/answer.h). Whatever happens there (a crash, an allocation beyond
// its memory limit, a loop, a hang, an answer that is not well-formed)
// becomes one ImportProcessError for that file; a file that fails in an
// importer that had read other files is imported again in a fresh one, so
// that its failure is its own.
#pragma once

#include <array>
#include <chrono>
#include <deque>
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "import/import_limits.h"
#include "import/imported_scene.h"
#include "import/mesh_file_error.h"

namespace wp {

inline constexpr const char* kImportHelperName = "wavepath-import";

enum class ImportProcessFailure { Crashed, OutOfMemory, CpuTime, WallTime, Malformed, ExitStatus };

// The helper failed; what() says how, in one line.
class ImportProcessError : public MeshFileError {
 public:
    ImportProcessError(ImportProcessFailure failure, const std::string& message)
        : MeshFileError(message), failure_(failure) {}
    ImportProcessFailure failure() const { return failure_; }

 private:
    ImportProcessFailure failure_;
};

// The helper could not be started (it is missing, or the system refused):
// an installation problem, not the mesh file's.
class ImportHelperUnavailable : public std::runtime_error {
 public:
    using std::runtime_error::runtime_error;
};

// wavepath-import beside the running executable (/proc/self/exe): the build
// puts it beside wavepath and links it beside the test programs, fuzzers and
// benchmarks; an installation puts it beside wavepath.
std::filesystem::path import_helper_path();

// Imports mesh files in an importer process, forked by a wavepath-import
// that is started at the first file, kept for the next and started again
// after a failure that ended it (or, after any failure of a file in an
// importer that had read others, to import that file alone). A scene's loader keeps one
// for all the scene's files (one start instead of one per file) and says
// which files it will ask for: then the next is imported while wavepath
// checks the one before (bench/results/big_scenes.md). The answers are
// taken in the loader's order, each a function of its file alone.
class MeshImporter {
 public:
    // `helper` empty: import_helper_path(), found at the first file.
    explicit MeshImporter(const MeshImportLimits& limits, std::filesystem::path helper = {});
    ~MeshImporter();
    MeshImporter(const MeshImporter&) = delete;
    MeshImporter& operator=(const MeshImporter&) = delete;

    // The files import() will be asked for next, in order: the helpers start
    // on them ahead. (Asked for another file, it drops what it started.)
    void expect(std::vector<std::filesystem::path> files);

    // The scene of `file` as the helper imports it under the limits (the
    // wall-clock limit counts from the file's start: this call, or where
    // expect() started it ahead). Throws MeshFileError with the importer's
    // own message if it could not read the file, ImportProcessError if the
    // importer or the helper failed, ImportHelperUnavailable if the helper
    // could not be started.
    ImportedScene import(const std::filesystem::path& file);

    const MeshImportLimits& limits() const { return limits_; }

    class Helper;

 private:
    static constexpr std::size_t kHelpers = 1;  // files under way at once
    struct Started {
        std::filesystem::path file;
        std::size_t helper;  // index into helpers_
        std::chrono::steady_clock::time_point deadline;
    };
    void start(const std::filesystem::path& file);  // on a helper with no file under way
    void start_expected();                          // up to kHelpers files under way
    void drop_started();
    struct Outcome;        // how one file's import ended (import_process.cpp)
    Outcome take_front();  // the first file under way's; then the next expected file starts
    ImportedScene scene_of(const Outcome& outcome) const;  // or the error it is

    MeshImportLimits limits_;
    std::filesystem::path helper_path_;
    std::array<std::unique_ptr<Helper>, kHelpers> helpers_;  // none before their first file and after a failure
    std::deque<Started> started_;                            // the files under way, in the order asked for
    std::vector<std::filesystem::path> expected_;
    std::size_t next_expected_ = 0;  // the first of expected_ not yet started
};

// One file in a helper of its own (MeshImporter::import).
ImportedScene import_in_child(const std::filesystem::path& file, const MeshImportLimits& limits,
                              const std::filesystem::path& helper = import_helper_path());

}  // namespace wp
