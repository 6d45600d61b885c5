// Mitsuba 3's named media (src/scene/named_media.h): lookups by name. That
// the table is Mitsuba's own is CTest's named_media_match_mitsuba
// (scripts/named_media.py --check).
#include "scene/named_media.h"

#include <gtest/gtest.h>

namespace wp {
namespace {
// A namespace of its own: the sanitizer build compiles test files together (unity).
namespace named_media_test {

TEST(NamedMedia, ConductorsHaveMitsubasRgbIndex) {
    const std::optional<ComplexIor> gold = named_conductor("Au");
    ASSERT_TRUE(gold);
    EXPECT_NEAR(gold->eta.x, 0.143036, 1e-6);  // Mitsuba 3.9.1, llvm_ad_rgb
    EXPECT_NEAR(gold->k.z, 1.60336, 1e-5);
    for (const char* metal : {"Ag", "Al", "Cr", "Cu", "Cu_palik", "W"}) EXPECT_TRUE(named_conductor(metal)) << metal;
}

// "none" is the perfect mirror: eta 0, k 1 (Fresnel reflectance 1).
TEST(NamedMedia, NoneIsThePerfectMirror) {
    const std::optional<ComplexIor> none = named_conductor("none");
    ASSERT_TRUE(none);
    EXPECT_EQ(none->eta, glm::dvec3(0.0));
    EXPECT_EQ(none->k, glm::dvec3(1.0));
}

// Conductor names are Mitsuba's file names, matched exactly; index names
// match in any case, as Mitsuba lowers them.
TEST(NamedMedia, ConductorNamesAreExactAndIndexNamesAnyCase) {
    EXPECT_FALSE(named_conductor("au"));
    EXPECT_FALSE(named_conductor("gold"));
    EXPECT_EQ(named_ior("bk7"), 1.5046);
    EXPECT_EQ(named_ior("BK7"), 1.5046);
    EXPECT_EQ(named_ior("Carbon Dioxide"), 1.00045);
    EXPECT_EQ(named_ior("vacuum"), 1.0);
    EXPECT_FALSE(named_ior("glass"));
}

TEST(NamedMedia, ListsNameEveryEntryForErrorMessages) {
    const std::string conductors = named_conductor_list(), iors = named_ior_list();
    EXPECT_EQ(conductors.rfind("none, Ag, Al, ", 0), 0u) << conductors;
    EXPECT_NE(conductors.find(", Cu, "), std::string::npos);
    EXPECT_NE(iors.find("bk7"), std::string::npos);
    EXPECT_NE(iors.find("water ice"), std::string::npos);
}

}  // namespace named_media_test
}  // namespace
}  // namespace wp
