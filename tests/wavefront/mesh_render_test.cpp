// Meshes rendered: every OpenCL backend retraces the reference's paths
// through a scene of triangle meshes (diffuse, mirror and glass), at 1 spp,
// on every pixel, both tracing with our BVH; and on the shipped scenes the
// wavefront retraces the reference with either intersector, Embree on the
// host or our BVH.
#include <gtest/gtest.h>

#include <cstddef>
#include <span>

#include "megakernel/megakernel_renderer.h"
#include "reference/reference_renderer.h"
#include "reference/reference_scene.h"
#include "support/analytic_scenes.h"
#include "support/meshes.h"
#include "support/path_agreement.h"
#include "wavefront/intersector_choice.h"
#include "wavefront/pipeline.h"
#include "wavefront/wavefront_renderer.h"
#include "wavefront/wavefront_test_support.h"

namespace wp {
namespace {

// A diffuse cube on a plane, a glass and a mirror icosphere, under a quad light.
Scene mesh_scene(int size, int spp) {
    test::RenderBlock block{.width = size, .height = size, .spp = spp, .max_depth = 6, .rr_depth = 3, .seed = 3};
    Scene scene = test::empty_scene(block, {0.0, -0.6, -4.0}, 45.0);
    int white = test::add_material(scene, test::diffuse({0.7, 0.7, 0.7}));
    int red = test::add_material(scene, test::diffuse({0.7, 0.2, 0.1}));
    int clear = test::add_material(scene, test::glass(1.5));
    int chrome = test::add_material(scene, test::mirror({0.9, 0.9, 0.9}));
    int lamp = test::add_material(scene, test::emitter({8.0, 8.0, 8.0}));
    scene.planes.push_back({{0.0, -1.5, 0.0}, {0.0, 1.0, 0.0}, white});
    scene.meshes.push_back(test::transformed(test::unit_cube(red), 0.8, {-1.4, -1.5, -4.5}));
    scene.meshes.push_back(test::transformed(test::icosphere(2, clear), 0.5, {0.2, -1.0, -3.6}));
    scene.meshes.push_back(test::transformed(test::icosphere(1, chrome), 0.45, {1.2, -1.05, -4.6}));
    scene.quads.push_back({{-0.75, 1.5, -4.75}, {1.5, 0.0, 0.0}, {0.0, 0.0, 1.5}, lamp});
    build_light_table(scene);
    return scene;
}

// The wavefront tracing with `intersector` (the library's default is the
// device's, which on a CPU is Embree for meshes).
WavefrontOptions traced_by(Intersector intersector, std::size_t wavefront = 0, unsigned lanes = 0) {
    WavefrontOptions options;
    options.intersector = intersector;
    options.wavefront = wavefront;
    options.lanes = lanes;
    return options;
}
const WavefrontOptions kBvh = traced_by(Intersector::Bvh);

TEST(MeshRender, WavefrontRetracesTheReferencePathForPath) {
    Scene scene = mesh_scene(48, 1);
    ASSERT_TRUE(scene.features().meshes);
    test::expect_path_for_path_agreement(render_wavefront(scene, kBvh, {}),
                                         render_reference(scene, ReferenceOptions{2, false}), "wavefront, meshes");
}

// With its default for meshes, one lane, and with 16 (--lanes 16): the
// megakernel traverses the BVH as the wavefront's stages do
// (device/bvh_lanes.h with several lanes).
TEST(MeshRender, MegakernelRetracesTheReferencePathForPath) {
    Scene scene = mesh_scene(48, 1);
    RenderResult reference = render_reference(scene, ReferenceOptions{2, false});
    for (unsigned lanes : {0u, 16u}) {
        MegakernelOptions options;
        options.lanes = lanes;
        MegakernelReport report;
        RenderResult megakernel = render_megakernel(scene, options, {}, &report);
        EXPECT_EQ(report.lanes, lanes == 0 ? 1u : lanes) << "meshes default to one lane";
        test::expect_path_for_path_agreement(megakernel, reference,
                                             "megakernel, meshes, lanes " + std::to_string(lanes));
    }
}

// The same scene lit by an emissive mesh (a triangulated, two-sided lamp)
// instead of the quad: next-event estimation samples the mesh's triangles.
TEST(MeshRender, MeshLightRetracesTheReferencePathForPath) {
    Scene scene = mesh_scene(48, 1);
    int lamp = scene.quads.back().material;
    scene.quads.pop_back();
    scene.materials[lamp].two_sided = true;
    scene.meshes.push_back(test::transformed(test::icosphere(1, lamp), 0.3, {0.0, 0.9, -4.2}));
    build_light_table(scene);
    ASSERT_TRUE(scene.features().mesh_lights);
    RenderResult reference = render_reference(scene, ReferenceOptions{2, false});
    EXPECT_GT(reference.stats.shadow_rays, 0u);
    test::expect_path_for_path_agreement(render_wavefront(scene, kBvh, {}), reference, "wavefront, mesh light");
    test::expect_path_for_path_agreement(render_megakernel(scene, {}, {}), reference, "megakernel, mesh light");
}

// The same scene with smooth icospheres (vertex normals: the unit sphere's),
// so that BSDFs and light samples use shading normals.
TEST(MeshRender, ShadingNormalsRetraceTheReferencePathForPath) {
    Scene scene = mesh_scene(48, 1);
    for (Mesh& mesh : scene.meshes) {
        if (mesh.file != "icosphere (test)") continue;
        glm::dvec3 center(0.0);
        for (const glm::dvec3& p : mesh.positions) center += p / double(mesh.positions.size());
        for (const glm::dvec3& p : mesh.positions) mesh.normals.push_back(glm::normalize(p - center));
    }
    ASSERT_TRUE(scene.features().shading_normals);
    RenderResult reference = render_reference(scene, ReferenceOptions{2, false});
    test::expect_path_for_path_agreement(render_wavefront(scene, kBvh, {}), reference, "wavefront, shading normals");
    test::expect_path_for_path_agreement(render_megakernel(scene, {}, {}), reference, "megakernel, shading normals");
}

// Meshes with 4, 8 and 16 lanes, the BVH traversed in each lane
// (device/bvh_lanes.h): the reference's paths and the same image as one lane,
// in the wavefront and the megakernel. Three lights of 20, 80 and 2 triangles
// (two meshes and the quad), so that the lanes of one work item search
// triangle CDFs of different lengths.
TEST(MeshRender, EveryLaneCountRetracesTheReferenceAsOneLaneDoes) {
    Scene scene = mesh_scene(32, 1);
    int lamp = scene.quads.back().material;
    scene.materials[lamp].two_sided = true;
    scene.meshes.push_back(test::transformed(test::icosphere(0, lamp), 0.2, {-0.8, 0.9, -4.2}));
    scene.meshes.push_back(test::transformed(test::icosphere(1, lamp), 0.25, {0.8, 0.9, -4.0}));
    build_light_table(scene);
    ASSERT_TRUE(scene.features().mesh_lights);
    // queue lengths rarely a multiple of the lanes: partly filled last lanes
    WavefrontOptions options = traced_by(Intersector::Bvh, 320);
    options.lanes = 1;
    RenderResult one = render_wavefront(scene, options, {});
    EXPECT_GT(one.stats.shadow_rays, 0u);
    for (unsigned lanes : {4u, 8u, 16u}) {
        options.lanes = lanes;
        RenderResult many = render_wavefront(scene, options, {});
        if (lanes == 16)
            test::expect_path_for_path_agreement(many, render_reference(scene, ReferenceOptions{2, false}),
                                                 "wavefront, 16 lanes, three mesh and quad lights");
        EXPECT_EQ(one.image.rgb, many.image.rgb) << "wavefront, " << lanes << " lanes";
        EXPECT_EQ(one.stats.extension_rays, many.stats.extension_rays) << "wavefront, " << lanes << " lanes";
        EXPECT_EQ(one.stats.shadow_rays, many.stats.shadow_rays) << "wavefront, " << lanes << " lanes";
    }
    MegakernelOptions megakernel_options;  // its other lane counts: MegakernelRetracesTheReferencePathForPath
    megakernel_options.lanes = 4;
    EXPECT_EQ(render_megakernel(scene, megakernel_options, {}).image.rgb, one.image.rgb) << "megakernel, 4 lanes";
}

// A parallelogram corner + u edge1 + v edge2 as a two-triangle mesh, its
// front on the side of edge1 x edge2.
Mesh panel(const glm::dvec3& corner, const glm::dvec3& edge1, const glm::dvec3& edge2, int material) {
    Mesh mesh;
    mesh.file = "panel (test)";
    mesh.material = material;
    mesh.positions = {corner, corner + edge1, corner + edge1 + edge2, corner + edge2};
    mesh.triangles = {{0, 1, 2}, {0, 2, 3}};
    return mesh;
}

// Two mesh lights and a plain mesh, placed so that a triangle of the first
// light has, in the BVH's order, the index at which the second light's
// triangles start among the light triangles: the light a hit belongs to is
// its mesh's alone, whatever its index. The kernels once also took a light
// whose shape word equalled the hit's (kernels/device/path_vertex.h before
// light_key), which weighted that triangle's emission by the other light's
// density: 207 of these 2304 pixels then disagreed with the reference.
TEST(MeshRender, TwoMeshLightsRetraceTheReferencePathForPath) {
    test::RenderBlock block{.width = 48, .height = 48, .spp = 1, .max_depth = 3, .rr_depth = 3, .seed = 5};
    Scene scene = test::empty_scene(block, {0.0, -0.5, -3.0}, 60.0);
    int white = test::add_material(scene, test::diffuse({0.7, 0.7, 0.7}));
    int dim = test::add_material(scene, test::emitter({2.0, 2.0, 2.0}));
    int bright = test::add_material(scene, test::emitter({20.0, 10.0, 5.0}));
    scene.planes.push_back({{0.0, -1.0, 0.0}, {0.0, 1.0, 0.0}, white});
    scene.meshes.push_back(panel({-2.5, -1.0, -5.0}, {5.0, 0.0, 0.0}, {0.0, 3.0, 0.0}, white));  // back wall
    scene.meshes.push_back(panel({-2.0, 1.0, -4.5}, {2.5, 0.0, 0.0}, {0.0, 0.0, 3.0}, dim));     // faces down
    scene.meshes.push_back(panel({-2.6, 0.9, -3.0}, {0.4, 0.0, 0.0}, {0.0, 0.0, 0.4}, bright));
    build_light_table(scene);
    reference::ReferenceScene<float> ref(scene);
    ASSERT_EQ(ref.lights.size(), 2u);
    const std::uint32_t second_light_start = ref.lights[1].first_triangle;
    ASSERT_LT(second_light_start, ref.triangles.size());
    ASSERT_EQ(ref.triangles[second_light_start].mesh, 1u) << "the first light's mesh holds that triangle index";
    RenderResult reference = render_reference(scene, ReferenceOptions{2, false});
    test::expect_path_for_path_agreement(render_wavefront(scene, kBvh, {}), reference, "wavefront, two mesh lights");
    test::expect_path_for_path_agreement(render_megakernel(scene, {}, {}), reference, "megakernel, two mesh lights");
}

// ---- Embree on the host (--intersector embree, wavefront/host_trace.h) ----

// A shipped scene at size x size pixels and `spp` samples per pixel.
Scene shipped(const std::string& name, int size, int spp) {
    Scene scene = test::scene_from_file("scenes/" + name + ".json");
    scene.camera.width = scene.camera.height = size;
    scene.render.spp = spp;
    return scene;
}

// The wavefront and the reference asking the same intersector: with Embree,
// every ray, near ties included, meets the same shape at the same distance
// (the tie rule is a function of the ray); with the BVH, both traverse the
// same tree. The shipped scenes, with meshes and without.
TEST(MeshRender, WavefrontRetracesTheReferenceWithTheSameIntersectorOnTheShippedScenes) {
    for (const char* name : {"cornell", "cornell_mesh", "bunny", "room"}) {
        Scene scene = shipped(name, 48, 1);
        for (Intersector intersector : {Intersector::Embree, Intersector::Bvh}) {
            std::string label = std::string(name) + ", " + intersector_name(intersector);
            WavefrontReport report;
            RenderResult wavefront = render_wavefront(scene, traced_by(intersector), {}, &report);
            EXPECT_EQ(report.intersector, intersector) << label;
            EXPECT_EQ(report.features.find("host-traced") != std::string::npos, intersector == Intersector::Embree)
                << label;
            // Where the host traces, no BVH is built: the kernels only shade its hits.
            if (!scene.meshes.empty()) {
                EXPECT_EQ(report.meshes.find("no BVH") != std::string::npos, intersector == Intersector::Embree)
                    << label << ": " << report.meshes;
            }
            EXPECT_GT(wavefront.stats.shadow_rays, 0u) << label;
            ReferenceOptions reference{2, false};
            reference.intersector = intersector;
            test::expect_path_for_path_agreement(wavefront, render_reference(scene, reference),
                                                 "wavefront and reference, " + label);
        }
    }
}

// Where the host traces, the device's triangle buffer is the host tracer's
// triangles in place (CL_MEM_USE_HOST_PTR): on a CPU device, one copy.
TEST(MeshRender, HostTracedTrianglesAreOneCopy) {
    Scene scene = shipped("cornell_mesh", 8, 1);
    FeatureSet features = scene.features();
    features.host_traced = features.shadow_stage = true;
    Pipeline pipeline(scene, choose_device(""), 64, 64, features);
    ASSERT_NE(pipeline.host_trace(), nullptr);
    const std::span<const std::byte> host = pipeline.host_trace()->intersector().triangle_bytes();
    const cl::Buffer& device = pipeline.device_scene().triangles();
    EXPECT_NE(device.getInfo<CL_MEM_FLAGS>() & CL_MEM_USE_HOST_PTR, 0u);
    EXPECT_EQ(device.getInfo<CL_MEM_HOST_PTR>(), static_cast<const void*>(host.data()));
    EXPECT_EQ(device.getInfo<CL_MEM_SIZE>(), host.size());
    EXPECT_EQ(host.size(), sizeof(SharedMath<float>::MeshTriangle) * pipeline.device_scene().meshes().triangles);
}

// The hits the host writes are a function of each ray alone: the same image,
// to the bit, for any wavefront size (queue lengths rarely a multiple of the
// lanes, passes cut elsewhere) and 1, 4, 8 or 16 lanes.
TEST(MeshRender, EmbreeImagesAreBitIdenticalAcrossWavefrontSizesAndLanes) {
    Scene scene = shipped("cornell_mesh", 32, 2);
    RenderResult first = render_wavefront(scene, traced_by(Intersector::Embree, 0, 8), {});
    EXPECT_GT(first.stats.shadow_rays, 0u);
    for (auto [wavefront, lanes] : {std::pair{320u, 1u}, {320u, 4u}, {320u, 8u}, {320u, 16u}, {1088u, 1u}, {0u, 1u}}) {
        RenderResult other = render_wavefront(scene, traced_by(Intersector::Embree, wavefront, lanes), {});
        std::string label = "wavefront " + std::to_string(wavefront) + ", lanes " + std::to_string(lanes);
        EXPECT_EQ(other.image.rgb, first.image.rgb) << label;
        EXPECT_EQ(other.stats.extension_rays, first.stats.extension_rays) << label;
        EXPECT_EQ(other.stats.shadow_rays, first.stats.shadow_rays) << label;
    }
}

}  // namespace
}  // namespace wp
