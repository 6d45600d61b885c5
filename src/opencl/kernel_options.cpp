#include "opencl/kernel_options.h"

#include <utility>
#include <vector>

#include "opencl/film.h"

namespace wp {
namespace {

// (name for --explain, macro) for each feature in use; no macro where no
// kernel code depends on the feature.
std::vector<std::pair<const char*, const char*>> features_in_use(const FeatureSet& f) {
    std::vector<std::pair<const char*, const char*>> in_use;
    auto add = [&](bool on, const char* name, const char* macro) {
        if (on) in_use.emplace_back(name, macro);
    };
    add(f.spheres, "spheres", "WP_HAS_SPHERES");
    add(f.planes, "planes", "WP_HAS_PLANES");
    add(f.quads, "quads", "WP_HAS_QUADS");
    add(f.meshes, "meshes", "WP_HAS_MESHES");
    add(f.shading_normals, "shading-normals", "WP_HAS_SHADING_NORMALS");
    add(f.diffuse, "diffuse", "WP_HAS_DIFFUSE");
    add(f.mirror, "mirror", "WP_HAS_MIRROR");
    add(f.glass, "glass", "WP_HAS_GLASS");
    add(f.conductor, "conductor", "WP_HAS_CONDUCTOR");
    add(f.rough_conductor, "roughconductor", "WP_HAS_ROUGH_CONDUCTOR");
    add(f.rough_dielectric, "roughdielectric", "WP_HAS_ROUGH_DIELECTRIC");
    add(f.thin_dielectric, "thindielectric", "WP_HAS_THIN_DIELECTRIC");
    add(f.plastic, "plastic", "WP_HAS_PLASTIC");
    add(f.rough_plastic, "roughplastic", "WP_HAS_ROUGH_PLASTIC");
    add(f.textures, "textures", "WP_HAS_TEXTURES");
    add(f.normal_map, "normal-map", "WP_HAS_NORMAL_MAP");
    add(f.bump_map, "bump-map", "WP_HAS_BUMP_MAP");
    add(f.anisotropic_roughness, "anisotropic-roughness", "WP_HAS_ANISOTROPIC_ROUGHNESS");
    add(f.mask, "mask", "WP_HAS_MASK");
    add(f.one_sided, "one-sided", "WP_HAS_ONE_SIDED");
    add(f.emitter_material, "emitter", nullptr);
    add(f.sphere_lights, "sphere-lights", "WP_HAS_SPHERE_LIGHTS");
    add(f.quad_lights, "quad-lights", "WP_HAS_QUAD_LIGHTS");
    add(f.mesh_lights, "mesh-lights", "WP_HAS_MESH_LIGHTS");
    add(f.directional_lights, "directional-lights", "WP_HAS_DIRECTIONAL_LIGHTS");
    add(f.point_lights, "point-lights", "WP_HAS_POINT_LIGHTS");
    add(f.constant_environment, "constant-environment", "WP_HAS_CONSTANT_ENVIRONMENT");
    add(f.environment_map, "environment-map", "WP_HAS_ENVIRONMENT_MAP");
    add(f.pixel_filter, "pixel-filter", "WP_HAS_PIXEL_FILTER");
    add(f.nee, "nee", "WP_NEE");
    add(f.mis, "mis", "WP_MIS");
    add(f.host_traced, "host-traced", "WP_HOST_TRACED");
    add(f.nee && f.shadow_stage, "shadow-stage", "WP_SHADOW_STAGE");
    add(f.intersect_and_shade, "intersect-and-shade", "WP_INTERSECT_AND_SHADE");
    add(f.sppm, "sppm", "WP_SPPM");
    return in_use;
}

}  // namespace

std::string kernel_build_options(const FeatureSet& features, const RenderSettings& render) {
    std::string options;
    for (const auto& [name, macro] : features_in_use(features))
        if (macro) options += std::string(" -D") + macro;
    if (render.hemisphere == Hemisphere::Uniform) options += " -DWP_UNIFORM_HEMISPHERE";
    if (render.sampler == Sampler::Independent) options += " -DWP_INDEPENDENT_SAMPLER";
    return options.empty() ? options : options.substr(1);
}

std::string shape_count_options(const Scene& scene) {
    std::string options;
    auto add = [&](const char* macro, std::size_t count) {
        if (count <= kMaxUnrolledCount) options += " -D" + std::string(macro) + "=" + std::to_string(count) + "u";
    };
    add("WP_SPHERE_COUNT", scene.spheres.size());
    add("WP_PLANE_COUNT", scene.planes.size());
    add("WP_QUAD_COUNT", scene.quads.size());
    add("WP_LIGHT_COUNT", scene.lights.size());
    return options;
}

std::string program_build_options(const Scene& scene, const FeatureSet& kernel_features, bool film_squares,
                                  const std::string& backend_options, unsigned lanes) {
    return kernel_build_options(kernel_features, scene.render) + film_build_options(film_squares) +
           shape_count_options(scene) + backend_options + " -DWP_LANES=" + std::to_string(lanes);
}

std::string describe_features(const FeatureSet& features) {
    std::string text;
    for (const auto& [name, macro] : features_in_use(features)) text += (text.empty() ? "" : " ") + std::string(name);
    return text;
}

}  // namespace wp
