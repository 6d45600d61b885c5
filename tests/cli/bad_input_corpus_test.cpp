// The corpus of malformed inputs (tests/corpus/bad/, docs/bad-input.md)
// through the wavepath binary: each case exits 3 with exactly the one error
// line its directory's expected_errors.tsv gives, and leaves no output file.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "cli/run_wavepath.h"

namespace wp::test {
namespace {

namespace fs = std::filesystem;

const fs::path kCorpus = fs::path(WAVEPATH_SOURCE_DIR) / "tests/corpus/bad";
constexpr const char* kTable = "expected_errors.tsv";

// One kind of input: a directory of cases, the files that are cases (the
// others are theirs: mesh files beside a scene), and the command that reads one.
struct CorpusKind {
    const char* directory;
    const char* case_extension;
    std::vector<std::string> (*command)(const std::string& input, const std::string& output);
};

// The mesh import's limits (docs/scene-format.md) small enough that a case on which assimp loops
// or allocates without end fails in seconds; the wall-clock limit far above the CPU limit, so
// that a loaded machine does not change which limit a case meets.
std::vector<std::string> render_scene(const std::string& scene, const std::string& output) {
    return {
        "render", scene, "-o", output, "--mesh-import-memory", "1024", "--mesh-import-cpu", "5", "--mesh-import-time",
        "300"};
}

const CorpusKind kKinds[] = {
    {"scenes", ".json", render_scene},
    // Mitsuba 3 XML scenes (docs/scene-format.md, "Mitsuba XML"), with what they include
    // (<case>.inc) and name (<case>.serialized) beside them.
    {"xml", ".xml", render_scene},
    // glTF 2.0 files given as the scene (docs/scene-format.md, "glTF scenes").
    {"gltf", ".gltf", render_scene},
    // scripts/make_checkpoint_corpus.py writes these, for this command.
    {"checkpoints", ".wpfilm",
     [](const std::string& checkpoint, const std::string& output) {
         return std::vector<std::string>{"render",   std::string(WAVEPATH_SOURCE_DIR) + "/scenes/test/room_small.json",
                                         "-o",       output,
                                         "--width",  "4",
                                         "--height", "4",
                                         "--spp",    "2",
                                         "--resume", checkpoint};
     }},
};

// expected_errors.tsv: "<case file>\t<the line after "wavepath: error: ">",
// '#' comments; in the line, {input} stands for the case's path and {dir}
// for its directory.
std::map<std::string, std::string> read_table(const fs::path& directory) {
    std::ifstream in(directory / kTable);
    EXPECT_TRUE(in) << "cannot open " << (directory / kTable);
    std::map<std::string, std::string> table;
    for (std::string line; std::getline(in, line);) {
        if (line.empty() || line[0] == '#') continue;
        const std::size_t tab = line.find('\t');
        EXPECT_NE(tab, std::string::npos) << "no tab in: " << line;
        if (tab == std::string::npos) continue;
        EXPECT_TRUE(table.emplace(line.substr(0, tab), line.substr(tab + 1)).second) << "twice: " << line;
    }
    return table;
}

std::string expand(std::string text, const std::string& name, const std::string& value) {
    for (std::size_t at = text.find(name); at != std::string::npos; at = text.find(name, at + value.size()))
        text.replace(at, name.size(), value);
    return text;
}

TEST(BadInputCorpus, EveryCaseFailsWithItsOneLineExitCode3AndNoOutput) {
    TempDirectory scratch{"scratch"}, outputs{"outputs"};
    int cases = 0;
    for (const CorpusKind& kind : kKinds) {
        const fs::path directory = kCorpus / kind.directory;
        for (const auto& [file, line] : read_table(directory)) {
            SCOPED_TRACE(std::string(kind.directory) + "/" + file);
            const std::string input = (directory / file).string();
            const CommandResult result = run_wavepath(kind.command(input, outputs / "out.exr"), scratch.path());
            EXPECT_EQ(result.exit_code, 3);
            // Exactly one line, all of it: the comparison checks the newline count too.
            EXPECT_EQ(result.err,
                      "wavepath: error: " + expand(expand(line, "{input}", input), "{dir}", directory) + "\n");
            EXPECT_EQ(result.out, "");
            EXPECT_EQ(outputs.entries(), std::vector<std::string>{});
            ++cases;
        }
    }
    EXPECT_GE(cases, 30);  // issue 13: a corpus of at least 30
}

// Every case file has its line and every line its file; every other file
// belongs to a case (a mesh file named after its scene), so none is orphaned.
TEST(BadInputCorpus, TablesAndDirectoriesAgree) {
    for (const CorpusKind& kind : kKinds) {
        const fs::path directory = kCorpus / kind.directory;
        const std::map<std::string, std::string> table = read_table(directory);
        std::set<std::string> case_stems;
        for (const auto& [file, line] : table) {
            EXPECT_TRUE(fs::is_regular_file(directory / file)) << file << " is in the table, not in " << directory;
            case_stems.insert(fs::path(file).stem());
        }
        for (const auto& entry : fs::directory_iterator(directory)) {
            const fs::path name = entry.path().filename();
            if (name == kTable) continue;
            if (name.extension() == kind.case_extension) {
                EXPECT_TRUE(table.contains(name)) << name << " has no line in " << (directory / kTable);
            } else {
                EXPECT_TRUE(case_stems.contains(name.stem())) << name << " belongs to no case";
            }
        }
    }
}

}  // namespace
}  // namespace wp::test
