/* The work at one path vertex, shared by the wavefront's stage kernels and
 * the megakernel: the camera ray, emission seen at a hit, the light sample of
 * next-event estimation, BSDF sampling and Russian roulette. What is computed
 * is the shared code's (kernels/shared: materials/, lights.h, estimator.h,
 * camera.h), which the reference calls too; this header reads each lane's
 * scene data and chooses per lane (shared/prelude.h): every kind of shape
 * and light in the scene is computed in every lane, and each lane keeps its
 * own with a select; a material kind is sampled and evaluated only where some
 * lane of the vector has it (bench/results/analysis.md, "Materials against
 * Mitsuba 3": evaluating every kind cost each vertex the scene's others). */
#ifndef WP_DEVICE_PATH_VERTEX_H
#define WP_DEVICE_PATH_VERTEX_H

#include "device/features.h"
#include "shared/estimator.h"
#include "shared/lights.h"
#include "shared/materials/bsdf.h"
#include "shared/prelude.h"
#include "shared/rng.h"
#include "shared/sampler.h"
#include "shared/triangle.h"
#ifdef WP_HAS_NON_SPECULAR
#include "shared/direct_light.h"
#endif
#ifdef WP_HAS_DIFFUSE
#include "shared/materials/diffuse.h"
#endif
#ifdef WP_HAS_MIRROR
#include "shared/materials/mirror.h" /* (and shared/fresnel.h, before the poison below) */
#endif
#ifdef WP_HAS_CONDUCTOR
#include "shared/materials/conductor.h"
#endif
#ifdef WP_HAS_ROUGH_CONDUCTOR
#include "shared/materials/roughconductor.h"
#endif
#ifdef WP_HAS_PLASTIC
#include "shared/materials/plastic.h"
#endif
#ifdef WP_HAS_ROUGH_PLASTIC
#include "shared/materials/roughplastic.h"
#endif
#if !defined(WP_HAS_DIELECTRICS) && !defined(WP_HAS_PLASTICS)
/* Without a dielectric interface the dielectric code must not be compiled in: any use is a build error. */
#pragma GCC poison fresnel_dielectric refract_direction
#endif
#ifdef WP_HAS_GLASS
#include "shared/materials/glass.h"
#endif
#ifdef WP_HAS_ROUGH_DIELECTRIC
#include "shared/materials/roughdielectric.h"
#endif
#ifdef WP_HAS_THIN_DIELECTRIC
#include "shared/materials/thindielectric.h"
#endif
#include "device/camera.h"
#include "device/guards.h"
#include "device/lane_memory.h"
#include "device/light_ranges.h"
#include "device/parameters.h"
#include "device/scene_hits.h"
#include "device/surface.h"

/* The build's choices as the values the shared functions take (the reference
 * passes its scene's). */
#ifdef WP_NEE
#define WP_USES_NEE 1
#else
#define WP_USES_NEE 0
#endif
#ifdef WP_MIS
#define WP_USES_MIS 1
#else
#define WP_USES_MIS 0
#endif
#if defined(WP_HAS_SHADING_NORMALS) || defined(WP_PERTURBS_NORMALS)
#define WP_USES_SHADING_NORMALS 1
#else
#define WP_USES_SHADING_NORMALS 0
#endif
#ifdef WP_INDEPENDENT_SAMPLER
#define WP_USES_SOBOL 0
#else
#define WP_USES_SOBOL 1
#endif
#ifdef WP_UNIFORM_HEMISPHERE
#define WP_USES_UNIFORM_HEMISPHERE 1
#else
#define WP_USES_UNIFORM_HEMISPHERE 0
#endif

/* The camera ray direction of sample s of pixel px, through the point of the
 * pixel its filter draws (shared/pixel_filter.h). */
WP_FN vec3 camera_ray_direction(__global const SceneHeader *scene, lane_uint px, lane_uint s) {
    CameraPair film = camera_pair(scene->seed, px, s, 0u, DIM_FILM_X, WP_USES_SOBOL);
#ifdef WP_HAS_PIXEL_FILTER
    FilmPoint point = pixel_filter_sample(scene_pixel_filter(scene), film.u, film.v);
    return pixel_ray_direction(scene, px, point.u, point.v);
#else
    return pixel_ray_direction(scene, px, film.u, film.v);
#endif
}

#ifdef WP_MIS
/* The solid-angle density with which next-event estimation from `reference`
 * samples `point` (geometric normal `normal`) of light `light`. */
WP_FN real light_point_pdf(WP_SCENE_PARAMS, lane_uint light, vec3 reference, vec3 point, vec3 normal) {
    lane_uint shape = SCENE_FIELD(lights, light, shape);
    lane_uint index = shape & WP_SHAPE_INDEX_MASK, type = shape >> WP_SHAPE_TYPE_SHIFT;
    real pdf = REAL(0.0);
#ifdef WP_HAS_SPHERE_LIGHTS
    {
        lane_int is_sphere = type == WP_SHAPE_SPHERE;
        lane_uint i = is_sphere ? index : (lane_uint)0u;
        real sphere_pdf = sphere_light_pdf(SCENE_FIELD(spheres, i, center), SCENE_FIELD(spheres, i, radius), reference,
                                           point, normal);
        pdf = is_sphere ? sphere_pdf : pdf;
    }
#endif
#ifdef WP_HAS_QUAD_LIGHTS
    {
        lane_int is_quad = type == WP_SHAPE_QUAD;
        lane_uint i = is_quad ? index : (lane_uint)0u;
        real quad_pdf =
            quad_light_pdf(SCENE_FIELD(quads, i, edge1), SCENE_FIELD(quads, i, edge2), reference, point, normal);
        pdf = is_quad ? quad_pdf : pdf;
    }
#endif
#ifdef WP_HAS_MESH_LIGHTS
    {
        real mesh_pdf = mesh_light_pdf(SCENE_FIELD(lights, light, area), reference, point, normal);
        pdf = type == WP_SHAPE_TRIANGLE ? mesh_pdf : pdf;
    }
#endif
    return light_sample_pdf(light_selection_pmf(light_cdf, light), pdf);
}

