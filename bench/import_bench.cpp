// import_bench: what containing the mesh import costs (issue 23). The time
// to read a mesh file into a Mesh in process (assimp in this process:
// import_with_assimp, then mesh_from_import) against contained
// (read_mesh_file: wavepath-import started for the file under the default
// limits, its answer decoded and checked, then mesh_from_import), for the
// bunny (69,666 triangles) and the bunny subdivided twice (1,114,656
// triangles, written as OBJ). Two settings:
//  - warm: every import in this process, one after another, whose memory
//    the earlier imports have already touched;
//  - fresh: every import in a new process (this program, started again with
//    --import-once), as a wavepath run imports its meshes once, into memory
//    it has never touched; its start is not counted.
// In each, the two interleaved, alternating which goes first, after one
// unrecorded round; wall clock and CPU time (user + system, the helper's
// and the fresh process's included). Besides: the helper's start alone (a
// file it cannot open: start, answer, exit) and the least
// --mesh-import-memory each mesh imports under (bisection).
//
// Usage: import_bench [--runs N] [--markdown FILE] [--json FILE] [--keep DIR]
// --keep: write the subdivided mesh into DIR and leave it there.
// import_bench --import-once in_process|contained FILE: one import, its wall
// and CPU seconds printed (the fresh setting's process).
#include <sys/resource.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "bench_support.h"
#include "import/helper/assimp_import.h"
#include "import/import_process.h"
#include "scene/mesh_file.h"

