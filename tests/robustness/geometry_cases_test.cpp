// Geometry at the extremes (issue 5), on both backends: the smallpt box of
// radius-1e5 sphere walls against the same box of quads, no light leaking
// along the room's edges, the camera inside a sphere and on a surface, and
// rays that exactly graze a plane or a sphere's silhouette.
#include <gtest/gtest.h>

#include <glm/trigonometric.hpp>
#include <glm/vec2.hpp>
#include <string>
#include <vector>

#include "robustness_support.h"
#include "support/analytic_scenes.h"

namespace wp::test {
namespace {

class Geometry : public ::testing::TestWithParam<Backend> {};

// A closed box of 100 x 80 x 170 times `size`, lit by a small sphere light,
// the camera inside near the front wall; its six walls either quads or, as
// in smallpt, spheres of radius 1e5 (whatever the box's size) whose surfaces
// touch the same planes at the walls' middles (they bulge by at most
// (85 size)^2 / 2e5 over a wall: 4e-4 of the box at size 1, 1.4e-5 units at
// size 0.02, the 2-unit room where a radius-1e5 wall's points are known only
// to ulp(1e5) = 0.008 in float).
std::string box_scene(bool sphere_walls, double size) {
    const double width = 100 * size, height = 80 * size, depth = 170 * size, wall_radius = 1e5;
    using nlohmann::json;
    auto vec = [](double x, double y, double z) { return json::array({x, y, z}); };
    auto quad = [&](json corner, json edge1, json edge2, const char* material) {
        return json{{"type", "quad"}, {"corner", corner}, {"edge1", edge1}, {"edge2", edge2}, {"material", material}};
    };
    auto sphere = [&](json center, double radius, const char* material) {
        return json{{"type", "sphere"}, {"center", center}, {"radius", radius}, {"material", material}};
    };
    json shapes = json::array({sphere(vec(width / 2, 70 * size, depth / 2), 5 * size, "lamp")});
    if (sphere_walls) {
        const double r = wall_radius;
        for (const json& wall : {sphere(vec(-r, height / 2, depth / 2), r, "red"),
                                 sphere(vec(width + r, height / 2, depth / 2), r, "blue"),
                                 sphere(vec(width / 2, -r, depth / 2), r, "white"),
                                 sphere(vec(width / 2, height + r, depth / 2), r, "white"),
                                 sphere(vec(width / 2, height / 2, -r), r, "white"),
                                 sphere(vec(width / 2, height / 2, depth + r), r, "white")})
            shapes.push_back(wall);
    } else {
        for (const json& wall : {quad(vec(0, 0, 0), vec(0, height, 0), vec(0, 0, depth), "red"),
                                 quad(vec(width, 0, 0), vec(0, 0, depth), vec(0, height, 0), "blue"),
                                 quad(vec(0, 0, 0), vec(0, 0, depth), vec(width, 0, 0), "white"),
                                 quad(vec(0, height, 0), vec(width, 0, 0), vec(0, 0, depth), "white"),
                                 quad(vec(0, 0, 0), vec(width, 0, 0), vec(0, height, 0), "white"),
                                 quad(vec(0, 0, depth), vec(0, height, 0), vec(width, 0, 0), "white")})
            shapes.push_back(wall);
    }
    json scene = {{"camera",
                   {{"position", vec(width / 2, 42 * size, 165 * size)},
                    {"look_at", vec(width / 2, 38 * size, 0)},
                    {"fov_y", 55},
                    {"width", 32},
                    {"height", 32}}},
                  {"render", {{"spp", 64}, {"max_depth", 6}, {"rr_depth", 3}, {"seed", 1}}},
                  {"materials",
                   {{"white", {{"type", "diffuse"}, {"albedo", vec(0.75, 0.75, 0.75)}}},
                    {"red", {{"type", "diffuse"}, {"albedo", vec(0.75, 0.25, 0.25)}}},
                    {"blue", {{"type", "diffuse"}, {"albedo", vec(0.25, 0.25, 0.75)}}},
                    {"lamp", {{"type", "emitter"}, {"radiance", vec(400, 400, 400)}}}}},
                  {"shapes", shapes}};
    return scene.dump();
}

// The sphere-walled box against the quad box, rendered with the same seed:
// with common random numbers the two renders' paths stay alike, so their
// per-pixel differences spread far less than independent renders' would,
// while each pixel's difference still has mean zero if the boxes render
// alike and pixels stay independent of one another (each has its own
// random numbers). Every 4x4 region and the whole image within
// kSigmaTolerance standard errors of that spread: a correct pair fails one of
// the 17 comparisons with probability below 1.2e-4.
// `float_bias` is an allowance, relative to the image, for float's own
// precision where it is known to fall short (the whole image only, and for
// the float backends only).
void expect_sphere_walls_match_quad_walls(Backend backend, double size, const std::string& figure,
                                          double float_bias = 0.0) {
    RenderResult quads = render_on(backend, parse_scene(box_scene(false, size), "quad box"));
    RenderResult spheres = render_on(backend, parse_scene(box_scene(true, size), "smallpt box"));
    EXPECT_EQ(spheres.stats.nonfinite, 0u);
    RegionComparison c = compare_regions(spheres.image, quads.image, 4);
    report_figure(figure, backend, describe(c));
    EXPECT_LE(c.worst_z, kSigmaTolerance);
    double relative_standard_error = c.whole_z != 0.0 ? std::fabs(c.whole_relative / c.whole_z) : 0.0;
    double allowance = backend == Backend::Reference ? 0.0 : float_bias;  // the reference runs in double
    EXPECT_LE(std::fabs(c.whole_relative), kSigmaTolerance * relative_standard_error + allowance)
        << "whole image z " << c.whole_z;
}

TEST_P(Geometry, SmallptSphereWallsMatchQuadWalls) {
    expect_sphere_walls_match_quad_walls(GetParam(), 1.0, "smallpt sphere walls vs quad walls (same seed)");
}

// The same box 2 units wide: the walls' radius is now 5e4 times the room.
// Measured: double +0.14% (z 1.4) for the whole image; float +1.8% (z 4.9;
// +0.6%, z 3.8 without MIS, whose bounce weights take the light's density
// from the offset ray origin), float's own precision at radius 1e5
// (docs/robustness.md), allowed for up to 2%; the old bound, gamma(16) (|center| + r), fails it
// with -10% (z -5.0) on both backends.
// So float's whole image may be off by 2% plus 4.5 standard errors (0.37%
// each at 64 spp: 3.7% in all), double's by the 4.5 standard errors alone
// (1.7%). More samples would shrink only the standard-error part: float's
// +1.8% is its precision at radius 1e5, not noise, and the allowance states
// it (at 4x the samples, 4 s more, float's bound would be 2.8%, not 3.7%).
// What the test catches on float is a bias about twice today's; on double,
// one of 1.7%.
TEST_P(Geometry, SmallptSphereWallsMatchQuadWallsInAUnitRoom) {
    expect_sphere_walls_match_quad_walls(GetParam(), 0.02,
                                         "smallpt sphere walls vs quad walls, 2-unit room (same seed)", 0.02);
}

// Pixel position of a camera-relative point.
glm::dvec2 project(const Camera& camera, const glm::dvec3& point) {
    glm::dvec3 forward = glm::normalize(camera.look_at - camera.position);
    glm::dvec3 right = glm::normalize(glm::cross(forward, camera.up));
    glm::dvec3 up = glm::cross(right, forward);
    glm::dvec3 d = point - camera.position;
    double t = std::tan(glm::radians(camera.fov_y_degrees) / 2.0), aspect = double(camera.width) / camera.height;
    double sx = glm::dot(d, right) / glm::dot(d, forward) / (t * aspect),
           sy = glm::dot(d, up) / glm::dot(d, forward) / t;
    return {(sx + 1.0) / 2.0 * camera.width, (1.0 - sy) / 2.0 * camera.height};
}

// Light leaking through an edge shows as a bright line along it. The room
// is closed, so its outside (the background) must never be seen; it is made
// 100 times as bright as the lamp to turn any leak into a bright line. For
// the four edges of the room's back wall (roof, floor, left and right walls
// meeting it), each pixel the edge crosses is compared with the mean of the
// pixels two away on either side (across the edge): over an edge, the mean
// of (edge pixel - neighbour mean) must not exceed kSigmaTolerance standard
// errors (one-sided: corners are darker than their surroundings, never
// brighter). The room translated by 1e+5 too, where float precision is
// tightest. And no sample anywhere may see the outside: no pixel reaches
// the outside's radiance / spp.
constexpr double kOutside = 1400.0;
TEST_P(Geometry, NoLightLeaksAlongTheRoomsEdges) {
    for (double translation : {0.0, 1e5}) {
        SCOPED_TRACE("translation " + std::to_string(translation));
        Scene scene = transformed_room(1.0, glm::dvec3(translation), 48, 64, 5, [](nlohmann::json& room) {
            room["background"] = {kOutside, kOutside, kOutside};
        });
        RenderResult result = render_on(GetParam(), scene);
        EXPECT_EQ(result.stats.nonfinite, 0u);
        // The back wall's corners, room coordinates, camera-relative.
        glm::dvec3 eye(0, 2.4, 7);
        glm::dvec3 corners[4] = {{-2.5, 0, -3}, {2.5, 0, -3}, {2.5, 5, -3}, {-2.5, 5, -3}};
        for (int e = 0; e < 4; ++e) {
            glm::dvec3 a = corners[e] - eye, b = corners[(e + 1) % 4] - eye;
            glm::dvec2 pa = project(scene.camera, a), pb = project(scene.camera, b);
            bool horizontal = std::fabs(pb.x - pa.x) > std::fabs(pb.y - pa.y);
            RunningMean excess, level;
            int last_x = -1, last_y = -1;
            for (double s = 0.1; s <= 0.9; s += 0.002) {
                glm::dvec2 p = project(scene.camera, a + s * (b - a));
                int x = int(std::floor(p.x)), y = int(std::floor(p.y));
                if ((x == last_x && y == last_y) || x < 2 || y < 2 || x >= 46 || y >= 46) continue;
                last_x = x, last_y = y;
                int dx = horizontal ? 0 : 2, dy = horizontal ? 2 : 0;
                double neighbours =
                    0.5 * (pixel_sum(result.image, x - dx, y - dy) + pixel_sum(result.image, x + dx, y + dy));
                excess.add(pixel_sum(result.image, x, y) - neighbours);
                level.add(neighbours);
            }
            ASSERT_GT(excess.count(), 10u) << "edge " << e;
            double z = excess.mean() / excess.standard_error();
            report_figure("room edge " + std::to_string(e) + (translation > 0 ? " (translated 1e+5)" : ""), GetParam(),
                          format("edge pixels minus neighbours: %+.3f of the neighbour level (z %+.2f)",
                                 excess.mean() / level.mean(), z));
            EXPECT_LE(z, kSigmaTolerance) << "edge " << e;
        }
        float brightest = *std::max_element(result.image.rgb.begin(), result.image.rgb.end());
        report_figure(std::string("room with a bright outside") + (translation > 0 ? " (translated 1e+5)" : ""),
                      GetParam(),
                      format("brightest pixel %.2f, one leaked sample would add %.2f", brightest, kOutside / 64));
        EXPECT_LT(brightest, kOutside / 64);
    }
}

// The camera inside a closed, two-sided emissive diffuse sphere (albedo 0.9)
// and, second, on such a sphere's surface, its rays entering the sphere (the
// camera point is exactly on it: a hit at t = 0 must not count). Next-event
// estimation from a sphere's inside is exact per vertex, so every pixel is
// the truncated series Le (1 - rho^(d+1)) / (1 - rho) to float rounding.
TEST_P(Geometry, CameraInsideASphereAndOnItsSurface) {
    RenderBlock block{16, 16, 4, 8};
    Scene inside = inside_emissive_sphere(block, glm::dvec3(0.9), glm::dvec3(1.0));
    Scene on_surface = parse_scene(R"({
      "camera": {"position": [0, 2, 5], "look_at": [0.2, 1.9, 3], "fov_y": 60, "width": 16, "height": 16},
      "render": {"spp": 4, "max_depth": 8, "rr_depth": 1000000, "seed": 1},
      "materials": {"glow": {"type": "diffuse", "albedo": [0.9, 0.9, 0.9], "emission": [1, 1, 1], "two_sided": true}},
      "shapes": [{"type": "sphere", "center": [0, 2, 4], "radius": 1, "material": "glow"}]})",
                                   "camera on sphere");
    double expected = inside_emissive_sphere_radiance(0.9, 1.0, 8);
    for (const Scene* scene : {&inside, &on_surface}) {
        RenderResult result = render_on(GetParam(), *scene);
        double worst = 0.0;
        for (float v : result.image.rgb) worst = std::max(worst, std::fabs(v - expected) / expected);
        report_figure(scene == &inside ? "camera inside a sphere" : "camera on a sphere's surface", GetParam(),
                      format("largest pixel deviation from Le(1-rho^9)/(1-rho): %.2e", worst));
        EXPECT_LE(worst, 1e-5);
        EXPECT_EQ(result.stats.nonfinite, 0u);
    }
}