/* The light an emitting hit `shape` belongs to (light_key): a scan of the
 * light table, whose length is a compile-time constant in small scenes. */
WP_FN lane_uint light_of_shape(WP_SCENE_PARAMS, lane_uint shape) {
    lane_uint kind = shape >> WP_SHAPE_TYPE_SHIFT, index = shape & WP_SHAPE_INDEX_MASK;
    lane_int is_triangle = kind == WP_SHAPE_TRIANGLE;
#ifdef WP_HAS_MESH_LIGHTS
    lane_uint mesh = SCENE_FIELD(triangles, is_triangle ? index : (lane_uint)0u, mesh);
#else
    lane_uint mesh = 0u; /* no light is a mesh's */
#endif
    lane_uint key = light_key(is_triangle, index, mesh);
    lane_uint light = 0u;
    for (uint i = 0u; i < LIGHT_COUNT; ++i) {
        lane_uint light_shape = lights[i].shape; /* in every lane, so that its conditions are lane conditions */
        lane_uint light_kind = light_shape >> WP_SHAPE_TYPE_SHIFT;
        lane_int is_this = light_kind == kind && light_key(light_kind == WP_SHAPE_TRIANGLE,
                                                           light_shape & WP_SHAPE_INDEX_MASK, lights[i].mesh) == key;
        light = is_this ? (lane_uint)i : light;
    }
    return light;
}
#endif

/* The emission a path of throughput `throughput` counts at vertex v (reached
 * along the ray from `origin`, which hit `shape`): emission_seen with its
 * share emission_weight; the bounce recorded its density `bsdf_pdf`. */
WP_VERTEX_FN vec3 hit_emission(WP_SCENE_PARAMS, lane_uint shape, vec3 origin, Vertex v, lane_int after_specular,
                               real bsdf_pdf, vec3 throughput) {
#ifdef WP_MIS
    real light_pdf =
        light_point_pdf(WP_SCENE_ARGS, light_of_shape(WP_SCENE_ARGS, shape), origin, v.surface.point, v.surface.normal);
#else
    real light_pdf = REAL(0.0);
#endif
    real weight = emission_weight(after_specular, bsdf_pdf, light_pdf, WP_USES_NEE, WP_USES_MIS);
    return emission_seen(v.material.emission, v.material.two_sided, v.front, weight, throughput);
}

/* `term` where `where` holds, else nothing: a term added only in some lanes. */
WP_FN vec3 only_where(lane_int where, vec3 term) {
    return v3_select(where, term, make_vec3(REAL(0.0), REAL(0.0), REAL(0.0)));
}

#if defined(WP_HAS_CONSTANT_ENVIRONMENT) || defined(WP_HAS_ENVIRONMENT_MAP)
/* Whether light `light` is the environment (the table's last light). */
WP_FN lane_int is_environment_light(WP_SCENE_PARAMS, lane_uint light) {
    return (SCENE_FIELD(lights, light, shape) >> WP_SHAPE_TYPE_SHIFT) == WP_LIGHT_ENVIRONMENT;
}

#ifdef WP_HAS_ENVIRONMENT_MAP
/* The environment map's size and frame, from the scene's header. */
WP_FN EnvironmentMapLayout scene_environment_map(WP_SCENE_PARAMS) {
    EnvironmentMapLayout map;
    map.width = scene->environment_width;
    map.height = scene->environment_height;
    for (int i = 0; i < 9; ++i) map.to_world[i] = scene->environment_to_world[i];
    return map;
}
#endif

/* The density with which next-event estimation picks the environment's
 * direction d: its selection probability times the map's density
 * (environment_pdf), or the uniform sphere's for the constant one. */
WP_FN real environment_light_pdf(WP_SCENE_PARAMS, vec3 d) {
    lane_uint environment = (lane_uint)(LIGHT_COUNT - 1u);
#ifdef WP_HAS_ENVIRONMENT_MAP
    real direction_pdf = environment_pdf(scene_environment_map(WP_SCENE_ARGS), environment_map, d);
#else
    real direction_pdf = uniform_sphere_pdf();
#endif
    return light_sample_pdf(light_selection_pmf(light_cdf, environment), direction_pdf);
}

/* The environment's radiance from direction d: the map's, or the constant background. */
WP_FN vec3 environment_radiance_from(WP_SCENE_PARAMS, vec3 d) {
#ifdef WP_HAS_ENVIRONMENT_MAP
    return environment_radiance(scene_environment_map(WP_SCENE_ARGS), environment_map, d);
#else
    return uniform_vec3(scene->background);
#endif
}

