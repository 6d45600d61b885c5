// Writing output files so that a reader (or a crash) never sees half of one:
// everything goes to a temporary file beside the target, then one rename.
#pragma once

#include <filesystem>
#include <functional>
#include <stdexcept>

namespace wp {

// An output file could not be written; one line naming the file and the cause.
class OutputError : public std::runtime_error {
 public:
    using std::runtime_error::runtime_error;
};

// Throws OutputError unless `path` names a file that can be created or
// replaced: its directory exists and is writable, and it is not a directory.
void check_writable_destination(const std::filesystem::path& path);

// The temporary name used for `target`: hidden, unique to this process, and
// ending in the target's own extension so that format detection still works,
// e.g. "out/.room.png.tmp-1234.png".
std::filesystem::path temporary_path_for(const std::filesystem::path& target);

// Calls `write(temporary)`, then renames the temporary onto `target`. If the
// writer throws or the rename fails, the temporary is removed, `target` is
// left as it was, and OutputError (or the writer's OutputError) propagates.
void write_atomically(const std::filesystem::path& target,
                      const std::function<void(const std::filesystem::path& temporary)>& write);

}  // namespace wp