namespace {

using namespace wp;
using namespace wp::bench;
using json = nlohmann::json;
namespace fs = std::filesystem;

const fs::path kBunny = fs::path(WAVEPATH_SOURCE_DIR) / "scenes/meshes/bunny.obj";

Mesh in_process(const fs::path& file) { return mesh_from_import(import_with_assimp(file), {}); }
Mesh contained(const fs::path& file) {
    MeshImporter importer({});  // started for this file
    return read_mesh_file(file, {}, importer);
}

bool identical(const Mesh& a, const Mesh& b) {
    const auto same = [](const auto& x, const auto& y) {
        return x.size() == y.size() && (x.empty() || std::memcmp(x.data(), y.data(), x.size() * sizeof(x[0])) == 0);
    };
    return same(a.positions, b.positions) && same(a.normals, b.normals) && same(a.triangles, b.triangles);
}

void write_obj(const Mesh& mesh, const fs::path& file) {
    std::FILE* out = std::fopen(file.c_str(), "w");
    for (const glm::dvec3& p : mesh.positions) std::fprintf(out, "v %.9g %.9g %.9g\n", p.x, p.y, p.z);
    for (const glm::uvec3& t : mesh.triangles) std::fprintf(out, "f %u %u %u\n", t.x + 1, t.y + 1, t.z + 1);
    std::fclose(out);
}

// What an import used: wall-clock seconds, CPU seconds (user + system) and of
// those the system's, and minor page faults (first touches of memory); CPU
// and faults of this process and of every process it waited for.
struct Usage {
    double wall = 0.0, cpu = 0.0, system = 0.0, faults = 0.0;
};
constexpr double Usage::*kMeasures[] = {&Usage::wall, &Usage::cpu, &Usage::system, &Usage::faults};
constexpr const char* kMeasureNames[] = {"wall clock s", "CPU s", "system CPU s", "minor page faults"};

Usage resources_used() {
    Usage usage;
    for (int who : {RUSAGE_SELF, RUSAGE_CHILDREN}) {
        rusage r{};
        ::getrusage(who, &r);
        const auto seconds = [](const timeval& t) { return double(t.tv_sec) + 1e-6 * double(t.tv_usec); };
        usage.cpu += seconds(r.ru_utime) + seconds(r.ru_stime);
        usage.system += seconds(r.ru_stime);
        usage.faults += double(r.ru_minflt);
    }
    return usage;
}

Usage measure_import(const std::function<Mesh()>& import, Mesh* result = nullptr) {
    const Clock::time_point start = Clock::now();
    const Usage before = resources_used();
    Mesh mesh = import();
    const Usage after = resources_used();
    if (result) *result = std::move(mesh);
    return {seconds_since(start), after.cpu - before.cpu, after.system - before.system, after.faults - before.faults};
}

// One import in a new process: this program again, with --import-once.
Usage measure_import_in_fresh_process(bool contained_turn, const fs::path& file) {
    const std::string command = "'" + fs::read_symlink("/proc/self/exe").string() + "' --import-once " +
                                (contained_turn ? "contained" : "in_process") + " '" + file.string() + "'";
    Usage usage;
    FILE* pipe = ::popen(command.c_str(), "r");
    const bool read =
        pipe && std::fscanf(pipe, "%lf %lf %lf %lf", &usage.wall, &usage.cpu, &usage.system, &usage.faults) == 4;
    if (pipe) ::pclose(pipe);
    if (!read) throw std::runtime_error("no figures from " + command);
    return usage;
}

struct Timing {
    std::vector<Usage> in_process, contained;
    bool identical = true;  // each warm result, to the bit (fresh: not compared)
};

Timing time_imports(const fs::path& file, int runs, bool fresh) {
    Timing timing;
    const Mesh reference = in_process(file);
    for (int run = -1; run < runs; ++run) {  // run -1: unrecorded
        for (int turn = 0; turn < 2; ++turn) {
            const bool contained_turn = (run + turn) % 2 != 0;  // alternating which goes first
            Usage usage;
            if (fresh) {
                usage = measure_import_in_fresh_process(contained_turn, file);
            } else {
                Mesh mesh;
                usage = measure_import([&] { return contained_turn ? contained(file) : in_process(file); }, &mesh);
                timing.identical &= identical(mesh, reference);
            }
            if (run >= 0) (contained_turn ? timing.contained : timing.in_process).push_back(usage);
        }
    }
    return timing;
}

// The least memory limit (MiB) under which the helper imports `file`.
std::uint64_t least_memory_limit(const fs::path& file) {
    std::uint64_t fails = 0, imports = 8192;  // it fails at `fails` and imports at `imports`
    while (imports - fails > 1) {
        const std::uint64_t middle = (fails + imports) / 2;
        try {
            import_in_child(file, {middle, 300, 600.0});
            imports = middle;
        } catch (const ImportProcessError&) {
            fails = middle;
        }
    }
    return imports;
}

std::string load_average() {
    std::ifstream in("/proc/loadavg");
    std::string one, five, fifteen;
    in >> one >> five >> fifteen;
    return one + " " + five + " " + fifteen;
}

std::string fixed(double value, int decimals) {
    char text[32];
    std::snprintf(text, sizeof text, "%.*f", decimals, value);
    return text;
}

std::string with_thousands(std::uint64_t n) {
    std::string digits = std::to_string(n), text;
    for (std::size_t i = 0; i < digits.size(); ++i) {
        if (i > 0 && (digits.size() - i) % 3 == 0) text += ',';
        text += digits[i];
    }
    return text;
}

json statistics(const std::vector<Usage>& usages, double Usage::*measure) {
    std::vector<double> values;
    for (const Usage& usage : usages) values.push_back(usage.*measure);
    return {{"min", minimum(values)}, {"median", median(values)}, {"all", values}};
}

json timing_row(const std::string& mesh, std::size_t triangles, const char* setting, const Timing& timing) {
    json row{{"mesh", mesh}, {"triangles", triangles}, {"setting", setting}, {"identical", timing.identical}};
    for (std::size_t m = 0; m < std::size(kMeasures); ++m) {
        row["measures"][kMeasureNames[m]] = {{"in_process", statistics(timing.in_process, kMeasures[m])},
                                             {"contained", statistics(timing.contained, kMeasures[m])}};
    }
    return row;
}

std::string markdown(const json& results) {
    const json& meta = results["meta"];
    std::string text =
        "# Mesh import: in process against contained\n\n"
        "Generated by `build/bench/import_bench --markdown bench/results/mesh_import.md` (bench/import_bench.cpp); "
        "do not edit by hand.\n\n";
    text += "- commit `" + meta["commit"].get<std::string>() + "`, " + meta["date"].get<std::string>() + "\n";
    text += "- machine: " + meta["cpu"].get<std::string>() + ", " + std::to_string(meta["cores"].get<int>()) +
            " cores; load average " + meta["load_before"].get<std::string>() + " before, " +
            meta["load_after"].get<std::string>() + " after (1, 5, 15 min; shared with other work)\n";
    text += "- " + std::to_string(meta["runs"].get<int>()) +
            " runs of each, interleaved (alternating which goes first) after one unrecorded round. OpenCL is not "
            "involved.\n\n";
    text +=
        "In process: assimp in the importing process (`import_with_assimp`), then `mesh_from_import`. "
        "Contained: `read_mesh_file`, which starts `wavepath-import` for the file under the default limits, "
        "reads and checks its answer, then `mesh_from_import`. Warm: every import in the benchmark's process, "
        "one after another. Fresh: every import in a new process (the benchmark started again), as a wavepath run "
        "imports its meshes once; the process's start is not counted. CPU is user + system time; CPU and page faults "
        "include the helper's and the fresh process's. Warm results are "
        "compared bit for bit with the first in-process one on every run.\n\n";
    text +=
        "| mesh | triangles | setting | measure | in process (min / median) | contained (min / median) | "
        "contained / in process (min, median) |\n|---|---|---|---|---|---|---|\n";
    for (const json& row : results["timings"]) {
        for (const char* measure : kMeasureNames) {
            const json& in = row["measures"][measure]["in_process"];
            const json& out = row["measures"][measure]["contained"];
            const int decimals = measure == std::string("minor page faults") ? 0 : 3;
            text += "| " + row["mesh"].get<std::string>() + " | " + with_thousands(row["triangles"]) + " | " +
                    row["setting"].get<std::string>() + " | " + measure + " | " + fixed(in["min"], decimals) + " / " +
                    fixed(in["median"], decimals) + " | " + fixed(out["min"], decimals) + " / " +
                    fixed(out["median"], decimals) + " | " +
                    fixed(out["min"].get<double>() / in["min"].get<double>(), 3) + ", " +
                    fixed(out["median"].get<double>() / in["median"].get<double>(), 3) + " |\n";
        }
    }
    bool identical = true;
    for (const json& row : results["timings"]) identical &= row["identical"].get<bool>();
    text += std::string("\nWarm results identical to the bit on every run: ") + (identical ? "yes" : "NO") + ".\n";
    const json& start = results["helper_start"];
    text +=
        "\nThe helper's start alone (`import_in_child` of a file it cannot open: spawn, the dynamic loader, "
        "its limits, its answer, its exit): " +
        fixed(1e3 * start["s_min"].get<double>(), 1) + " ms min, " + fixed(1e3 * start["s_median"].get<double>(), 1) +
        " ms median.\n\n";
    text += "| mesh | least `--mesh-import-memory` it imports under (MiB) |\n|---|---|\n";
    for (const json& row : results["memory"]) {
        text += "| " + row["mesh"].get<std::string>() + " | " +
                std::to_string(row["least_memory_limit_mib"].get<std::uint64_t>()) + " |\n";
    }
    return text;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc == 4 && argv[1] == std::string("--import-once")) {
        const bool contained_mode = argv[2] == std::string("contained");
        const fs::path file = argv[3];
        const Usage usage = measure_import([&] { return contained_mode ? contained(file) : in_process(file); });
        std::printf("%.6f %.6f %.6f %.0f\n", usage.wall, usage.cpu, usage.system, usage.faults);
        return 0;
    }
    int runs = 7;
    std::string markdown_path, json_path, keep;
    for (int i = 1; i < argc; i += 2) {
        const std::string flag = argv[i];
        const char* value = i + 1 < argc ? argv[i + 1] : nullptr;
        if (value != nullptr && flag == "--runs" && std::atoi(value) > 0) {
            runs = std::atoi(value);
        } else if (value != nullptr && flag == "--markdown") {
            markdown_path = value;
        } else if (value != nullptr && flag == "--json") {
            json_path = value;
        } else if (value != nullptr && flag == "--keep") {
            keep = value;
        } else {
            std::fprintf(stderr,
                         "import_bench: bad argument '%s' (usage: import_bench [--runs N] [--markdown FILE] "
                         "[--json FILE] [--keep DIR])\n",
                         flag.c_str());
            return 2;
        }
    }
    json results;
    results["meta"] = machine_metadata();
    results["meta"]["runs"] = runs;
    results["meta"]["load_before"] = load_average();