/* The environment's radiance a path of throughput `throughput` counts where
 * it leaves the scene along d: environment_seen with its share emission_weight. */
WP_FN vec3 environment_emission(WP_SCENE_PARAMS, vec3 d, lane_int after_specular, real bsdf_pdf, vec3 throughput) {
#ifdef WP_MIS
    real light_pdf = environment_light_pdf(WP_SCENE_ARGS, d);
#else
    real light_pdf = REAL(0.0);
#endif
    real weight = emission_weight(after_specular, bsdf_pdf, light_pdf, WP_USES_NEE, WP_USES_MIS);
    return environment_seen(throughput, environment_radiance_from(WP_SCENE_ARGS, d), weight);
}
#endif

/* `radiance` plus what a path of throughput `throughput` sees where its ray
 * from `origin` along `direction` ends: the environment where it `missed`,
 * the emission at vertex v (hit_emission) where it `hit`. A non-finite term
 * is dropped and counted in *dropped. */
WP_FN vec3 add_radiance_seen(WP_SCENE_PARAMS, vec3 radiance, lane_int missed, lane_int hit, lane_uint shape,
                             vec3 origin, vec3 direction, Vertex v, lane_int after_specular, real bsdf_pdf,
                             vec3 throughput, lane_uint *dropped) {
#if defined(WP_HAS_CONSTANT_ENVIRONMENT) || defined(WP_HAS_ENVIRONMENT_MAP)
    radiance = add_finite(
        radiance,
        only_where(missed, environment_emission(WP_SCENE_ARGS, direction, after_specular, bsdf_pdf, throughput)),
        dropped);
#endif
    vec3 emitted = hit_emission(WP_SCENE_ARGS, shape, origin, v, after_specular, bsdf_pdf, throughput);
    return add_finite(radiance, only_where(hit, emitted), dropped);
}

/* Whether the path ends at vertex v once its emission is counted: the depth
 * cap (a vertex at depth max_depth adds its emission and no more) or an
 * emitter material, which reflects nothing. */
WP_VERTEX_FN lane_int vertex_ends_path(Vertex v, lane_uint bounce, uint max_depth) {
    return bounce >= max_depth || v.material.type == WP_MATERIAL_EMITTER;
}

/* Light `light`'s shape in each lane, read for its kind: every light kind in
 * the scene is read and each lane keeps its own kind's; a lane whose light is
 * of another kind reads that kind's arrays at index 0. u_triangle picks a
 * mesh light's triangle in proportion to area. With it, the material that
 * emits and the magnitude its error comes from (offset.h). Camera paths
 * sample it as seen from a point (sample_light_shape), photons leave it
 * uniformly by area (device/photon_vertex.h). */
typedef struct {
    lane_uint type; /* WP_SHAPE_* */
    lane_uint material;
    real magnitude;
#ifdef WP_HAS_SPHERE_LIGHTS
    vec3 center;
    real radius;
#endif
#ifdef WP_HAS_QUAD_LIGHTS
    vec3 corner, edge1, edge2;
#endif
#ifdef WP_HAS_MESH_LIGHTS
    vec3 p0, p1, p2; /* the triangle u_triangle picked */
    real mesh_area;  /* the whole mesh light's */
#endif
} LightShape;

WP_FN LightShape light_shape(WP_SCENE_PARAMS, lane_uint light, real u_triangle) {
    lane_uint shape = SCENE_FIELD(lights, light, shape);
    lane_uint index = shape & WP_SHAPE_INDEX_MASK;
    LightShape l;
    l.type = shape >> WP_SHAPE_TYPE_SHIFT;
    l.material = 0u;
    l.magnitude = REAL(0.0);
#ifdef WP_HAS_SPHERE_LIGHTS
    {
        lane_int is_sphere = l.type == WP_SHAPE_SPHERE;
        lane_uint i = is_sphere ? index : (lane_uint)0u;
        l.center = SCENE_FIELD(spheres, i, center);
        l.radius = SCENE_FIELD(spheres, i, radius);
        l.material = is_sphere ? SCENE_FIELD(spheres, i, material) : l.material;
        l.magnitude = is_sphere ? sphere_magnitude(l.center, l.radius) : l.magnitude;
    }
#endif
#ifdef WP_HAS_QUAD_LIGHTS
    {
        lane_int is_quad = l.type == WP_SHAPE_QUAD;
        lane_uint i = is_quad ? index : (lane_uint)0u;
        l.corner = SCENE_FIELD(quads, i, corner);
        l.edge1 = SCENE_FIELD(quads, i, edge1);
        l.edge2 = SCENE_FIELD(quads, i, edge2);
        l.material = is_quad ? SCENE_FIELD(quads, i, material) : l.material;
        l.magnitude = is_quad ? quad_magnitude(l.corner, l.edge1, l.edge2) : l.magnitude;
    }
#endif
#ifdef WP_HAS_MESH_LIGHTS
    {
        lane_int is_mesh = l.type == WP_SHAPE_TRIANGLE;
        lane_uint first = is_mesh ? index : (lane_uint)0u;
        lane_uint count = is_mesh ? SCENE_FIELD(lights, light, triangle_count) : (lane_uint)0u;
        lane_uint k = select_light_in_range(light_triangle_cdf, first, count, u_triangle);
        l.p0 = SCENE_FIELD(light_triangles, k, p0);
        l.p1 = SCENE_FIELD(light_triangles, k, p1);
        l.p2 = SCENE_FIELD(light_triangles, k, p2);
        l.mesh_area = SCENE_FIELD(lights, light, area);
        l.material = is_mesh ? SCENE_FIELD(light_triangles, k, material) : l.material;
        l.magnitude = is_mesh ? triangle_magnitude(l.p0, l.p1, l.p2) : l.magnitude;
    }
#endif
    return l;
}

