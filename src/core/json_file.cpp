#include "core/json_file.h"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <nlohmann/json.hpp>

#include "core/atomic_file.h"

namespace wp {

void write_json_atomically(const nlohmann::json& value, const std::string& path) {
    check_writable_destination(path);
    write_atomically(path, [&](const std::filesystem::path& temporary) {
        std::ofstream out(temporary);
        out << value.dump(2) << '\n';
        out.close();
        if (!out) throw OutputError("cannot write " + path + ": " + std::strerror(errno));
    });
}

}  // namespace wp
