// Kernel sources read as text, for the tests that hold declarations and docs
// to what the kernels do: a kernel file with the kernel headers it includes,
// without comments or preprocessor lines.
#pragma once

#include <filesystem>
#include <regex>
#include <set>
#include <sstream>
#include <string>

#include "support/temp_directory.h"

namespace wp::test {

inline const std::filesystem::path kKernelDirectory = WAVEPATH_SOURCE_DIR "/kernels";

// `source` without its /* */ and // comments, and with backslash-continued
// lines joined.
inline std::string without_comments(const std::string& source) {
    std::string code;
    for (std::size_t at = 0; at < source.size();) {
        if (source.compare(at, 2, "/*") == 0) {
            std::size_t end = source.find("*/", at + 2);
            at = end == std::string::npos ? source.size() : end + 2;
            code += ' ';
        } else if (source.compare(at, 2, "//") == 0) {
            at = source.find('\n', at);
            if (at == std::string::npos) at = source.size();
        } else if (source.compare(at, 2, "\\\n") == 0) {
            at += 2;
        } else {
            code += source[at++];
        }
    }
    return code;
}

// The code of kernels/<file> and of every header under kernels/ it includes,
// directly or not, each once: comments and preprocessor lines (#include,
// #define, #if ...) left out, so that what remains is what the code does.
inline std::string kernel_code_with_includes(const std::string& file, std::set<std::string>& seen) {
    if (!seen.insert(file).second) return "";
    std::istringstream lines(without_comments(read_text(kKernelDirectory / file)));
    static const std::regex include(R"re(^\s*#\s*include\s*"([^"]+)")re");
    std::string code, line;
    for (std::smatch m; std::getline(lines, line);) {
        const std::size_t first = line.find_first_not_of(" \t");
        if (first == std::string::npos || line[first] != '#')
            code += line + "\n";
        else if (std::regex_search(line, m, include) && std::filesystem::exists(kKernelDirectory / m[1].str()))
            code += kernel_code_with_includes(m[1].str(), seen);
    }
    return code;
}

inline std::string kernel_code_with_includes(const std::string& file) {
    std::set<std::string> seen;
    return kernel_code_with_includes(file, seen);
}

}  // namespace wp::test