#if defined(WP_HAS_ROUGH_CONDUCTOR) || defined(WP_HAS_ROUGH_DIELECTRIC)
/* The frame of v's rough material's microfacets about the normal of
 * `isotropic`, the frame the material builds from the normal alone
 * (shared/materials/microfacet.h): that frame itself unless the scene has
 * anisotropic roughness. */
WP_VERTEX_FN Frame vertex_microfacet_frame(Vertex v, Frame isotropic) {
#ifdef WP_HAS_ANISOTROPIC_ROUGHNESS
    return microfacet_frame(v.material.microfacet, isotropic, v.dp_du);
#else
    return isotropic;
#endif
}
#endif

#ifdef WP_HAS_NON_SPECULAR
/* The path's throughput times f, and the density of BSDF sampling, for the
 * direction wi from vertex v: next-event estimation's two numbers from the
 * material (SPPM's gather takes the first at a visible point). Every non-specular kind that some lane has is evaluated
 * and each lane keeps its own material's (0 at a specular one, which samples no light). */
typedef struct {
    vec3 throughput_f;
    real pdf;
} BsdfValue;

WP_VERTEX_FN BsdfValue vertex_bsdf_value(Vertex v, vec3 wi, vec3 throughput) {
    Material m = v.material;
    BsdfValue b;
    b.throughput_f = make_vec3(REAL(0.0), REAL(0.0), REAL(0.0));
    b.pdf = REAL(0.0);
#ifdef WP_HAS_DIFFUSE
    if (lanes_have_kind(m.type, WP_MATERIAL_DIFFUSE)) {
        lane_int is_diffuse = m.type == WP_MATERIAL_DIFFUSE;
        /* the albedo before 1 / pi (diffuse_eval), in the order the estimator has always rounded it */
        b.throughput_f = v3_select(is_diffuse, diffuse_eval(v3_mul(throughput, m.albedo), v.ns, wi), b.throughput_f);
        b.pdf = is_diffuse ? diffuse_pdf(v.ns, wi, WP_USES_UNIFORM_HEMISPHERE) : b.pdf;
    }
#endif
#ifdef WP_HAS_ROUGH_CONDUCTOR
    if (lanes_have_kind(m.type, WP_MATERIAL_ROUGH_CONDUCTOR)) {
        lane_int is_rough = m.type == WP_MATERIAL_ROUGH_CONDUCTOR;
        Frame frame = vertex_microfacet_frame(v, frame_from_normal(v.ns));
        vec3 f = roughconductor_eval(m.microfacet, m.eta, m.k, m.specular_reflectance, frame, v.wo, wi);
        b.throughput_f = v3_select(is_rough, v3_mul(throughput, f), b.throughput_f);
        b.pdf = is_rough ? roughconductor_pdf(m.microfacet, frame, v.wo, wi) : b.pdf;
    }
#endif
#ifdef WP_HAS_ROUGH_DIELECTRIC
    if (lanes_have_kind(m.type, WP_MATERIAL_ROUGH_DIELECTRIC)) {
        lane_int is_rough = m.type == WP_MATERIAL_ROUGH_DIELECTRIC;
        Frame frame = vertex_microfacet_frame(v, roughdielectric_frame(v.ns, v.front));
        vec3 f = roughdielectric_eval(m.microfacet, m.ior, v.front, frame, v.wo, wi, WP_TRANSPORT_RADIANCE);
        b.throughput_f = v3_select(is_rough, v3_mul(throughput, f), b.throughput_f);
        b.pdf = is_rough ? roughdielectric_pdf(m.microfacet, m.ior, v.front, frame, v.wo, wi) : b.pdf;
    }
#endif
#ifdef WP_HAS_PLASTIC
    if (lanes_have_kind(m.type, WP_MATERIAL_PLASTIC)) {
        /* the diffuse lobe's (the delta lobe has no density to sample lights by) */
        lane_int is_plastic = m.type == WP_MATERIAL_PLASTIC;
        vec3 f = plastic_eval(m.plastic, v.ns, v.wo, wi);
        b.throughput_f = v3_select(is_plastic, v3_mul(throughput, f), b.throughput_f);
        b.pdf = is_plastic ? plastic_pdf(m.plastic, v.ns, v.wo, wi) : b.pdf;
    }
#endif
#ifdef WP_HAS_ROUGH_PLASTIC
    if (lanes_have_kind(m.type, WP_MATERIAL_ROUGH_PLASTIC)) {
        lane_int is_rough = m.type == WP_MATERIAL_ROUGH_PLASTIC;
        vec3 f = roughplastic_eval(m.roughplastic, v.roughplastic_table, v.ns, v.wo, wi);
        b.throughput_f = v3_select(is_rough, v3_mul(throughput, f), b.throughput_f);
        b.pdf = is_rough ? roughplastic_pdf(m.roughplastic, v.roughplastic_table, v.ns, v.wo, wi) : b.pdf;
    }
#endif
#ifdef WP_PERTURBS_NORMALS
    b.throughput_f = v3_scale(b.throughput_f, normal_map_terminator(v.terminator_alpha2, v.ns_unperturbed, wi));
#endif
#ifdef WP_HAS_MASK
    b.throughput_f = v3_scale(b.throughput_f, m.opacity);
    b.pdf = b.pdf * m.opacity;
#endif
    return b;
}

