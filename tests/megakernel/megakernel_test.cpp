// The megakernel baseline against the reference and the wavefront: the same
// estimator, random numbers and per-vertex code, so the same paths.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include "megakernel/megakernel_renderer.h"
#include "opencl/device.h"
#include "reference/reference_renderer.h"
#include "support/image_statistics.h"
#include "support/path_agreement.h"
#include "wavefront/wavefront_renderer.h"
#include "wavefront/wavefront_test_support.h"

namespace wp {
namespace {

MegakernelOptions with_lanes(unsigned lanes) {
    MegakernelOptions options;
    options.lanes = lanes;
    return options;
}

// 45 x 45 pixels: 2025 work items, so the last work item has one active
// lane with 4 and 8 lanes and 9 with 16, which must not disturb the others.
TEST(Megakernel, OneSampleMatchesReferencePathForPathWithEveryLaneCount) {
    Scene scene = test::small_room(45, 1);
    RenderResult reference = render_reference(scene, ReferenceOptions{2, false});
    for (unsigned lanes : {1u, 4u, 8u, 16u}) {
        MegakernelReport report;
        RenderResult megakernel = render_megakernel(scene, with_lanes(lanes), {}, &report);
        EXPECT_EQ(report.lanes, lanes);
        test::expect_path_for_path_agreement(megakernel, reference, "megakernel, lanes " + std::to_string(lanes));
    }
}

// Without meshes on a CPU: as many lanes as the preferred float vector
// holds where that is 16 (AVX-512), else 8 (bench/results/lanes_megakernel.md).
TEST(Megakernel, UsesTheVectorWidthsLanesOnCpus) {
    const DeviceInfo device = choose_device("");
    ASSERT_EQ(device.type, "CPU") << "PoCL's devices are CPUs";
    MegakernelReport report;
    render_megakernel(test::small_room(8, 1), {}, {}, &report);
    EXPECT_EQ(report.lanes, device.preferred_float_vector_width >= 16 ? 16u : 8u)
        << "preferred float vector width " << device.preferred_float_vector_width;
}

// Both OpenCL backends run the same float code per vertex and accumulate each
// pixel's samples in sample order, so their images are bit-identical, with
// any number of lanes.
TEST(Megakernel, BitIdenticalToWavefront) {
    Scene scene = test::small_room(40, 3);
    RenderResult wavefront = render_wavefront(scene, {}, {});
    for (unsigned lanes : {1u, 4u, 8u, 16u}) {
        RenderResult megakernel = render_megakernel(scene, with_lanes(lanes), {});
        EXPECT_EQ(megakernel.image.rgb, wavefront.image.rgb) << "lanes " << lanes;
        EXPECT_EQ(megakernel.stats.extension_rays, wavefront.stats.extension_rays) << "lanes " << lanes;
        EXPECT_EQ(megakernel.stats.shadow_rays, wavefront.stats.shadow_rays) << "lanes " << lanes;
    }
}

// The materials with a delta lobe beside a diffuse one (plastic, nonlinear
// or not) and rough plastics (their coat's tables in device memory, GGX and
// Beckmann) render the same bits on the three backends: the float
// reference reads the host's constants rounded as the kernels do.
TEST(Megakernel, PlasticsBitIdenticalToWavefrontAndReference) {
    Scene scene = load_scene(WAVEPATH_SOURCE_DIR "/scenes/test/oracle_plastics.json");
    scene.render.spp = 2;
    ASSERT_TRUE(scene.features().plastic && scene.features().rough_plastic);
    RenderResult wavefront = render_wavefront(scene, {}, {});
    RenderResult reference = render_reference(scene, ReferenceOptions{2, false});
    EXPECT_EQ(reference.image.rgb, wavefront.image.rgb);
    for (unsigned lanes : {1u, 16u}) {
        RenderResult megakernel = render_megakernel(scene, with_lanes(lanes), {});
        EXPECT_EQ(megakernel.image.rgb, wavefront.image.rgb) << "lanes " << lanes;
        EXPECT_EQ(megakernel.stats.shadow_rays, wavefront.stats.shadow_rays) << "lanes " << lanes;
    }
}

// Textures (kernels/shared/texture.h): a checkerboard and bitmaps of each
// filter and wrap mode on quads, a sphere and a PLY mesh with uvs, looked up
// by the same shared code in every backend, so bit-identical images,
// whatever the lanes and the wavefront's size; in SPPM too, whose photons and
// visible points read the same albedo.
TEST(Megakernel, TexturesBitIdenticalInEveryBackend) {
    Scene scene = load_scene(WAVEPATH_SOURCE_DIR "/scenes/test/oracle_textures.json");
    ASSERT_TRUE(scene.features().textures);
    scene.render.spp = 2;
    const RenderResult reference = render_reference(scene, ReferenceOptions{2, false});
    for (unsigned lanes : {1u, 16u}) {
        EXPECT_EQ(render_megakernel(scene, with_lanes(lanes), {}).image.rgb, reference.image.rgb) << "lanes " << lanes;
        WavefrontOptions options;
        options.lanes = lanes;
        options.wavefront = 777;
        WavefrontReport report;
        EXPECT_EQ(render_wavefront(scene, options, {}, &report).image.rgb, reference.image.rgb) << "lanes " << lanes;
        // --explain's line: 6 descriptors of 72 bytes, 5 bitmaps of 8 x 8 texels, the panel's 2 triangles' uvs
        EXPECT_NE(report.explain().find(
                      "textures: 6 textures (5 bitmaps, 1 checkerboard), 320 texels, 5 KiB of device memory\n"),
                  std::string::npos)
            << report.explain();
    }
    scene.render.integrator = Integrator::Sppm;
    scene.render.spp = 1;
    scene.render.sppm.photons = 4096;
    EXPECT_EQ(render_wavefront(scene, {}, {}).image.rgb, render_reference(scene, ReferenceOptions{2, false}).image.rgb);
}

// Textured plastics' diffuse_reflectance and specular_reflectance and
// conductors' specular_reflectance (smooth and rough), read through the one
// shared colour_parameter in every backend: bit-identical images; in SPPM
// too, whose glossy visible points keep their uv for the photons' lookups.
TEST(Megakernel, TexturedMaterialsBitIdenticalInEveryBackend) {
    Scene scene = load_scene(WAVEPATH_SOURCE_DIR "/scenes/test/oracle_textured_materials.json");
    ASSERT_TRUE(scene.features().textures);
    scene.render.spp = 2;
    const RenderResult reference = render_reference(scene, ReferenceOptions{2, false});
    EXPECT_EQ(render_megakernel(scene, with_lanes(16), {}).image.rgb, reference.image.rgb);
    WavefrontOptions options;
    options.lanes = 4;
    options.wavefront = 777;
    EXPECT_EQ(render_wavefront(scene, options, {}).image.rgb, reference.image.rgb);
    scene.render.integrator = Integrator::Sppm;
    scene.render.spp = 1;
    scene.render.sppm.photons = 4096;
    EXPECT_EQ(render_wavefront(scene, {}, {}).image.rgb, render_reference(scene, ReferenceOptions{2, false}).image.rgb);
}

// A scene renders bit-identical images in every backend whatever the lanes
// and the wavefront's size (the adapters' scenes: normal and bump maps,
// masks); the double reference,
// whose paths part from float's only where rounding turns a decision, has
// the float image's mean within 1%.
void expect_bit_identical_in_every_backend(const Scene& scene) {
    const RenderResult reference = render_reference(scene, ReferenceOptions{2, false});
    for (unsigned lanes : {1u, 16u}) {
        EXPECT_EQ(render_megakernel(scene, with_lanes(lanes), {}).image.rgb, reference.image.rgb) << "lanes " << lanes;
        WavefrontOptions options;
        options.lanes = lanes;
        options.wavefront = 777;
        EXPECT_EQ(render_wavefront(scene, options, {}).image.rgb, reference.image.rgb) << "lanes " << lanes;
    }
    const RenderResult in_double = render_reference(scene, ReferenceOptions{2, true});
    double sum_float = 0.0, sum_double = 0.0;
    for (float c : reference.image.rgb) sum_float += c;
    for (float c : in_double.image.rgb) sum_double += c;
    EXPECT_TRUE(std::isfinite(sum_double));
    EXPECT_NEAR(sum_double, sum_float, 0.01 * sum_float);
}

// Normal maps (kernels/shared/normal_map.h) over diffuse, rough conductor,
// rough plastic and plastic materials on quads, spheres and a PLY mesh with
// uvs: the same perturbed frame and the same arrival rule in every backend.
TEST(Megakernel, NormalMapsBitIdenticalInEveryBackend) {
    Scene scene = load_scene(WAVEPATH_SOURCE_DIR "/scenes/test/oracle_normal_map.json");
    ASSERT_TRUE(scene.features().normal_map && scene.features().textures);
    scene.render.spp = 2;
    expect_bit_identical_in_every_backend(scene);
}

// Bump maps (normal_map.h' bump_mapped, texture.h' texture_gradient) over the
// same materials and shapes (a sheared to_uv among them), alone and beside a
// normal map (the floor's heights read as one: both adapters in one vector of
// lanes).
TEST(Megakernel, BumpMapsBitIdenticalInEveryBackend) {
    Scene scene = load_scene(WAVEPATH_SOURCE_DIR "/scenes/test/oracle_bump_map.json");
    ASSERT_TRUE(scene.features().bump_map && !scene.features().normal_map);
    scene.render.spp = 2;
    expect_bit_identical_in_every_backend(scene);
    auto floor_it = std::find_if(scene.materials.begin(), scene.materials.end(),
                                 [](const Material& m) { return m.name == "floor"; });
    ASSERT_NE(floor_it, scene.materials.end());
    Material& floor = *floor_it;
    std::swap(floor.texture(TexturedParameter::NormalMap), floor.texture(TexturedParameter::BumpMap));
    ASSERT_TRUE(scene.features().bump_map && scene.features().normal_map);
    expect_bit_identical_in_every_backend(scene);
}

// Anisotropic roughness (microfacet.h' microfacet_frame) on a quad, a
// sphere, a PLY mesh with uvs and, textured, on a rough dielectric sphere:
// the same dp/du and the same microfacet frames in every backend.
TEST(Megakernel, AnisotropicRoughnessBitIdenticalInEveryBackend) {
    Scene scene = load_scene(WAVEPATH_SOURCE_DIR "/scenes/test/oracle_anisotropic.json");
    ASSERT_TRUE(scene.features().anisotropic_roughness && scene.features().meshes && scene.features().spheres);
    scene.render.spp = 2;
    expect_bit_identical_in_every_backend(scene);
}

// Masks (kernels/shared/materials/mask.h) of a checkerboard, a bitmap and
// constant opacities around a diffuse, a plastic, a dielectric and a rough
// conductor: the same passes, rescaled lobe numbers and scaled densities in
// every backend; and with every mask made opaque, the image of the nested
// materials alone, bit for bit (an opacity of 1 never passes, and scales
// f, the density and the lobe number by exactly 1).
TEST(Megakernel, MasksBitIdenticalInEveryBackend) {
    Scene scene = load_scene(WAVEPATH_SOURCE_DIR "/scenes/test/oracle_mask.json");
    ASSERT_TRUE(scene.features().mask && scene.features().textures);
    scene.render.spp = 2;
    expect_bit_identical_in_every_backend(scene);

    Scene opaque = scene, unmasked = scene;
    Texture ones;
    ones.name = "ones";
    ones.type = TextureType::Checkerboard;
    ones.color0 = ones.color1 = glm::dvec3(1.0);
    opaque.textures.push_back(ones);
    for (Material& m : opaque.materials) {
        if (!m.masked()) continue;
        m.opacity = 0.0;
        m.texture(TexturedParameter::Opacity) = static_cast<int>(opaque.textures.size()) - 1;
    }
    for (Material& m : unmasked.materials) {
        m.opacity = 1.0;
        m.texture(TexturedParameter::Opacity) = kNoTexture;
    }
    ASSERT_TRUE(opaque.features().mask && !unmasked.features().mask);
    EXPECT_EQ(render_megakernel(opaque, with_lanes(16u), {}).image.rgb,
              render_megakernel(unmasked, with_lanes(16u), {}).image.rgb);
    // masks the only delta lobe (their passes): every nested material made diffuse
    Scene diffuse = scene;
    for (Material& m : diffuse.materials)
        if (m.type != MaterialType::Emitter) m.type = MaterialType::Diffuse, m.albedo = glm::dvec3(0.5);
    ASSERT_TRUE(diffuse.features().mask && diffuse.features().specular());
    ASSERT_FALSE(diffuse.features().glass || diffuse.features().plastic || diffuse.features().rough_conductor);
    expect_bit_identical_in_every_backend(diffuse);
}

// One-sided materials (Mitsuba's BSDFs outside a twosided: black from the
// back), a diffuse, a rough plastic seen from behind and a rough conductor:
// the same paths end at the same backs in every backend.
TEST(Megakernel, OneSidedMaterialsBitIdenticalInEveryBackend) {
    Scene scene = load_scene(WAVEPATH_SOURCE_DIR "/scenes/test/oracle_one_sided.json");
    ASSERT_TRUE(scene.features().one_sided);
    scene.render.spp = 2;
    expect_bit_identical_in_every_backend(scene);
}

// The environment map (kernels/shared/environment_map.h): its lookup where
// rays leave, its importance sampling and density in next-event estimation
// and MIS, the same shared code in every backend, so bit-identical images
// whatever the lanes and the wavefront's size.
TEST(Megakernel, EnvironmentMapBitIdenticalInEveryBackend) {
    Scene scene = load_scene(WAVEPATH_SOURCE_DIR "/scenes/test/oracle_envmap.json");
    ASSERT_TRUE(scene.features().environment_map);
    scene.render.spp = 2;
    const RenderResult reference = render_reference(scene, ReferenceOptions{2, false});
    for (unsigned lanes : {1u, 16u}) {
        EXPECT_EQ(render_megakernel(scene, with_lanes(lanes), {}).image.rgb, reference.image.rgb) << "lanes " << lanes;
        WavefrontOptions options;
        options.lanes = lanes;
        options.wavefront = 777;
        EXPECT_EQ(render_wavefront(scene, options, {}).image.rgb, reference.image.rgb) << "lanes " << lanes;
    }
}

// Point and spot lights (kernels/shared/direct_light.h's point_direct_light
// and spot_falloff), delta lights beside the environment: the same light
// choice, falloff and shadow ray in every backend.
TEST(Megakernel, PointAndSpotLightsBitIdenticalInEveryBackend) {
    Scene scene = load_scene(WAVEPATH_SOURCE_DIR "/scenes/test/oracle_spot.json");
    ASSERT_TRUE(scene.features().point_lights);
    scene.render.spp = 2;
    expect_bit_identical_in_every_backend(scene);
}

TEST(Megakernel, ProfileTimesItsLaunches) {
    Scene scene = test::small_room(32, 2);
    MegakernelReport report;
    MegakernelOptions options;
    options.profile = true;
    RenderResult result = render_megakernel(scene, options, {}, &report);
    // Items: the scene's samples, counted here (the renderer sets both the
    // profile's items and stats.samples from one variable of its own).
    const std::uint64_t samples = std::uint64_t(scene.camera.width) * scene.camera.height * scene.render.spp;
    EXPECT_EQ(report.profile.kernel("megakernel").items, samples);
    EXPECT_EQ(result.stats.samples, samples);
    EXPECT_EQ(report.profile.kernel("megakernel").launches, 1u);
    EXPECT_EQ(report.profile.kernel("accumulate").launches, 1u);
    EXPECT_GT(report.profile.kernel("megakernel").device_s, 0.0);
    // The launches ran inside the timed render: their device times (event
    // nanoseconds, converted) add up to less than its wall time.
    EXPECT_LE(report.profile.kernel_s(), report.profile.render_s);
}

}  // namespace
}  // namespace wp
