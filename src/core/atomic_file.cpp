#include "core/atomic_file.h"

#include <unistd.h>

#include <string>
#include <system_error>

namespace wp {

namespace fs = std::filesystem;

namespace {

fs::path directory_of(const fs::path& path) {
    const fs::path parent = path.parent_path();
    return parent.empty() ? fs::path(".") : parent;
}

[[noreturn]] void fail(const fs::path& path, const std::string& problem) {
    throw OutputError("cannot write " + path.string() + ": " + problem);
}

}  // namespace

void check_writable_destination(const fs::path& path) {
    if (path.filename().empty()) fail(path, "not a file name");
    const fs::path directory = directory_of(path);
    std::error_code error;
    if (!fs::is_directory(directory, error)) fail(path, "directory " + directory.string() + " does not exist");
    if (::access(directory.c_str(), W_OK) != 0) fail(path, "directory " + directory.string() + " is not writable");
    if (fs::is_directory(path, error)) fail(path, "is a directory");
}

fs::path temporary_path_for(const fs::path& target) {
    // Appending (rather than "." + string) also avoids a GCC 12 -Wrestrict false positive.
    std::string name(".");
    name += target.filename().string();
    name += ".tmp-" + std::to_string(::getpid());
    name += target.extension().string();
    return directory_of(target) / name;
}

void write_atomically(const fs::path& target, const std::function<void(const fs::path& temporary)>& write) {
    const fs::path temporary = temporary_path_for(target);
    try {
        write(temporary);
        std::error_code error;
        fs::rename(temporary, target, error);
        if (error) fail(target, error.message());
    } catch (...) {
        std::error_code ignored;
        fs::remove(temporary, ignored);
        throw;
    }
}

}  // namespace wp