/* Whether vertex v's material transmits light through a lobe of finite
 * density: next-event estimation then samples lights on both sides. */
WP_VERTEX_FN lane_int vertex_transmits(Vertex v) {
#ifdef WP_HAS_ROUGH_DIELECTRIC
    return v.material.type == WP_MATERIAL_ROUGH_DIELECTRIC;
#else
    return 0;
#endif
}

/* Whether vertex v's material has a lobe of finite density (next-event
 * estimation samples a light there). */
WP_VERTEX_FN lane_int vertex_is_non_specular(Vertex v) {
    lane_int non_specular = 0;
#ifdef WP_HAS_DIFFUSE
    non_specular = non_specular || v.material.type == WP_MATERIAL_DIFFUSE;
#endif
#ifdef WP_HAS_ROUGH_CONDUCTOR
    non_specular = non_specular || v.material.type == WP_MATERIAL_ROUGH_CONDUCTOR;
#endif
#ifdef WP_HAS_PLASTIC
    non_specular = non_specular || v.material.type == WP_MATERIAL_PLASTIC; /* its diffuse lobe */
#endif
#ifdef WP_HAS_ROUGH_PLASTIC
    non_specular = non_specular || v.material.type == WP_MATERIAL_ROUGH_PLASTIC;
#endif
    non_specular = non_specular || vertex_transmits(v);
    return non_specular;
}

#ifdef WP_SPPM
/* Whether SPPM's camera pass makes its visible point at vertex v, whose
 * BSDF sample is `scattered`: at a non-specular material, and at a plastic
 * where the sample chose its base (the coat's delta lobe goes on as a
 * specular bounce, as path tracing takes it). */
WP_VERTEX_FN lane_int vertex_is_visible_point(Vertex v, BsdfSample scattered) {
    lane_int visible = vertex_is_non_specular(v);
#ifdef WP_HAS_PLASTIC
    visible = visible && !(v.material.type == WP_MATERIAL_PLASTIC && scattered.specular != 0u);
#endif
    return visible;
}

/* The weight a visible point at vertex v keeps from its camera path of
 * throughput `throughput`, which the gather multiplies by f: at a diffuse
 * vertex times the albedo (textured where it is: diffuse_eval then takes
 * it, photon_deposit), at a plastic's base over the probability with which
 * the sample chose it (plastic_base_throughput), else the throughput. */
WP_VERTEX_FN vec3 visible_point_weight(Vertex v, vec3 throughput) {
    vec3 weight = throughput;
#ifdef WP_HAS_PLASTIC
    weight = v3_select(v.material.type == WP_MATERIAL_PLASTIC,
                       plastic_base_throughput(v.material.plastic, v.ns, v.wo, throughput), weight);
#endif
#if defined(WP_HAS_DIFFUSE) && defined(WP_HAS_GLOSSY)
    weight = v3_select(v.material.type == WP_MATERIAL_DIFFUSE, v3_mul(throughput, v.material.albedo), weight);
#elif defined(WP_HAS_DIFFUSE)
    weight = v3_mul(throughput, v.material.albedo); /* every visible point is diffuse */
#endif
    return weight;
}
#endif
#endif

#ifdef WP_NEE
/* A point sampled on light `light` as seen from x, with its material and
 * magnitude (light_shape). u and v place the point; u_triangle picks a mesh
 * light's triangle. */
typedef struct {
    LightSample sample;
    lane_uint material;
    real magnitude;
} LightPoint;

WP_FN LightPoint sample_light_shape(WP_SCENE_PARAMS, lane_uint light, vec3 x, real u, real v, real u_triangle) {
    LightShape l = light_shape(WP_SCENE_ARGS, light, u_triangle);
    LightPoint p;
    p.sample.point = p.sample.normal = make_vec3(REAL(0.0), REAL(0.0), REAL(0.0));
    p.sample.pdf_solid_angle = REAL(0.0);
    p.material = l.material;
    p.magnitude = l.magnitude;
#ifdef WP_HAS_SPHERE_LIGHTS
    p.sample = select_light_sample(l.type == WP_SHAPE_SPHERE, sample_sphere(l.center, l.radius, x, u, v), p.sample);
#endif
#ifdef WP_HAS_QUAD_LIGHTS
    p.sample = select_light_sample(l.type == WP_SHAPE_QUAD, sample_quad(l.corner, l.edge1, l.edge2, x, u, v), p.sample);
#endif
#ifdef WP_HAS_MESH_LIGHTS
    p.sample = select_light_sample(l.type == WP_SHAPE_TRIANGLE, sample_triangle(l.p0, l.p1, l.p2, l.mesh_area, x, u, v),
                                   p.sample);
#endif
    return p;
}

#ifdef WP_HAS_NON_SPECULAR
/* Samples one light for vertex v on a path of throughput `throughput` into
 * *direct (direct_light); returns where it carries light. */
