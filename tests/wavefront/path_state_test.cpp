// The path state list: its docs table, its writers and readers, and buffers
// only for features in use.
#include "wavefront/path_state.h"

#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <regex>
#include <sstream>

#include "support/kernel_sources.h"
#include "wavefront/host_trace.h"
#include "wavefront/stage.h"

namespace wp {
namespace {

TEST(PathState, ArchitectureDocHasTheCurrentFieldTable) {
    std::ifstream in(WAVEPATH_SOURCE_DIR "/docs/architecture.md");
    std::stringstream doc;
    doc << in.rdbuf();
    EXPECT_NE(doc.str().find(path_state_table_markdown()), std::string::npos) << "docs/architecture.md must contain:\n"
                                                                              << path_state_table_markdown();
}

// The fields' "written by" and "read by" (the docs table's columns) name
// exactly the stages whose kernels, with the kernel headers they include,
// PATH_WRITE and PATH_READ the field, or whose rays the host reads and whose
// results it writes where it traces (host_trace_fields), in stage order.
TEST(PathState, WritersAndReadersAreTheStagesThatWriteAndReadTheField) {
    std::map<std::string, std::string> written_by, read_by;  // field -> stages, space-separated
    auto add = [](std::string& stages, const char* stage) {
        if (!stages.empty()) stages += ' ';
        stages += stage;
    };
    static const std::regex use(R"(\bPATH_(READ|WRITE)\(\s*(\w+))");
    for (const StageDeclaration& stage : stage_declarations) {
        const std::string code = test::kernel_code_with_includes(std::string(stage.kernel) + ".cl");
        ASSERT_NE(code.find("STAGE_QUEUES"), std::string::npos) << stage.kernel;
        std::set<std::string> reads, writes;
        for (std::sregex_iterator m(code.begin(), code.end(), use), end; m != end; ++m)
            ((*m)[1] == "READ" ? reads : writes).insert((*m)[2]);
        const HostTraceFields host = host_trace_fields(stage.traces);
        reads.insert(host.reads.begin(), host.reads.end());
        writes.insert(host.writes.begin(), host.writes.end());
        for (const std::string& field : writes) add(written_by[field], stage.kernel);
        for (const std::string& field : reads) add(read_by[field], stage.kernel);
    }
    for (const PathStateField& f : path_state_fields()) {
        EXPECT_EQ(f.writers, written_by[f.name]) << f.name;
        EXPECT_EQ(f.readers, read_by[f.name]) << f.name;
    }
}

TEST(PathState, FieldsExistOnlyForFeaturesInUse) {
    FeatureSet diffuse_only;
    diffuse_only.spheres = diffuse_only.diffuse = true;
    FeatureSet with_glass = diffuse_only;
    with_glass.glass = true;
    FeatureSet diffuse_nee = diffuse_only, glass_mis = with_glass;
    diffuse_nee.nee = glass_mis.nee = glass_mis.mis = true;
    FeatureSet diffuse_mis = diffuse_nee;
    diffuse_mis.mis = true;
    std::size_t base = PathState::bytes_per_path(diffuse_only);
    EXPECT_EQ(PathState::bytes_per_path(with_glass), base + 4 + 4);        // specular flag, eta_scale
    EXPECT_EQ(PathState::bytes_per_path(diffuse_nee), base + 11 * 4);      // shadow ray, contribution, ends path
    EXPECT_EQ(PathState::bytes_per_path(diffuse_mis), base + 11 * 4 + 4);  // and the bounce's density
    FeatureSet glass_mis_host_traced = glass_mis, diffuse_host_traced = diffuse_only;
    glass_mis_host_traced.host_traced = diffuse_host_traced.host_traced = true;
    EXPECT_EQ(PathState::bytes_per_path(diffuse_host_traced), base);  // no shadow rays: nothing more
    std::size_t total = 0;
    for (const PathStateField& f : path_state_fields()) total += f.bytes;
    EXPECT_EQ(PathState::bytes_per_path(glass_mis_host_traced), total);
    EXPECT_EQ(PathState::bytes_per_path(glass_mis), total - 4);  // the shadow rays' verdicts, from the host
}

}  // namespace
}  // namespace wp
