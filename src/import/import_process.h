// Mesh files are read by assimp in a child process, wavepath-import
// (import/helper/main.cpp), started for each file with posix_spawn (safe
// after MPI_Init: nothing of this process runs in the child) under
// MeshImportLimits, which answers over a pipe (import/answer.h). Whatever
// happens there (a crash, an allocation beyond its memory limit, a loop, a
// hang, an answer that is not well-formed) becomes one ImportProcessError.
#pragma once

#include <filesystem>
#include <stdexcept>
#include <string>

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

// The scene of `file` as `helper` imports it. Throws MeshFileError with the
// helper's own message if it could not read the file, ImportProcessError if
// the process failed, ImportHelperUnavailable if it could not be started.
ImportedScene import_in_child(const std::filesystem::path& file, const MeshImportLimits& limits,
                              const std::filesystem::path& helper = import_helper_path());

}  // namespace wp