WP_VERTEX_FN lane_int sample_direct_light(WP_SCENE_PARAMS, lane_uint pixel, lane_uint sample, lane_uint bounce,
                                          Vertex v, vec3 throughput, DirectLight *direct) {
    uint seed = scene->seed;
    lane_uint light = select_light(light_cdf, LIGHT_COUNT,
                                   camera_uniform(seed, pixel, sample, bounce, DIM_LIGHT_SELECT, WP_USES_SOBOL));
#ifdef WP_HAS_MESH_LIGHTS
    real u_triangle = camera_uniform(seed, pixel, sample, bounce, DIM_LIGHT_TRIANGLE, WP_USES_SOBOL);
#else
    real u_triangle = REAL(0.0);
#endif
    CameraPair point = camera_pair(seed, pixel, sample, bounce, DIM_LIGHT_U, WP_USES_SOBOL);
    LightPoint p = sample_light_shape(WP_SCENE_ARGS, light, v.surface.point, point.u, point.v, u_triangle);
    Emission emitter = emission_at(materials, p.material);
    vec3 wi = direct_light_direction(p.sample, v.surface.point);
#ifdef WP_HAS_CONSTANT_ENVIRONMENT
    lane_int environment = is_environment_light(WP_SCENE_ARGS, light);
    wi = v3_select(environment, sample_uniform_sphere(point.u, point.v), wi);
#endif
#ifdef WP_HAS_ENVIRONMENT_MAP
    lane_int environment = is_environment_light(WP_SCENE_ARGS, light);
    EnvironmentSample sky = environment_sample(scene_environment_map(WP_SCENE_ARGS), environment_map, point.u, point.v);
    wi = v3_select(environment, sky.direction, wi);
#endif
#ifdef WP_HAS_DIRECTIONAL_LIGHTS
    lane_int directional = (SCENE_FIELD(lights, light, shape) >> WP_SHAPE_TYPE_SHIFT) == WP_LIGHT_DIRECTIONAL;
    wi = v3_select(directional, SCENE_FIELD(lights, light, to_light), wi);
#endif
#ifdef WP_HAS_POINT_LIGHTS
    lane_int point_light = (SCENE_FIELD(lights, light, shape) >> WP_SHAPE_TYPE_SHIFT) == WP_LIGHT_POINT;
    vec3 light_position = SCENE_FIELD(lights, light, position);
    wi = v3_select(point_light, v3_normalize(v3_sub(light_position, v.surface.point)), wi);
#endif
    BsdfValue bsdf = vertex_bsdf_value(v, wi, throughput);
    real selection_pmf = light_selection_pmf(light_cdf, light);
    *direct = direct_light(v.surface.point, v.surface.error, v.nf, v.ns, vertex_transmits(v), wi, bsdf.throughput_f,
                           bsdf.pdf, p.sample, p.magnitude, selection_pmf, emitter.emission, emitter.two_sided,
                           WP_USES_MIS, WP_USES_SHADING_NORMALS);
#ifdef WP_HAS_CONSTANT_ENVIRONMENT
    DirectLight distant =
        distant_direct_light(v.surface.point, v.surface.error, v.nf, v.ns, vertex_transmits(v), wi, bsdf.throughput_f,
                             bsdf.pdf, light_sample_pdf(selection_pmf, uniform_sphere_pdf()),
                             uniform_vec3(scene->background), WP_USES_MIS, WP_USES_SHADING_NORMALS);
    *direct = select_direct_light(environment, distant, *direct);
#endif
#ifdef WP_HAS_ENVIRONMENT_MAP
    DirectLight mapped = distant_direct_light(v.surface.point, v.surface.error, v.nf, v.ns, vertex_transmits(v), wi,
                                              bsdf.throughput_f, bsdf.pdf, light_sample_pdf(selection_pmf, sky.pdf),
                                              sky.radiance, WP_USES_MIS, WP_USES_SHADING_NORMALS);
    *direct = select_direct_light(environment, mapped, *direct);
#endif
#ifdef WP_HAS_DIRECTIONAL_LIGHTS
    /* a delta light: no multiple importance sampling, its density the selection probability */
    DirectLight sun =
        distant_direct_light(v.surface.point, v.surface.error, v.nf, v.ns, vertex_transmits(v), wi, bsdf.throughput_f,
                             bsdf.pdf, selection_pmf, SCENE_FIELD(lights, light, emitted), 0, WP_USES_SHADING_NORMALS);
    *direct = select_direct_light(directional, sun, *direct);
#endif
#ifdef WP_HAS_POINT_LIGHTS
    /* a delta light too */
    real falloff = spot_falloff(SCENE_FIELD(lights, light, axis), v3_neg(wi), SCENE_FIELD(lights, light, cos_cutoff),
                                SCENE_FIELD(lights, light, cos_beam), SCENE_FIELD(lights, light, cutoff_angle),
                                SCENE_FIELD(lights, light, inv_transition_width));
    DirectLight bulb = point_direct_light(
        v.surface.point, v.surface.error, v.nf, v.ns, vertex_transmits(v), wi, bsdf.throughput_f, selection_pmf,
        light_position, v3_scale(SCENE_FIELD(lights, light, emitted), falloff), WP_USES_SHADING_NORMALS);
    *direct = select_direct_light(point_light, bulb, *direct);
#endif
    return direct->carries;
}

