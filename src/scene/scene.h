// A loaded, validated scene. Positions are camera-relative: the loader
// subtracts the camera position (in double) from every position, so that
// float kernels keep full precision near the viewer wherever the scene sits.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <glm/mat3x3.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "import/import_limits.h"

namespace wp {

// Mitsuba 3's pixel filters (kernels/shared/pixel_filter.h, sampled by
// importance): the box is the pixel itself.
enum class FilterType { Box, Tent, Gaussian };

struct PixelFilter {
    FilterType type = FilterType::Box;
    double radius = 1.0;  // tent: its half-width in pixels
    double stddev = 0.5;  // gaussian: its standard deviation in pixels, windowed at 4 stddev
};

struct Camera {
    glm::dvec3 position{0.0};  // always the origin after loading
    glm::dvec3 look_at{0.0, 0.0, -1.0};
    glm::dvec3 up{0.0, 1.0, 0.0};
    double fov_y_degrees = 40.0;
    int width = 0;
    int height = 0;
    PixelFilter filter;
    double tan_half_fov_y() const;
    double aspect() const;  // width / height
};

// How diffuse vertices choose the next direction (the weight keeps the
// estimator unbiased either way; cosine has the lower variance).
enum class Hemisphere { Cosine, Uniform };

// What a camera sample's numbers are: Owen-scrambled Sobol' points for each
// vertex's 2-D integrals (kernels/shared/sampler.h), or independent numbers.
enum class Sampler { Sobol, Independent };

// What estimates each pixel: path tracing, or stochastic progressive photon
// mapping (docs/architecture.md, "Photon mapping"), whose iterations `spp` counts.
enum class Integrator { Path, Sppm };

struct SppmSettings {
    std::uint32_t photons = 0;  // photons per iteration; 0: kSppmDefaultPhotons
    double radius = 0.0;        // every pixel's first radius; 0: from its footprint (sppm_first_radius, shared/sppm.h)
    double alpha = 2.0 / 3.0;   // the fraction of new photons a pixel keeps as its radius shrinks
};

struct RenderSettings {
    int spp = 16;
    int max_depth = 8;  // most scattering events a path may have
    int rr_depth = 3;   // Russian roulette from this many scattering events on
    std::uint32_t seed = 0;
    bool nee = true;  // next-event estimation; off: emission is counted at every hit (pure BSDF sampling)
    bool mis = true;  // with nee: light samples and BSDF-sampled emitter hits combined by the power heuristic
    Hemisphere hemisphere = Hemisphere::Cosine;
    Sampler sampler = Sampler::Sobol;
    Integrator integrator = Integrator::Path;
    SppmSettings sppm = {};  // with Integrator::Sppm
};

// The material kinds (docs/scene-format.md, "materials"). Conductor and
// RoughConductor are Mitsuba 3's `conductor` and `roughconductor`, Plastic and
// RoughPlastic its `plastic` and `roughplastic`, with its parameter names.
enum class MaterialType {
    Diffuse,
    Mirror,
    Glass,
    Emitter,
    Conductor,
    RoughConductor,
    RoughDielectric,
    ThinDielectric,
    Plastic,
    RoughPlastic
};

inline constexpr int kNoTexture = -1;

// The texture kinds (docs/scene-format.md, "textures"), Mitsuba 3's bitmap
// and checkerboard, with its parameters and their defaults.
enum class TextureType { Bitmap, Checkerboard };
enum class TextureFilter { Bilinear, Nearest };
enum class TextureWrap { Repeat, Mirror, Clamp };

struct Texture {
    std::string name;
    TextureType type = TextureType::Bitmap;
    // bitmap: the file as the scene names it (for messages), the path it was
    // read from, whether it was read `raw` (not decoded from sRGB), its size
    // and its texels in linear RGB, row by row, row 0 at v = 0 (the image's top row)
    std::string file;
    std::string path;
    bool raw = false;
    int width = 0, height = 0;
    std::vector<float> texels;
    TextureFilter filter = TextureFilter::Bilinear;
    TextureWrap wrap = TextureWrap::Repeat;
    glm::dvec3 color0{0.4}, color1{0.2};  // checkerboard
    // u' = to_uv[0] u + to_uv[1] v + to_uv[2], v' = to_uv[3] u + to_uv[4] v + to_uv[5]
    std::array<double, 6> to_uv{1.0, 0.0, 0.0, 0.0, 1.0, 0.0};
};

// The material parameters that may be textured (docs/scene-format.md), each
// a slot of Material::textures: Albedo is the diffuse albedo and the
// plastics' diffuse_reflectance (Material::albedo), SpecularReflectance the
// conductors' and plastics' specular_reflectance, AlphaU and AlphaV the
// roughconductor's and roughdielectric's roughness (alpha_u, alpha_v; `alpha`
// is both), NormalMap a `normalmap` adapter's map (read raw:
// kernels/shared/normal_map.h), BumpMap a `bumpmap` adapter's height (a
// bitmap; the gradient of its luminance bends the normal), Opacity a `mask`
// adapter's opacity (kernels/shared/materials/mask.h). The kernels' WP_TEXTURED_*
// (kernels/interface/scene_layout.h) in the same order.
enum class TexturedParameter { Albedo, SpecularReflectance, AlphaU, AlphaV, NormalMap, BumpMap, Opacity };
inline constexpr std::size_t kTexturedParameters = 7;

// The microfacet distributions of the rough materials (kernels/shared/materials/microfacet.h).
enum class Microfacet { Beckmann, GGX };

struct Material {
    std::string name;
    MaterialType type = MaterialType::Diffuse;
    glm::dvec3 albedo{0.0};       // diffuse; plastic and roughplastic: the base's diffuse_reflectance
    glm::dvec3 reflectance{0.0};  // mirror
    double ior = 1.5;             // glass, roughdielectric, thindielectric and the plastics: inside over outside
    glm::dvec3 emission{0.0};     // diffuse (optional) and emitter
    bool two_sided = false;       // emission on both sides
    // conductor and roughconductor: the complex index of refraction eta + i k
    // per channel (eta 0, k 1 reflects everything: Mitsuba's material "none"),
    // and a factor on the reflection (the plastics' too, on their coat's)
    glm::dvec3 eta{0.0}, k{1.0};
    glm::dvec3 specular_reflectance{1.0};
    // roughconductor, roughdielectric and roughplastic: the microfacet distribution and its
    // roughness along the shading frame's two tangents (equal where isotropic; roughplastic's are)
    Microfacet distribution = Microfacet::Beckmann;
    bool rough() const;  // roughconductor, roughdielectric or roughplastic: one with microfacets
    double alpha_u = 0.1, alpha_v = 0.1;
    bool nonlinear = false;  // plastic and roughplastic: Mitsuba's `nonlinear` (colours saturate under the coat)
    double bump_scale =
        1;  // a `bumpmap` adapter's `scale`: its height's gradient times this (TexturedParameter::BumpMap)
    // diffuse, mirror, the conductors and the plastics: black where the path
    // meets the back (the side the geometric normal points away from), as
    // Mitsuba 3's BSDFs outside a twosided; else they reflect alike on both sides
    bool one_sided = false;
    // a `mask` adapter's opacity in [0, 1] (TexturedParameter::Opacity): the
    // probability that the surface scatters a ray rather than let it pass
    // (kernels/shared/materials/mask.h); 1 without a mask
    double opacity = 1;
    // Per TexturedParameter: an index into Scene::textures, or kNoTexture for the constant above.
    std::array<int, kTexturedParameters> textures{kNoTexture, kNoTexture, kNoTexture, kNoTexture,
                                                  kNoTexture, kNoTexture, kNoTexture};
    int& texture(TexturedParameter p) { return textures[static_cast<std::size_t>(p)]; }
    int texture(TexturedParameter p) const { return textures[static_cast<std::size_t>(p)]; }
    bool textured() const;  // some parameter is
    bool masked() const;    // a `mask` adapter: its opacity is below 1 somewhere
    bool adapted() const;   // a `normalmap`, `bumpmap` or `mask` adapter around its nested material
    // a roughconductor or roughdielectric whose alpha_u may differ from its alpha_v: two different
    // constants, two different textures, or one textured and not the other
    bool anisotropic() const;
    bool emits() const;
};

struct Sphere {
    glm::dvec3 center{0.0};
    double radius = 1.0;
    int material = 0;
};

struct Plane {
    glm::dvec3 point{0.0};
    glm::dvec3 normal{0.0, 1.0, 0.0};  // unit length after loading
    int material = 0;
};

struct Quad {
    glm::dvec3 corner{0.0};
    glm::dvec3 edge1{1.0, 0.0, 0.0};
    glm::dvec3 edge2{0.0, 0.0, 1.0};
    int material = 0;
};

// A triangle mesh from a file (docs/scene-format.md, "mesh"), in the scene's
// camera-relative world space: transformed and rebased in double at load.
struct Mesh {
    std::string file;                   // as the scene names it, for messages
    std::vector<glm::dvec3> positions;  // finite
    std::vector<glm::dvec3> normals;    // one per position, unit length; empty: face normals only
    std::vector<glm::dvec2> uvs;        // one per position (the file's first set); empty: none
    std::vector<glm::uvec3> triangles;  // indices into positions, none of zero area; the front is
                                        // the side of (p1 - p0) x (p2 - p0) (counter-clockwise)
    int material = 0;
    std::size_t degenerate_dropped = 0;  // zero-area triangles of the file left out
};

enum class ShapeType { Sphere, Plane, Quad, Mesh };

// What emits a light: a shape's material, a directional light (Mitsuba 3's
// `directional`: Scene::directional_lights), a point or spot light (its
// `point` and `spot`: Scene::point_lights), or the environment, the
// radiance Scene::background of every direction that leaves the scene
// (Mitsuba 3's `constant` emitter) or Scene::environment_map's (its `envmap`).
enum class LightKind { Shape, Directional, Point, Environment };

// A light at infinity in one direction, a delta light (docs/scene-format.md, "lights").
struct DirectionalLight {
    glm::dvec3 direction{0.0, -1.0, 0.0};  // unit: the way its light travels (Mitsuba's `direction`)
    glm::dvec3 irradiance{1.0};            // on a surface facing it
};

// A spot's cone (Mitsuba 3's `spot`): its intensity falls off linearly in
// the angle to its axis, from 1 at the beam width to 0 at the cutoff angle.
struct SpotCone {
    glm::dvec3 axis{0.0, 0.0, 1.0};  // unit: the direction it points in (to_world's +z in Mitsuba)
    double cutoff_angle = 20.0;      // degrees, in (0, 90]
    double beam_width = 15.0;        // degrees, in [0, cutoff_angle]
};

// A light at a point, a delta light (docs/scene-format.md, "lights"): a
// point light shines alike in every direction, a spot within its cone.
struct PointLight {
    glm::dvec3 position{0.0};
    glm::dvec3 intensity{1.0};     // radiant intensity (a spot's on its axis): irradiance I cos / r^2
    std::optional<SpotCone> cone;  // a spot's
};

// The terms of a point light's falloff (kernels/shared/direct_light.h,
// spot_falloff), in double; the device's and the reference's round them.
// A point light's cosines are -2: its falloff is 1 in every direction.
struct SpotFalloffTerms {
    glm::dvec3 axis{0.0, 0.0, 1.0};
    double cos_cutoff = -2.0, cos_beam = -2.0, cutoff_angle = 0.0, inv_transition_width = 0.0;
};
SpotFalloffTerms spot_falloff_terms(const PointLight& light);

// The environment as an image (Mitsuba 3's `envmap`; docs/scene-format.md,
// "lights"): a latitude-longitude map of the radiance arriving from every
// direction, kernels/shared/environment_map.h's mapping.
struct EnvironmentMap {
    std::string file;  // as the scene names it, for messages
    int width = 0, height = 0;
    std::vector<float> texels;  // linear RGB, row by row, row 0 the image's top (t = 0), before `scale`
    double scale = 1.0;
    glm::dmat3 to_world{1.0};  // orthogonal: the map's frame in the world's
    std::string path;          // the file as the reader found it (for the scene writer)
};

// An emitting sphere, quad or mesh (planes cannot emit: infinite power), a
// directional light, a point light, or the environment, which is the
// table's last light.
struct Light {
    LightKind kind = LightKind::Shape;
    ShapeType shape = ShapeType::Quad;  // a shape's
    int index = 0;  // into Scene::spheres, Scene::quads or Scene::meshes; Scene::directional_lights or point_lights
    // A shape's: pi * luminance(emission) * area * (two_sided ? 2 : 1). The
    // distant lights' what reaches the scene's bounding sphere (radius r), as
    // pbrt-v4 estimates it (DistantLight::Phi, UniformInfiniteLight::Phi,
    // ImageInfiniteLight::Phi): pi r^2 * luminance(irradiance),
    // 4 pi * pi r^2 * luminance(radiance), an environment map's pi r^2 times
    // its luminance's integral over the sphere (environment_luminance_integral).
    // A point light's: 4 pi luminance(intensity); a spot's as pbrt-v4's
    // SpotLight::Phi, 2 pi luminance(intensity) ((1 - cos beam) + (cos beam -
    // cos cutoff) / 2), its falloff taken as linear in the cosine.
    double power = 0.0;
};

// Which features occur, so kernels and path state can leave the rest out.
struct FeatureSet {
    bool spheres = false, planes = false, quads = false, meshes = false;
    bool diffuse = false, mirror = false, glass = false, emitter_material = false;
    bool conductor = false, rough_conductor = false, rough_dielectric = false, thin_dielectric = false;
    bool plastic = false, rough_plastic = false;
    bool shading_normals = false;  // a mesh shades with its vertex normals
    bool pixel_filter = false;     // the camera's filter is a tent or a gaussian, not the box
    bool textures = false;         // a material parameter is textured: hits compute their uv
    bool normal_map = false;       // a material is a `normalmap` adapter: hits perturb their shading normal
    bool bump_map = false;         // a material is a `bumpmap` adapter: hits bend their shading normal
    // a rough conductor's or dielectric's alpha_u may differ from its alpha_v (Material::anisotropic):
    // its microfacets' frame follows the surface's dp/du
    bool anisotropic_roughness = false;
    bool mask = false;       // a material is a `mask` adapter: rays may pass its surface
    bool one_sided = false;  // a material is black from the back (Material::one_sided)
    bool sphere_lights = false, quad_lights = false, mesh_lights = false;
    bool directional_lights = false;
    bool point_lights = false;          // point and spot lights (Scene::point_lights)
    bool constant_environment = false;  // a non-black background: the environment light
    bool environment_map = false;       // the environment is an image (Scene::environment_map)
    bool nee = false;                   // next-event estimation runs: render.nee is on and the scene has a light
    bool mis = false;                   // nee runs at non-specular vertices and render.mis is on
    bool sppm = false;                  // the integrator is sppm: visible points and photons
    // Not the scene's: the wavefront's kernels read the rays' hits, which the
    // host traced (--intersector embree, kernels/interface/stages.h).
    bool host_traced = false;
    // Not the scene's either: next-event estimation's shadow rays go through
    // the SHADOW queue to their own stage, intersect_shadow (where the host
    // traces them, and on GPUs), rather than being traced in shade
    // (docs/architecture.md, "Shadow rays").
    bool shadow_stage = false;
    // Nor this: one kernel, intersect_and_shade, traces the extension rays
    // and shades their hits, which then need no HIT queue (on CPU devices
    // with scan compaction; docs/architecture.md, "Intersect and shade as one
    // kernel"), rather than intersect and shade apart.
    bool intersect_and_shade = false;

