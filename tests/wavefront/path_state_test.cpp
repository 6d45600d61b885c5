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
#include "wavefront/sppm_state.h"
#include "wavefront/stage.h"

namespace wp {
namespace {

void expect_architecture_doc_contains(const std::string& table) {
    std::ifstream in(WAVEPATH_SOURCE_DIR "/docs/architecture.md");
    std::stringstream doc;
    doc << in.rdbuf();
    EXPECT_NE(doc.str().find(table), std::string::npos) << "docs/architecture.md must contain:\n" << table;
}

TEST(PathState, ArchitectureDocHasTheCurrentFieldTable) {
    expect_architecture_doc_contains(path_state_table_markdown());
}

TEST(SppmState, ArchitectureDocHasTheCurrentEntryTable) {
    expect_architecture_doc_contains(sppm_state_table_markdown());
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
    diffuse_nee.shadow_stage = glass_mis.shadow_stage = true;
    FeatureSet diffuse_mis = diffuse_nee;
    diffuse_mis.mis = true;
    std::size_t base = PathState::bytes_per_path(diffuse_only);
    EXPECT_EQ(PathState::bytes_per_path(with_glass), base + 4 + 4);        // specular flag, eta_scale
    EXPECT_EQ(PathState::bytes_per_path(diffuse_nee), base + 11 * 4);      // shadow ray, contribution, ends path
    EXPECT_EQ(PathState::bytes_per_path(diffuse_mis), base + 11 * 4 + 4);  // and the bounce's density
    FeatureSet shadows_in_shade = diffuse_mis;
    shadows_in_shade.shadow_stage = false;  // shade traces them: no shadow ray kept
    EXPECT_EQ(PathState::bytes_per_path(shadows_in_shade), base + 4);
    FeatureSet glass_mis_host_traced = glass_mis, diffuse_host_traced = diffuse_only;
    glass_mis_host_traced.host_traced = diffuse_host_traced.host_traced = true;
    EXPECT_EQ(PathState::bytes_per_path(diffuse_host_traced), base);  // no shadow rays: nothing more
    FeatureSet sppm = glass_mis;
    sppm.sppm = true;
    // the camera path's distance travelled, the photon and its flux
    EXPECT_EQ(PathState::bytes_per_path(sppm), PathState::bytes_per_path(glass_mis) + 4 + 4 + 12);
    FeatureSet everything = glass_mis_host_traced;
    everything.sppm = true;
    std::size_t total = 0;
    for (const PathStateField& f : path_state_fields()) total += f.bytes;
    EXPECT_EQ(PathState::bytes_per_path(everything), total);
    EXPECT_EQ(PathState::bytes_per_path(glass_mis), total - 4 - 20);  // the shadow verdicts, sppm's fields
}

// The bytes per item --profile reports for a stage come from the declared
// readers and writers of the fields whose buffers exist, whole stage names
// only (intersect is not intersect_shadow nor intersect_photons), plus its
// queue entry and one entry per push target. The figures below are read off
// kernels/interface/path_state.h and stages.h by hand.
TEST(PathState, StageBytesPerItemComeFromTheDeclarations) {
    FeatureSet diffuse;
    diffuse.spheres = diffuse.diffuse = true;
    const StageBytes intersect = stage_bytes_per_item(declaration(Stage::intersect), diffuse);
    // origin, direction
    EXPECT_EQ(intersect.state_read, 12u + 12);
    EXPECT_EQ(intersect.state_written, 4u + 4);  // hit_t, hit_shape
    EXPECT_EQ(intersect.queue_read, 4u);
    EXPECT_EQ(intersect.queue_written, 4u);  // HIT
    EXPECT_EQ(intersect.total(), 24u + 8 + 4 + 4);

    const StageBytes shade = stage_bytes_per_item(declaration(Stage::shade), diffuse);
    // pixel, sample, pass_item, depth, origin, direction, throughput, radiance, hit_t, hit_shape
    EXPECT_EQ(shade.state_read, 4u * 4 + 4 * 12 + 4 + 4);
    EXPECT_EQ(shade.state_written, 4u + 4 * 12);  // depth, origin, direction, throughput, radiance
    EXPECT_EQ(shade.queue_written, 3u * 4);       // SHADOW, RAY, FREE

    // Fields only some renders have: specular, eta_scale and bsdf_pdf are
    // read and written by shade, the shadow ray only written.
    FeatureSet glass_mis = diffuse;
    glass_mis.glass = glass_mis.nee = glass_mis.mis = glass_mis.shadow_stage = true;
    const StageBytes shade_glass_mis = stage_bytes_per_item(declaration(Stage::shade), glass_mis);
    EXPECT_EQ(shade_glass_mis.state_read, shade.state_read + 3 * 4);
    EXPECT_EQ(shade_glass_mis.state_written, shade.state_written + 3 * 4 + (12 + 12 + 4 + 12 + 4));

    const StageBytes shadow = stage_bytes_per_item(declaration(Stage::intersect_shadow), glass_mis);
    // pass_item, radiance, shadow_origin, shadow_direction, shadow_distance, shadow_radiance, shadow_ends_path
    EXPECT_EQ(shadow.state_read, 4u + 12 + 12 + 12 + 4 + 12 + 4);
    EXPECT_EQ(shadow.state_written, 12u);  // radiance
    EXPECT_EQ(shadow.queue_written, 0u);
    FeatureSet host_traced = glass_mis;
    host_traced.host_traced = true;  // the host's verdicts, shadow_occluded
    const StageBytes shadow_host = stage_bytes_per_item(declaration(Stage::intersect_shadow), host_traced);
    EXPECT_EQ(shadow_host.state_read, shadow.state_read + 4);
    EXPECT_EQ(shadow_host.state_written, shadow.state_written + 4);

    FeatureSet sppm = diffuse;
    sppm.sppm = true;
    const StageBytes emit = stage_bytes_per_item(declaration(Stage::emit_photons), sppm);
    EXPECT_EQ(emit.state_read, 0u);
    // depth, origin, direction, throughput, photon, photon_flux
    EXPECT_EQ(emit.state_written, 4u + 12 + 12 + 12 + 4 + 12);
    EXPECT_EQ(emit.queue_written, 4u);  // PHOTON_RAY
}

}  // namespace
}  // namespace wp