/* The light sample of next-event estimation at vertex v, where the path
 * `continues` past its emission (vertex_ends_path) and the material is
 * non-specular: returns where it has a shadow ray to trace, its
 * contribution in *direct. */
WP_VERTEX_FN lane_int vertex_light_sample(WP_SCENE_PARAMS, lane_int continues, Vertex v, lane_uint pixel,
                                          lane_uint sample, lane_uint bounce, vec3 throughput, DirectLight *direct) {
#ifdef WP_VERTEX_MAY_NOT_SHADE
    continues = continues && v.shades;
#endif
    return continues && vertex_is_non_specular(v) &&
           sample_direct_light(WP_SCENE_ARGS, pixel, sample, bounce, v, throughput, direct);
}
#endif

/* Where a light sample's shadow ray, cast where `casts`, reaches its light:
 * nothing hit before its distance (traced here, on the device). */
WP_FN lane_int shadow_ray_reaches_light(WP_SCENE_PARAMS, lane_int casts, ShadowRay shadow) {
    lane_int lit = casts;
    if (lanes_any(casts)) lit = casts && !any_hit(WP_SCENE_ARGS, shadow.origin, shadow.direction, shadow.distance);
    return lit;
}
#endif

/* The path's radiance with a light sample's contribution added where its
 * shadow ray reached the light (`lit`); a non-finite sum is dropped and
 * counted in *dropped (add_finite). */
WP_FN vec3 add_light_sample(vec3 radiance, lane_int lit, vec3 contribution, lane_uint *dropped) {
    lane_uint not_finite = 0u;
    vec3 sum = add_finite(radiance, contribution, &not_finite);
    *dropped += lit ? not_finite : (lane_uint)0u;
    return v3_select(lit, sum, radiance);
}

/* The random numbers of a BSDF sample, of the material kinds compiled in:
 * at bounce `bounce` of camera sample s of pixel px, and of photon `photon`
 * of SPPM iteration `iteration` (shared/rng.h). */
WP_FN BsdfRandom camera_bsdf_random(uint seed, lane_uint px, lane_uint s, lane_uint bounce) {
    BsdfRandom random;
    random.lobe = random.u = random.v = REAL(0.0);
#ifdef WP_HAS_LOBE_CHOICE
    random.lobe = camera_uniform(seed, px, s, bounce, DIM_BSDF_LOBE, WP_USES_SOBOL);
#endif
#ifdef WP_HAS_NON_SPECULAR
    CameraPair direction = camera_pair(seed, px, s, bounce, DIM_BSDF_U, WP_USES_SOBOL);
    random.u = direction.u;
    random.v = direction.v;
#endif
    return random;
}

WP_FN BsdfRandom photon_bsdf_random(uint seed, uint iteration, lane_uint photon, lane_uint bounce) {
    BsdfRandom random;
    random.lobe = random.u = random.v = REAL(0.0);
#ifdef WP_HAS_LOBE_CHOICE
    random.lobe = photon_uniform(seed, iteration, photon, bounce, DIM_PHOTON_BSDF_LOBE);
#endif
#ifdef WP_HAS_NON_SPECULAR
    random.u = photon_uniform(seed, iteration, photon, bounce, DIM_PHOTON_BSDF_U);
    random.v = photon_uniform(seed, iteration, photon, bounce, DIM_PHOTON_BSDF_V);
#endif
    return random;
}

/* BSDF sampling with `random` at vertex v, reached along d, for its
 * material's kind (every kind that some lane has is sampled; each lane keeps its
 * material's), on a path that carries `transport` (WP_TRANSPORT_*). */