    // A material with a delta lobe: paths carry whether their last bounce was one (a mask's pass is
    // one; kernels/device/features.h's WP_HAS_SPECULAR).
    bool specular() const { return mirror || glass || conductor || thin_dielectric || plastic || mask; }
    // A material with a lobe of finite density: next-event estimation runs at its vertices.
    bool non_specular() const { return diffuse || rough_conductor || rough_dielectric || plastic || rough_plastic; }
    // A lobe of finite density other than the Lambertian one: SPPM's visible points keep their material to evaluate it.
    bool glossy() const { return rough_conductor || rough_dielectric || plastic || rough_plastic; }
    // The kernels read the mesh triangles' uvs: for a texture's uv, or for the dp/du anisotropic roughness follows.
    bool triangle_uvs() const { return textures || anisotropic_roughness; }
    // A refraction into another medium: paths carry eta^2 for the roulette.
    bool refraction() const { return glass || rough_dielectric; }
};

struct Scene {
    std::string source;  // file name, for messages
    Camera camera;
    RenderSettings render;
    glm::dvec3 background{0.0};    // the environment's radiance (a light where not black)
    glm::dvec3 world_offset{0.0};  // camera position in the file's coordinates
    std::vector<Texture> textures;
    std::vector<Material> materials;
    std::vector<Sphere> spheres;
    std::vector<Plane> planes;
    std::vector<Quad> quads;
    std::vector<Mesh> meshes;
    std::vector<DirectionalLight> directional_lights;
    std::vector<PointLight> point_lights;
    // The environment as an image; then the background is black (one
    // environment per scene).
    std::optional<EnvironmentMap> environment_map;
    std::vector<Light> lights;
    std::vector<double> light_cdf;  // cumulative selection probability, proportional to power; last = 1

