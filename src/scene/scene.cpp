#include "scene/scene.h"

#include <algorithm>
#include <cmath>
#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>
#include <limits>
#include <numbers>

#include "core/shared_math.h"
#include "scene/environment_layout.h"

namespace wp {
namespace {

double luminance(const glm::dvec3& c) { return 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z; }

// Radiant power (in luminance) leaving a Lambertian emitter of this area.
double emitted_power(const Material& material, double area) {
    return std::numbers::pi * luminance(material.emission) * area * (material.two_sided ? 2.0 : 1.0);
}

}  // namespace

double Camera::tan_half_fov_y() const { return std::tan(glm::radians(fov_y_degrees) / 2.0); }

double Camera::aspect() const { return static_cast<double>(width) / static_cast<double>(height); }

bool Material::emits() const { return SharedMath<double>::emits(emission); }

bool Material::masked() const { return opacity != 1.0 || texture(TexturedParameter::Opacity) != kNoTexture; }

bool Material::adapted() const {
    return texture(TexturedParameter::NormalMap) != kNoTexture || texture(TexturedParameter::BumpMap) != kNoTexture ||
           masked();
}

bool Material::rough() const {
    return type == MaterialType::RoughConductor || type == MaterialType::RoughDielectric ||
           type == MaterialType::RoughPlastic;
}

bool Material::anisotropic() const {
    const int u = texture(TexturedParameter::AlphaU), v = texture(TexturedParameter::AlphaV);
    return (type == MaterialType::RoughConductor || type == MaterialType::RoughDielectric) &&
           (u != v || (u == kNoTexture && alpha_u != alpha_v));
}

bool Material::textured() const {
    return std::any_of(textures.begin(), textures.end(), [](int t) { return t != kNoTexture; });
}

double triangle_area(const Mesh& mesh, const glm::uvec3& t) {
    return 0.5 * glm::length(
                     glm::cross(mesh.positions[t.y] - mesh.positions[t.x], mesh.positions[t.z] - mesh.positions[t.x]));
}

double mesh_area(const Mesh& mesh) {
    double area = 0.0;
    for (const glm::uvec3& t : mesh.triangles) area += triangle_area(mesh, t);
    return area;
}

FeatureSet Scene::features() const {
    FeatureSet f;
    f.spheres = !spheres.empty();
    f.planes = !planes.empty();
    f.quads = !quads.empty();
    f.meshes = !meshes.empty();
    for (const Mesh& mesh : meshes)  // an emitter ends its paths: its normals shade nothing
        f.shading_normals |= !mesh.normals.empty() && materials[mesh.material].type != MaterialType::Emitter;
    for (const Material& m : materials) {
        f.diffuse |= m.type == MaterialType::Diffuse;
        f.mirror |= m.type == MaterialType::Mirror;
        f.glass |= m.type == MaterialType::Glass;
        f.emitter_material |= m.type == MaterialType::Emitter;
        f.conductor |= m.type == MaterialType::Conductor;
        f.rough_conductor |= m.type == MaterialType::RoughConductor;
        f.rough_dielectric |= m.type == MaterialType::RoughDielectric;
        f.thin_dielectric |= m.type == MaterialType::ThinDielectric;
        f.plastic |= m.type == MaterialType::Plastic;
        f.rough_plastic |= m.type == MaterialType::RoughPlastic;
        f.textures |= m.textured();
        f.normal_map |= m.texture(TexturedParameter::NormalMap) != kNoTexture;
        f.bump_map |= m.texture(TexturedParameter::BumpMap) != kNoTexture;
        f.anisotropic_roughness |= m.anisotropic();
        f.mask |= m.masked();
        f.one_sided |= m.one_sided;
    }
    for (const Light& light : lights) {
        bool shape = light.kind == LightKind::Shape;
        f.sphere_lights |= shape && light.shape == ShapeType::Sphere;
        f.quad_lights |= shape && light.shape == ShapeType::Quad;
        f.mesh_lights |= shape && light.shape == ShapeType::Mesh;
        f.directional_lights |= light.kind == LightKind::Directional;
        f.point_lights |= light.kind == LightKind::Point;
        f.constant_environment |= light.kind == LightKind::Environment && !environment_map;
        f.environment_map |= light.kind == LightKind::Environment && environment_map.has_value();
    }
    f.pixel_filter = camera.filter.type != FilterType::Box;
    f.nee = render.nee && !lights.empty();
    f.mis = f.nee && f.non_specular() && render.mis;
    f.sppm = render.integrator == Integrator::Sppm;
    return f;
}

std::string sppm_problem(const Scene& scene) {
    if (scene.render.integrator != Integrator::Sppm) return "";
    FeatureSet f = scene.features();
    if (f.constant_environment) {
        return "sppm takes its light from emitting shapes, and the background is not black: it would light paths no "
               "photon takes (make the background black or render with the path integrator)";
    }
    if (f.environment_map) {
        return "sppm takes its light from emitting shapes, and an environment map would light paths no photon takes "
               "(render with the path integrator)";
    }
    if (f.directional_lights) {
        return "sppm takes its light from emitting shapes, and a directional light would light paths no photon takes "
               "(render with the path integrator)";
    }
    if (f.point_lights) {
        return "sppm takes its light from emitting shapes, and a point or spot light would light paths no photon "
               "takes (render with the path integrator)";
    }
    if (f.normal_map) return "sppm does not render normalmap materials (render with the path integrator)";
    if (f.bump_map) return "sppm does not render bumpmap materials (render with the path integrator)";
    if (f.mask) return "sppm does not render mask materials (render with the path integrator)";
    if (f.anisotropic_roughness)
        return "sppm does not render anisotropic roughness (alpha_u differs from alpha_v; render with the path "
               "integrator)";
    if (f.one_sided)
        return "sppm does not render one-sided materials (render with the path integrator, or make them two-sided)";
    return "";
}

std::uint64_t sppm_photons(const Scene& scene) {
    return scene.render.sppm.photons != 0 ? scene.render.sppm.photons : kSppmDefaultPhotons;
}

double sppm_pixel_spread(const Scene& scene) {
    return 2.0 * scene.camera.tan_half_fov_y() / double(scene.camera.height);
}

BoundingSphere bounding_sphere(const Scene& scene) {
    glm::dvec3 lo(std::numeric_limits<double>::max()), hi(-std::numeric_limits<double>::max());
    auto enclose = [&](const glm::dvec3& p) {
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    };
    for (const Sphere& s : scene.spheres) {
        enclose(s.center - glm::dvec3(s.radius));
        enclose(s.center + glm::dvec3(s.radius));
    }
    for (const Quad& q : scene.quads) {
        enclose(q.corner);
        enclose(q.corner + q.edge1);
        enclose(q.corner + q.edge2);
        enclose(q.corner + q.edge1 + q.edge2);
    }
    for (const Mesh& mesh : scene.meshes)
        for (const glm::dvec3& p : mesh.positions) enclose(p);
    if (lo.x > hi.x) return {};
    return {(lo + hi) * 0.5,
            glm::length(hi - lo) * 0.5};  // the box's bounding sphere, as pbrt-v4's Bounds3::BoundingSphere
}

SpotFalloffTerms spot_falloff_terms(const PointLight& light) {
    SpotFalloffTerms terms;
    if (!light.cone) return terms;
    const double cutoff = glm::radians(light.cone->cutoff_angle), beam = glm::radians(light.cone->beam_width);
    terms.axis = light.cone->axis;
    terms.cos_cutoff = std::cos(cutoff);
    terms.cos_beam = std::cos(beam);
    terms.cutoff_angle = cutoff;
    terms.inv_transition_width = cutoff > beam ? 1.0 / (cutoff - beam) : 0.0;
    return terms;
}

namespace {

// pbrt-v4's estimate (PointLight::Phi, SpotLight::Phi): 4 pi I for a point
// light; for a spot 2 pi I ((1 - cos beam) + (cos beam - cos cutoff) / 2),
// its falloff taken as linear in the cosine (Mitsuba's is linear in the
// angle: the estimate only weighs the light's choice).
double point_light_power(const PointLight& light) {
    const double intensity = luminance(light.intensity);
    if (!light.cone) return 4.0 * std::numbers::pi * intensity;
    const SpotFalloffTerms terms = spot_falloff_terms(light);
    return 2.0 * std::numbers::pi * intensity * ((1.0 - terms.cos_beam) + (terms.cos_beam - terms.cos_cutoff) / 2.0);
}

}  // namespace

void build_light_table(Scene& scene) {
    scene.lights.clear();
    scene.light_cdf.clear();
    for (int i = 0; i < static_cast<int>(scene.spheres.size()); ++i) {
        const Sphere& s = scene.spheres[i];
        const Material& m = scene.materials[s.material];
        if (m.emits()) {
            scene.lights.push_back(
                {LightKind::Shape, ShapeType::Sphere, i, emitted_power(m, SharedMath<double>::sphere_area(s.radius))});
        }
    }
    for (int i = 0; i < static_cast<int>(scene.quads.size()); ++i) {
        const Quad& q = scene.quads[i];
        const Material& m = scene.materials[q.material];
        if (m.emits()) {
            scene.lights.push_back({LightKind::Shape, ShapeType::Quad, i,
                                    emitted_power(m, SharedMath<double>::quad_area(q.edge1, q.edge2))});
        }
    }
    for (int i = 0; i < static_cast<int>(scene.meshes.size()); ++i) {
        const Mesh& mesh = scene.meshes[i];
        const Material& m = scene.materials[mesh.material];
        if (m.emits())
            scene.lights.push_back({LightKind::Shape, ShapeType::Mesh, i, emitted_power(m, mesh_area(mesh))});
    }
    const double radius = bounding_sphere(scene).radius;
    for (int i = 0; i < static_cast<int>(scene.directional_lights.size()); ++i) {
        double power = std::numbers::pi * radius * radius * luminance(scene.directional_lights[i].irradiance);
        scene.lights.push_back({LightKind::Directional, ShapeType::Sphere, i, power});
    }
    for (int i = 0; i < static_cast<int>(scene.point_lights.size()); ++i)
        scene.lights.push_back({LightKind::Point, ShapeType::Sphere, i, point_light_power(scene.point_lights[i])});
    if (scene.environment_map) {
        double power = std::numbers::pi * radius * radius * environment_luminance_integral(*scene.environment_map);
        scene.lights.push_back({LightKind::Environment, ShapeType::Sphere, 0, power});
    } else if (SharedMath<double>::emits(scene.background)) {
        double power = 4.0 * std::numbers::pi * std::numbers::pi * radius * radius * luminance(scene.background);
        scene.lights.push_back({LightKind::Environment, ShapeType::Sphere, 0, power});
    }
    std::vector<double> powers;
    for (const Light& light : scene.lights) powers.push_back(light.power);
    scene.light_cdf = cumulative_distribution(powers);
}

std::vector<double> cumulative_distribution(const std::vector<double>& weights) {
    double total = 0.0;
    for (double weight : weights) total += weight;
    std::vector<double> cdf;
    double running = 0.0;
    for (std::size_t i = 0; i < weights.size(); ++i) {
        running += weights[i];
        // Weights that all underflowed to 0 (a radiance of 1e-320) would give 0 / 0.
        cdf.push_back(total > 0.0 ? running / total : static_cast<double>(i + 1) / static_cast<double>(weights.size()));
    }
    if (!cdf.empty()) cdf.back() = 1.0;
    return cdf;
}

}  // namespace wp