// The camera exactly on a diffuse plane (after the loader's rebase the
// plane passes through the origin): no ray meets the plane at t = 0, so
// every pixel shows the background, on both sides of the horizon.
TEST_P(Geometry, CameraOnAPlaneSeesPastIt) {
    Scene scene = parse_scene(R"({
      "camera": {"position": [3, 1, 2], "look_at": [3, 0.5, 1], "fov_y": 60, "width": 16, "height": 16},
      "render": {"spp": 2, "max_depth": 4, "seed": 1},
      "background": [0.25, 0.5, 1],
      "materials": {"white": {"type": "diffuse", "albedo": [0.5, 0.5, 0.5]}},
      "shapes": [{"type": "plane", "point": [5, 1, 7], "normal": [0, 1, 0], "material": "white"}]})",
                              "camera on plane");
    RenderResult result = render_on(GetParam(), scene);
    int off = 0;
    for (int y = 0; y < 16; ++y)
        for (int x = 0; x < 16; ++x)
            for (int c = 0; c < 3; ++c) off += pixel_channel(result.image, x, y, c) != float(scene.background[c]);
    report_figure("camera on a plane", GetParam(), format("pixels not equal to the background: %.0f of 256", off));
    EXPECT_EQ(off, 0);
}

// At 1 spp a pixel is one sample. Under a uniform background of 1 and no
// other lights, without next-event estimation (whose light samples of the
// background would vary), a sample that meets a convex surface of albedo (or
// reflectance) 0.5 scatters once into the sky and carries exactly 0.5; one
// that misses carries 1; a ray that hits its own surface again after
// scattering would carry 0.25 or less. `grazing_hits` counts the hits among
// the pixels.
void expect_one_scattering_only(const RenderResult& result, const std::string& name, Backend backend,
                                int minimum_hits) {
    int hits = 0, other = 0;
    for (float v : result.image.rgb) {
        if (std::fabs(v - 0.5f) <= 1e-6f)
            ++hits;
        else if (v != 1.0f)
            ++other;
    }
    report_figure(name, backend, format("1-spp pixel channels: %.0f hit (0.5), %.0f neither 0.5 nor 1", hits, other));
    EXPECT_EQ(other, 0);
    EXPECT_GE(hits, minimum_hits);
    EXPECT_EQ(result.stats.nonfinite, 0u);
}