    FeatureSet features() const;
};

// One line: "<source>: <json path>: <problem>", e.g.
// "scenes/bad.json: shapes[3].radius: must be > 0, got -1".
class SceneError : public std::runtime_error {
 public:
    using std::runtime_error::runtime_error;
};

// Why the scene cannot be rendered with its sppm settings, or "" when it can:
// photons leave emitting shapes only, so a background that is not black (an
// environment light), a directional light or a point light would light paths
// no photon takes.
std::string sppm_problem(const Scene& scene);

// The photons per iteration by default: the CPU's default wavefront
// (default_wavefront_size, src/wavefront/wavefront_renderer.cpp), whose
// paths in flight the photon pass then fills. A constant, not the device's
// wavefront: the photons are part of the estimate (which photon goes where,
// when the radii shrink), so a device-dependent count would render another
// image on another device. A GPU holds 2^20 paths in flight: --photons
// 1048576 fills it (docs/scene-format.md, bench/sppm_caustic.py).
inline constexpr std::uint64_t kSppmDefaultPhotons = std::uint64_t(1) << 16;

// The photons per iteration: render.sppm.photons, or kSppmDefaultPhotons.
std::uint64_t sppm_photons(const Scene& scene);

// The angle of a pixel at the image's centre, 2 tan(fov_y / 2) / height:
// how fast the camera ray's cone widens with distance (sppm_footprint,
// kernels/shared/sppm.h). Each pixel's first radius is WP_SPPM_FOOTPRINTS
// times its cone's width at its first visible point (sppm_first_radius), or
// render.sppm.radius where that is set.
double sppm_pixel_spread(const Scene& scene);

// A mesh triangle's area, and a mesh's (in double).
double triangle_area(const Mesh& mesh, const glm::uvec3& triangle);
double mesh_area(const Mesh& mesh);

// Running sums of `weights` divided by their total, the last exactly 1: what
// select_light searches. Uniform when the weights are all 0.
std::vector<double> cumulative_distribution(const std::vector<double>& weights);

// The centre and radius of a sphere around the scene's bounded shapes
// (spheres, quads and meshes; planes are infinite), radius 0 where there are
// none: what the environment's power is estimated over.
struct BoundingSphere {
    glm::dvec3 center{0.0};
    double radius = 0.0;
};
BoundingSphere bounding_sphere(const Scene& scene);

// Fills Scene::lights and Scene::light_cdf from the emitting spheres, quads
// and meshes (in that order), the directional lights, the point lights, then the environment
// where there is one (an environment map, or a background that is not black). The loader calls it; tests that
// build scenes in code call it too.
void build_light_table(Scene& scene);

// What every loader does after reading a scene: rebases all positions to the
// camera (Scene::world_offset keeps the camera's position in the file's
// coordinates) and builds the light table.
void finish_scene(Scene& scene);

// Told after each shape a loader has read: how many so far, of how many the
// scene has. Mesh files make a load long (each is imported in a helper
// process, import/import_process.h), so the command line shows it.
using ShapeProgress = std::function<void(std::size_t read, std::size_t count)>;

// Mesh files are imported under `mesh_import` (import/import_limits.h).
Scene load_scene(const std::string& path, const MeshImportLimits& mesh_import = {}, const ShapeProgress& progress = {});
Scene parse_scene(const std::string& json_text, const std::string& source_name,
                  const MeshImportLimits& mesh_import = {}, const ShapeProgress& progress = {});

}  // namespace wp
