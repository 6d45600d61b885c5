// The path state list: its docs table, and buffers only for features in use.
#include "wavefront/path_state.h"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

namespace wp {
namespace {

TEST(PathState, ArchitectureDocHasTheCurrentFieldTable) {
    std::ifstream in(WAVEPATH_SOURCE_DIR "/docs/architecture.md");
    std::stringstream doc;
    doc << in.rdbuf();
    EXPECT_NE(doc.str().find(path_state_table_markdown()), std::string::npos) << "docs/architecture.md must contain:\n"
                                                                              << path_state_table_markdown();
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
    EXPECT_EQ(PathState::bytes_per_path(diffuse_nee), base + 10 * 4);      // shadow ray and contribution
    EXPECT_EQ(PathState::bytes_per_path(diffuse_mis), base + 10 * 4 + 4);  // and the bounce's density
    std::size_t total = 0;
    for (const PathStateField& f : path_state_fields()) total += f.bytes;
    EXPECT_EQ(PathState::bytes_per_path(glass_mis), total);
}

}  // namespace
}  // namespace wp
