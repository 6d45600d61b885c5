#include "opencl/program_cache.h"

#include <unistd.h>

#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

namespace wp {
namespace fs = std::filesystem;
namespace {

std::string read_file(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw DeviceError("cannot read kernel file " + path.string());
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

// FNV-1a, 64 bits: stable across runs and machines, enough to key a cache.
struct Fnv1a {
    std::uint64_t hash = 14695981039346656037ull;
    void add(const std::string& text) {
        for (unsigned char c : text) hash = (hash ^ c) * 1099511628211ull;
        hash = (hash ^ 0xffu) * 1099511628211ull;  // separator, so that ("ab","c") != ("a","bc")
    }
};

// Every regular file under the kernel directory, sorted.
std::vector<fs::path> kernel_tree_files(const fs::path& dir) {
    std::vector<fs::path> files;
    if (fs::is_directory(dir))
        for (const fs::directory_entry& e : fs::recursive_directory_iterator(dir))
            if (e.is_regular_file()) files.push_back(e.path());
    std::sort(files.begin(), files.end());
    return files;
}

std::string cache_key(const DeviceInfo& device, const fs::path& dir, const std::vector<std::string>& files,
                      const std::string& options) {
    Fnv1a h;
    for (const std::string& s : {device.platform, device.platform_version, device.name, device.driver_version, options})
        h.add(s);
    for (const std::string& name : files) h.add(name);  // which program: the wavefront's or the megakernel's
    for (const fs::path& file : kernel_tree_files(dir)) {
        h.add(file.lexically_relative(dir).string());
        h.add(read_file(file));
    }
    char hex[17];
    std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(h.hash));
    return hex;
}

// The first error as "file:line: message", from either log format:
// clang's "file:line:col: error: message" or PoCL's "error: file:line:col: message"
// (in a macro expansion, "error: file:line:col <Spelling=header:line:col>: message",
// the line of the macro's use).
std::string first_error_line(const std::string& log) {
    static const std::regex clang_format(R"(([^\s:][^:\n]*):(\d+):\d+: (?:fatal )?error: ([^\n]*))");
    static const std::regex pocl_format(
        R"((?:fatal )?error: ([^\s:][^:\n]*):(\d+):\d+(?: <Spelling=[^>\n]*>)?: ([^\n]*))");
    std::smatch m;
    if (std::regex_search(log, m, pocl_format) || std::regex_search(log, m, clang_format))
        return m[1].str() + ":" + m[2].str() + ": " + m[3].str();
    return "(no error location in the build log)";
}

// Writes atomically (temporary file, then rename) so that concurrent
// renders never read a half-written binary.
void store_binary(const fs::path& file, const std::vector<unsigned char>& binary) {
    std::error_code error;
    fs::create_directories(file.parent_path(), error);
    fs::path temporary = file;
    temporary += ".tmp" + std::to_string(::getpid());
    {
        std::ofstream out(temporary, std::ios::binary);
        out.write(reinterpret_cast<const char*>(binary.data()), static_cast<std::streamsize>(binary.size()));
        if (!out) return;  // a cache that cannot be written is only slower
    }
    fs::rename(temporary, file, error);
    if (error) fs::remove(temporary, error);
}

bool build_from_binary(const cl::Context& context, const DeviceInfo& device, const fs::path& file,
                       const std::string& options, cl::Program& program) {
    std::error_code error;
    if (file.empty() || !fs::is_regular_file(file, error)) return false;
    std::string bytes = read_file(file);
    try {
        cl::Program::Binaries binaries{std::vector<unsigned char>(bytes.begin(), bytes.end())};
        program = cl::Program(context, {device.device}, binaries);
        program.build({device.device}, options.c_str());
        return true;
    } catch (const cl::Error&) {
        return false;  // stale or corrupt: rebuild from source and overwrite
    }
}

cl::Program build_from_source(const cl::Context& context, const DeviceInfo& device, const fs::path& dir,
                              const std::vector<std::string>& files, const std::string& options) {
    // #line makes the compiler name each .cl file in its messages, although
    // the files are compiled as one program.
    std::string source;
    for (const std::string& name : files)
        source += "#line 1 \"" + (dir / name).string() + "\"\n" + read_file(dir / name) + "\n";
    cl::Program program(context, source);
    try {
        program.build({device.device}, options.c_str());
    } catch (const cl::BuildError&) {
        std::string log = program.getBuildInfo<CL_PROGRAM_BUILD_LOG>(device.device);
        throw KernelBuildError(first_error_line(log), log);
    }
    return program;
}

}  // namespace

std::string kernel_directory() {
    const char* env = std::getenv("WAVEPATH_KERNEL_DIR");
    return env && *env ? env : WAVEPATH_KERNEL_DIR;
}

std::string program_cache_directory() {
    if (const char* env = std::getenv("WAVEPATH_CACHE_DIR"); env && *env) return env;
    if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg) return (fs::path(xdg) / "wavepath").string();
    if (const char* home = std::getenv("HOME"); home && *home) return (fs::path(home) / ".cache" / "wavepath").string();
    return "";
}

std::string compiler_options(const std::string& options) {
    // Correctly rounded divide and sqrt, as in C++; never fast-math or -cl-mad-enable.
    return "-cl-std=CL1.2 -cl-fp32-correctly-rounded-divide-sqrt -I " + kernel_directory() + " " + options;
}

BuiltProgram build_program(const cl::Context& context, const DeviceInfo& device, const std::vector<std::string>& files,
                           const std::string& options, const Progress& progress) {
    fs::path dir = kernel_directory();
    BuiltProgram built;
    built.options = compiler_options(options);
    std::string cache_dir = program_cache_directory();
    if (!cache_dir.empty())
        built.cache_file = (fs::path(cache_dir) / (cache_key(device, dir, files, built.options) + ".bin")).string();

    auto start = std::chrono::steady_clock::now();
    built.cache_hit = build_from_binary(context, device, built.cache_file, built.options, built.program);
    if (!built.cache_hit) {
        progress.announce(built.cache_file.empty()
                              ? "building the kernels for this scene (no cache directory: every run rebuilds them)"
                              : "building the kernels for this scene; later runs with the same features reuse "
                                "them from " +
                                    fs::path(built.cache_file).parent_path().string());
        built.program = build_from_source(context, device, dir, files, built.options);
        if (!built.cache_file.empty()) {
            std::vector<std::vector<unsigned char>> binaries = built.program.getInfo<CL_PROGRAM_BINARIES>();
            if (!binaries.empty() && !binaries.front().empty()) store_binary(built.cache_file, binaries.front());
        }
    }
    built.build_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return built;
}

std::string explain_build(const std::string& options, bool cache_hit, double build_seconds,
                          const std::string& cache_file) {
    std::ostringstream out;
    out << "build options: " << options << "\n"
        << "program: " << (cache_hit ? "cache hit" : "cache miss, compiled") << " in " << build_seconds << " s"
        << (cache_file.empty() ? " (no cache directory)" : " (" + cache_file + ")") << "\n";
    return out.str();
}

}  // namespace wp
