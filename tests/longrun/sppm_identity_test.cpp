// SPPM on the wavefront (docs/architecture.md, "Photon mapping"): the image
// is the same bits with one and eight lanes, with the paths in flight fewer
// than the pixels and the photons (so that the camera pass and the photon
// pass each take several passes and iterations of their stages), after a
// checkpoint and a resume through a film file, and as the reference renders
// it in float. Photon deposits are summed in fixed point, so the order in
// which photons reach a pixel changes nothing.
//
// Cost (2 cores): the first run compiles the sppm kernels (tens of seconds
// on PoCL, cached after); each render of 16x16 pixels, 3 iterations of
// 1,500 photons, takes well under a second.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <string>

#include "longrun/film_file.h"
#include "longrun/render_identity.h"
#include "reference/reference_renderer.h"
#include "support/temp_directory.h"
#include "wavefront/wavefront_renderer.h"
#include "wavefront/wavefront_test_support.h"

namespace wp {
namespace {

// A glass sphere on a diffuse floor under a small quad light, beside a
// mirror sphere: caustics through glass and off the mirror, with every
// material kind on the photons' paths.
Scene caustic_scene() {
    return test::scene_from_json(R"({
      "camera": {"position": [0, 1.2, 3], "look_at": [0, 0.3, 0], "up": [0, 1, 0], "fov_y": 50,
                 "width": 16, "height": 16},
      "render": {"spp": 3, "max_depth": 6, "rr_depth": 2, "seed": 5, "integrator": "sppm", "photons": 1500},
      "materials": {
        "white": {"type": "diffuse", "albedo": [0.7, 0.7, 0.7]},
        "red": {"type": "diffuse", "albedo": [0.7, 0.2, 0.1]},
        "glass": {"type": "glass", "ior": 1.5},
        "mirror": {"type": "mirror", "reflectance": [0.9, 0.9, 0.9]},
        "lamp": {"type": "emitter", "radiance": [30, 30, 30]}
      },
      "shapes": [
        {"type": "quad", "corner": [-2, 0, -2], "edge1": [0, 0, 4], "edge2": [4, 0, 0], "material": "white"},
        {"type": "quad", "corner": [-2, 0, -2], "edge1": [4, 0, 0], "edge2": [0, 3, 0], "material": "red"},
        {"type": "sphere", "center": [0.3, 0.4, 0], "radius": 0.4, "material": "glass"},
        {"type": "sphere", "center": [-0.6, 0.3, -0.4], "radius": 0.3, "material": "mirror"},
        {"type": "quad", "corner": [0, 2, 0], "edge1": [0.3, 0, 0], "edge2": [0, 0, 0.3], "material": "lamp"}
      ]
    })");
}

WavefrontOptions options_with(unsigned lanes, std::size_t wavefront) {
    WavefrontOptions options;
    options.lanes = lanes;
    options.wavefront = wavefront;
    return options;
}

class SppmWavefront : public ::testing::Test {
 protected:
    static void SetUpTestSuite() {
        scene_ = new Scene(caustic_scene());
        whole_ = new RenderResult(render_wavefront(*scene_, options_with(8, 0), {}));
    }
    static void TearDownTestSuite() {
        delete whole_;
        delete scene_;
    }
    static Scene* scene_;
    static RenderResult* whole_;  // 8 lanes, the automatic wavefront
};
Scene* SppmWavefront::scene_ = nullptr;
RenderResult* SppmWavefront::whole_ = nullptr;

TEST_F(SppmWavefront, TracesAndDepositsPhotons) {
    EXPECT_EQ(whole_->stats.photons, 3u * 1500u);
    EXPECT_GT(whole_->stats.photon_rays, whole_->stats.photons);  // some scatter
    EXPECT_GT(whole_->stats.photon_deposits, 0u);
    double sum = 0.0;
    for (float v : whole_->image.rgb) sum += v;
    EXPECT_GT(sum, 0.0);
}

// 320 slots: fewer than the 256 pixels' paths and the 1,500 photons need at
// once, with queue lengths rarely a multiple of 8.
TEST_F(SppmWavefront, SameBitsWithOneLaneAndFewSlots) {
    const RenderResult narrow = render_wavefront(*scene_, options_with(1, 320), {});
    EXPECT_EQ(narrow.image.rgb, whole_->image.rgb);
    EXPECT_EQ(narrow.stats.photon_rays, whole_->stats.photon_rays);
    EXPECT_EQ(narrow.stats.photon_deposits, whole_->stats.photon_deposits);
}

TEST_F(SppmWavefront, SameBitsAsTheReferenceInFloat) {
    const RenderResult reference = render_reference(*scene_, {.threads = 2});
    EXPECT_EQ(reference.image.rgb, whole_->image.rgb);
    EXPECT_EQ(reference.stats.photon_rays, whole_->stats.photon_rays);
    EXPECT_EQ(reference.stats.photon_deposits, whole_->stats.photon_deposits);
}

// Each pixel's radius is 0 until its first visible point sets it from the
// distance its camera path travelled (sppm_first_radius): the radii, the
// footprints and the estimate are the same bits in the reference, here after
// one iteration and after three, by which time pixels whose first path left
// by the glass sphere's reflection (no visible point) have had one since,
// and pixels that see only the sky still have none.
TEST_F(SppmWavefront, SameRadiiAndFootprintsAsTheReference) {
    const std::uint64_t pixels = 16 * 16;
    std::unique_ptr<FilmRenderer> wavefront = make_wavefront_renderer(*scene_, options_with(8, 0), {});
    std::unique_ptr<FilmRenderer> reference = make_reference_renderer(*scene_, {.threads = 2});
    auto unset = [](const PhotonEstimate& photons) {
        return std::count(photons.radius.begin(), photons.radius.end(), 0.0);
    };
    wavefront->render({0, pixels}, {});
    reference->render({0, pixels}, {});
    const PhotonEstimate first = reference->film().photons;
    EXPECT_EQ(wavefront->film().photons, first);
    wavefront->render({pixels, 3 * pixels}, {});
    reference->render({pixels, 3 * pixels}, {});
    const PhotonEstimate third = reference->film().photons;
    EXPECT_EQ(wavefront->film().photons, third);
    EXPECT_GT(unset(third), 0);
    EXPECT_LT(unset(third), unset(first));
    for (std::uint64_t p = 0; p < pixels; ++p)  // no override: two footprints, shrunk where photons came
        if (third.radius[p] > 0.0 && third.count[p] == 0.0) {
            EXPECT_EQ(third.radius[p], double(2.0f * float(third.footprint[p]))) << p;
        }
}

// Iteration 1 rendered, written to a film file, read back into a new
// renderer which renders iterations 2 and 3: each pixel's N, r and tau
// travel through the file (as doubles holding the device's floats).
TEST_F(SppmWavefront, ResumesFromAFilmFileToTheSameBits) {
    const std::uint64_t pixels = 16 * 16;
    test::TempDirectory dir("sppm_resume");
    const std::string path = dir / "first.wpfilm";
    {
        std::unique_ptr<FilmRenderer> first = make_wavefront_renderer(*scene_, options_with(8, 0), {});
        first->render({0, pixels}, {});
        write_film_file(path, {render_identity(*scene_, "opencl", {}), first->film()});
    }
    std::unique_ptr<FilmRenderer> rest = make_wavefront_renderer(*scene_, options_with(8, 0), {});
    rest->load(read_film_file(path).film);
    rest->render({pixels, 3 * pixels}, {});
    EXPECT_EQ(rest->film().image().rgb, whole_->image.rgb);
}

// A panel of two triangles whose vertex normals lean away from its
// geometric normal (0, 0, 1) by up to 25 degrees: shading normals.
constexpr const char* kLeaningPanelObj =
    "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
    "vn -0.3 -0.3 1\nvn 0.4 -0.2 1\nvn 0.3 0.3 1\nvn -0.2 0.45 1\n"
    "f 1//1 2//2 3//3\nf 1//1 3//3 4//4\n";

// Visible points and photon deposits on every non-specular material
// (docs/architecture.md, "Photon mapping"): a rough conductor, a rough
// plastic and a smooth plastic (whose coat the camera paths pass as a
// mirror where their lobe choice takes it) and a rough dielectric (photons
// reaching its visible points through it, from behind) on a diffuse floor,
// and, with shading normals, a rough dielectric and a rough conductor panel
// (`panel`, an OBJ file of kLeaningPanelObj). The same bits with one lane
// and few slots, and in the reference in float.
Scene rough_scene(const std::string& panel) {
    return test::scene_from_json(R"({
      "camera": {"position": [0, 1.2, 3], "look_at": [0, 0.3, 0], "up": [0, 1, 0], "fov_y": 50,
                 "width": 16, "height": 16},
      "render": {"spp": 3, "max_depth": 6, "rr_depth": 2, "seed": 7, "integrator": "sppm", "photons": 1500},
      "materials": {
        "white": {"type": "diffuse", "albedo": [0.7, 0.7, 0.7]},
        "gold": {"type": "roughconductor", "material": "Au", "alpha": 0.2},
        "varnish": {"type": "roughplastic", "diffuse_reflectance": [0.2, 0.4, 0.7], "alpha": 0.15},
        "gloss": {"type": "plastic", "diffuse_reflectance": [0.7, 0.2, 0.1]},
        "frosted": {"type": "roughdielectric", "int_ior": 1.5, "alpha": 0.3},
        "lamp": {"type": "emitter", "radiance": [30, 30, 30]}
      },
      "shapes": [
        {"type": "quad", "corner": [-2, 0, -2], "edge1": [0, 0, 4], "edge2": [4, 0, 0], "material": "white"},
        {"type": "quad", "corner": [-2, 0, -2], "edge1": [4, 0, 0], "edge2": [0, 3, 0], "material": "gloss"},
        {"type": "sphere", "center": [0.5, 0.35, 0.2], "radius": 0.35, "material": "frosted"},
        {"type": "sphere", "center": [-0.6, 0.3, -0.4], "radius": 0.3, "material": "gold"},
        {"type": "sphere", "center": [-0.3, 0.25, 0.6], "radius": 0.25, "material": "varnish"},
        {"type": "mesh", "file": ")" +
                                 panel + R"(", "material": "frosted",
         "transform": {"scale": 0.6, "rotate": [1, 0, 0, -30], "translate": [0.2, 0.2, 0.9]}},
        {"type": "mesh", "file": ")" +
                                 panel + R"(", "material": "gold",
         "transform": {"scale": 0.5, "rotate": [0, 1, 0, 40], "translate": [-1.2, 0.1, 0.3]}},
        {"type": "quad", "corner": [0, 2, 0], "edge1": [0.3, 0, 0], "edge2": [0, 0, 0.3], "material": "lamp"}
      ]
    })");
}

TEST(SppmWavefrontRough, SameBitsWithOneLaneAndFewSlotsAndAsTheReferenceInFloat) {
    test::TempDirectory dir("sppm_rough");
    const std::string panel = dir / "panel.obj";
    std::ofstream(panel) << kLeaningPanelObj;
    const Scene scene = rough_scene(panel);
    ASSERT_TRUE(scene.features().shading_normals);
    const RenderResult wide = render_wavefront(scene, options_with(8, 0), {});
    EXPECT_GT(wide.stats.photon_deposits, 0u);
    const RenderResult narrow = render_wavefront(scene, options_with(1, 320), {});
    EXPECT_EQ(narrow.image.rgb, wide.image.rgb);
    EXPECT_EQ(narrow.stats.photon_deposits, wide.stats.photon_deposits);
    const RenderResult reference = render_reference(scene, {.threads = 2});
    EXPECT_EQ(reference.image.rgb, wide.image.rgb);
    EXPECT_EQ(reference.stats.photon_rays, wide.stats.photon_rays);
    EXPECT_EQ(reference.stats.photon_deposits, wide.stats.photon_deposits);
}

}  // namespace
}  // namespace wp