    const fs::path scratch = keep.empty()
                                 ? fs::temp_directory_path() / ("wavepath-import-bench-" + std::to_string(::getpid()))
                                 : fs::path(keep);
    fs::create_directories(scratch);
    const fs::path subdivided = scratch / "bunny_subdivided_twice.obj";
    write_obj(subdivide(subdivide(in_process(kBunny))), subdivided);

    const std::pair<std::string, fs::path> meshes[] = {{"bunny.obj", kBunny},
                                                       {"bunny subdivided twice (OBJ)", subdivided}};
    for (const auto& [name, file] : meshes) {
        const std::size_t triangles = in_process(file).triangles.size();
        for (const bool fresh : {false, true}) {
            const Timing timing = time_imports(file, runs, fresh);
            results["timings"].push_back(timing_row(name, triangles, fresh ? "fresh" : "warm", timing));
            const json& cpu = results["timings"].back()["measures"]["CPU s"];
            std::printf("%s, %s: CPU s (medians) in process %.3f, contained %.3f\n", name.c_str(),
                        fresh ? "fresh" : "warm", cpu["in_process"]["median"].get<double>(),
                        cpu["contained"]["median"].get<double>());
        }
    }
    for (const auto& [name, file] : meshes)
        results["memory"].push_back({{"mesh", name}, {"least_memory_limit_mib", least_memory_limit(file)}});
    std::vector<double> start_s;
    for (int run = 0; run < 4 * runs; ++run) {
        const Clock::time_point start = Clock::now();
        try {
            import_in_child(scratch / "absent.obj", {});
        } catch (const MeshFileError&) {
        }
        start_s.push_back(seconds_since(start));
    }
    results["helper_start"] = {{"s_min", minimum(start_s)}, {"s_median", median(start_s)}};
    results["meta"]["load_after"] = load_average();
    if (keep.empty()) fs::remove_all(scratch);

    const std::string text = markdown(results);
    std::printf("\n%s", text.c_str());
    if (!markdown_path.empty()) std::ofstream(markdown_path) << text;
    if (!json_path.empty()) std::ofstream(json_path) << results.dump(2) << "\n";
}