// The camera 1 above a diffuse plane, looking at the horizon: the rows just
// below it meet the plane at t up to ~1e6 and incidence angles down to 1e-6
// rad, where o + t d carries an error of ulp(t), far above ulp of the point.
TEST_P(Geometry, RaysGrazingAPlane) {
    RenderBlock block{48, 48, 1, 8};
    Scene scene = empty_scene(block, {0, 0, -1}, 2.0);
    scene.render.nee = false;
    scene.background = glm::dvec3(1.0);
    scene.planes.push_back({{0, -1, 0}, {0, 1, 0}, add_material(scene, diffuse(glm::dvec3(0.5)))});
    build_light_table(scene);
    expect_one_scattering_only(render_on(GetParam(), scene), "rays grazing a plane", GetParam(), 3 * 48 * 20);
}

// A mirror sphere seen at its silhouette through a 0.5 degree field: most
// rays meet it within a fraction of a degree of tangency.
TEST_P(Geometry, RaysGrazingASpheresSilhouette) {
    RenderBlock block{48, 48, 1, 8};
    double s = 0.25;  // sin of the silhouette's angle from the axis: radius / distance
    Scene scene = empty_scene(block, {s, 0, -std::sqrt(1 - s * s)}, 0.5);
    scene.background = glm::dvec3(1.0);
    scene.spheres.push_back({{0, 0, -4}, 1.0, add_material(scene, mirror(glm::dvec3(0.5)))});
    build_light_table(scene);
    expect_one_scattering_only(render_on(GetParam(), scene), "rays grazing a sphere's silhouette", GetParam(),
                               3 * 48 * 10);
}

INSTANTIATE_TEST_SUITE_P(Backends, Geometry, ::testing::Values(Backend::Reference, Backend::Wavefront), BackendNames());

}  // namespace
}  // namespace wp::test