WP_VERTEX_FN BsdfSample scatter_vertex(Vertex v, vec3 d, BsdfRandom random, uint transport) {
    Material m = v.material;
    vec3 wo = v3_neg(d);
    BsdfSample scattered = no_bsdf_sample();
#ifdef WP_HAS_MASK
    lane_int passes = mask_passes(m.opacity, random.lobe);
    random.lobe = mask_nested_lobe(m.opacity, random.lobe);
#endif
#ifdef WP_HAS_DIFFUSE
    if (lanes_have_kind(m.type, WP_MATERIAL_DIFFUSE))
        scattered = select_bsdf_sample(m.type == WP_MATERIAL_DIFFUSE,
                                       diffuse_sample(m.albedo, v.nf, v.ns, random.u, random.v,
                                                      WP_USES_UNIFORM_HEMISPHERE, WP_USES_SHADING_NORMALS),
                                       scattered);
#endif
#ifdef WP_HAS_MIRROR
    if (lanes_have_kind(m.type, WP_MATERIAL_MIRROR))
        scattered =
            select_bsdf_sample(m.type == WP_MATERIAL_MIRROR,
                               mirror_sample(m.reflectance, wo, v.nf, v.ns, WP_USES_SHADING_NORMALS), scattered);
#endif
#ifdef WP_HAS_GLASS
    if (lanes_have_kind(m.type, WP_MATERIAL_GLASS))
        scattered = select_bsdf_sample(
            m.type == WP_MATERIAL_GLASS,
            glass_sample(m.ior, v.front, wo, v.nf, v.ns, random.lobe, transport, WP_USES_SHADING_NORMALS), scattered);
#endif
#ifdef WP_HAS_CONDUCTOR
    if (lanes_have_kind(m.type, WP_MATERIAL_CONDUCTOR))
        scattered = select_bsdf_sample(
            m.type == WP_MATERIAL_CONDUCTOR,
            conductor_sample(m.eta, m.k, m.specular_reflectance, wo, v.nf, v.ns, WP_USES_SHADING_NORMALS), scattered);
#endif
#ifdef WP_HAS_ROUGH_DIELECTRIC
    if (lanes_have_kind(m.type, WP_MATERIAL_ROUGH_DIELECTRIC))
        scattered =
            select_bsdf_sample(m.type == WP_MATERIAL_ROUGH_DIELECTRIC,
                               roughdielectric_sample(m.microfacet, m.ior, v.front, v.nf,
                                                      vertex_microfacet_frame(v, roughdielectric_frame(v.ns, v.front)),
                                                      wo, random, transport, WP_USES_SHADING_NORMALS),
                               scattered);
#endif
#ifdef WP_HAS_THIN_DIELECTRIC
    if (lanes_have_kind(m.type, WP_MATERIAL_THIN_DIELECTRIC))
        scattered = select_bsdf_sample(
            m.type == WP_MATERIAL_THIN_DIELECTRIC,
            thindielectric_sample(m.ior, wo, v.nf, v.ns, random.lobe, WP_USES_SHADING_NORMALS), scattered);
#endif
#ifdef WP_HAS_ROUGH_CONDUCTOR
    if (lanes_have_kind(m.type, WP_MATERIAL_ROUGH_CONDUCTOR))
        scattered = select_bsdf_sample(m.type == WP_MATERIAL_ROUGH_CONDUCTOR,
                                       roughconductor_sample(m.microfacet, m.eta, m.k, m.specular_reflectance, v.nf,
                                                             vertex_microfacet_frame(v, frame_from_normal(v.ns)), wo,
                                                             random.u, random.v, WP_USES_SHADING_NORMALS),
                                       scattered);
#endif
#ifdef WP_HAS_PLASTIC
    scattered =
        select_bsdf_sample(m.type == WP_MATERIAL_PLASTIC,
                           plastic_sample(m.plastic, v.nf, v.ns, wo, random, WP_USES_SHADING_NORMALS), scattered);
#endif
#ifdef WP_HAS_ROUGH_PLASTIC
    if (lanes_have_kind(m.type, WP_MATERIAL_ROUGH_PLASTIC))
        scattered = select_bsdf_sample(
            m.type == WP_MATERIAL_ROUGH_PLASTIC,
            roughplastic_sample(m.roughplastic, v.roughplastic_table, v.nf, v.ns, wo, random, WP_USES_SHADING_NORMALS),
            scattered);
#endif
#ifdef WP_VERTEX_MAY_NOT_SHADE
    scattered.valid = scattered.valid && v.shades;
#endif
#ifdef WP_PERTURBS_NORMALS
    scattered.weight =
        v3_scale(scattered.weight, normal_map_terminator(v.terminator_alpha2, v.ns_unperturbed, scattered.direction));
#endif
#ifdef WP_HAS_MASK
    scattered = mask_sample(m.opacity, passes, scattered, d, v.nf);
#endif
    return scattered;
}

/* Where a path goes from vertex v: its BSDF sample, the next ray and
 * throughput, and whether it goes on at all. */
typedef struct {
    BsdfSample scattered;
    vec3 origin;         /* of the next ray (its direction: scattered.direction) */
    vec3 throughput;     /* times the sample's weight, over the survival probability where the roulette played */
    real eta_scale;      /* times the sample's eta^2 */
    lane_int continues;  /* a valid sample, the roulette survived and a finite throughput */
    lane_uint nonfinite; /* 1 where a valid sample survived with a non-finite throughput (which ends the path) */
} PathStep;

/* BSDF sampling at bounce `bounce` of vertex v, reached along d by a path of
 * throughput `throughput` and eta_scale `eta_scale` (roulette_survival),
 * then Russian roulette (russian_roulette) once the depth after it reaches
 * rr_depth. */
WP_VERTEX_FN PathStep step_from_vertex(Vertex v, vec3 d, vec3 throughput, real eta_scale, uint seed, lane_uint px,
                                       lane_uint s, lane_uint bounce, uint rr_depth) {
    PathStep step;
    step.scattered = scatter_vertex(v, d, camera_bsdf_random(seed, px, s, bounce), WP_TRANSPORT_RADIANCE);
    step.origin = offset_ray_origin(v.surface.point, step.scattered.leave_side, v.surface.error);
    step.eta_scale = eta_scale * step.scattered.eta_squared;
    RouletteOutcome roulette =
        russian_roulette(v3_mul(throughput, step.scattered.weight), step.eta_scale, bounce + 1u >= rr_depth,
                         camera_uniform(seed, px, s, bounce, DIM_ROULETTE, WP_USES_SOBOL));
    step.throughput = roulette.throughput;
    lane_uint nonfinite = 0u;
    lane_int finite = throughput_is_finite(step.throughput, &nonfinite);
    lane_int survives = step.scattered.valid && roulette.survives;
    step.continues = survives && finite;
    step.nonfinite = survives ? nonfinite : (lane_uint)0u;
    return step;
}

#endif
