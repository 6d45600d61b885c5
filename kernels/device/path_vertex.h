/* The work at one path vertex, shared by the wavefront's stage kernels and
 * the megakernel so that both compute exactly the reference's estimator
 * (docs/architecture.md, "Conventions"): the camera ray, emission seen at a
 * hit, the light sample of next-event estimation, BSDF sampling and Russian
 * roulette. Written for any number of lanes (shared/prelude.h): every choice
 * is a select, so a lane computes what every other lane's case needs and
 * keeps its own. */
#ifndef WP_DEVICE_PATH_VERTEX_H
#define WP_DEVICE_PATH_VERTEX_H

#include "shared/offset.h"
#include "shared/prelude.h"
#include "shared/rng.h"
#include "shared/sampling.h"
#include "shared/triangle.h"
#if defined(WP_HAS_MIRROR) || defined(WP_HAS_GLASS)
#include "shared/fresnel.h"
#endif
#ifndef WP_HAS_GLASS
/* Without glass the dielectric code must not be compiled in: any use is a build error. */
#pragma GCC poison fresnel_dielectric refract_direction
#endif
#include "device/features.h"
#include "device/lane_memory.h"
#include "device/light_ranges.h"
#include "device/parameters.h"
#include "device/surface.h"

/* Whether `direction` leaves on the side `normal` points to. Shading
 * normals bend directions but only the geometric normal says where a ray
 * really goes: a direction sampled or reflected about ns that points into the
 * surface as nf sees it, or a ray arriving from behind ns, ends the path (as
 * in Mitsuba 3 and pbrt-v4's treatment of the two normals): continuing would
 * leak light through the surface or shade from the wrong side. Without
 * shading normals ns is nf and every such test passes. */
WP_FN lane_int same_side(vec3 direction, vec3 normal) {
#ifdef WP_HAS_SHADING_NORMALS
    return v3_dot(direction, normal) > REAL(0.0);
#else
    return 1;
#endif
}

/* The camera ray direction of sample s of pixel px (the camera is at the origin). */
WP_FN vec3 camera_ray_direction(__global const SceneHeader *scene, lane_uint px, lane_uint s) {
    lane_uint x = px % scene->width, y = px / scene->width;
    real u0 = rng_uniform(scene->seed, px, s, 0u, DIM_FILM_X);
    real u1 = rng_uniform(scene->seed, px, s, 0u, DIM_FILM_Y);
    return camera_direction(uniform_vec3(scene->camera_right), uniform_vec3(scene->camera_up),
                            uniform_vec3(scene->camera_forward), scene->tan_half_fov_y, scene->aspect,
                            (TO_REAL(x) + u0) / (real)scene->width, (TO_REAL(y) + u1) / (real)scene->height);
}

/* Emission the path adds at a hit where the material emits towards the ray
 * (or is two-sided): throughput x emission x `weight`, the share of the
 * emission_weight below. */
WP_FN vec3 emission_seen(Material m, lane_int front, real weight, vec3 throughput) {
    lane_int emits = m.emission.x > REAL(0.0) || m.emission.y > REAL(0.0) || m.emission.z > REAL(0.0);
    lane_int seen = emits && (m.two_sided || front) && weight > REAL(0.0);
    return v3_select(seen, v3_scale(v3_mul(throughput, m.emission), weight),
                     make_vec3(REAL(0.0), REAL(0.0), REAL(0.0)));
}

#ifdef WP_MIS
/* The solid-angle density with which next-event estimation from `reference`
 * samples `point` (geometric normal `normal`) of light `light`: its
 * selection probability times the density of its point sampling
 * (sample_light_shape). */
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
        real area = v3_length(v3_cross(SCENE_FIELD(quads, i, edge1), SCENE_FIELD(quads, i, edge2)));
        real quad_pdf = area_to_solid_angle_pdf(REAL(1.0) / area, reference, point, normal);
        pdf = is_quad ? quad_pdf : pdf;
    }
#endif
#ifdef WP_HAS_MESH_LIGHTS
    {
        real mesh_pdf = area_to_solid_angle_pdf(REAL(1.0) / SCENE_FIELD(lights, light, area), reference, point, normal);
        pdf = type == WP_SHAPE_TRIANGLE ? mesh_pdf : pdf;
    }
#endif
    return light_selection_pmf(light_cdf, light) * pdf;
}

/* The light an emitting hit `shape` belongs to: a scan of the light table,
 * whose length is a compile-time constant in small scenes; a triangle's light
 * is its mesh's. */
WP_FN lane_uint light_of_shape(WP_SCENE_PARAMS, lane_uint shape) {
#ifdef WP_HAS_MESH_LIGHTS
    lane_int is_mesh = shape >> WP_SHAPE_TYPE_SHIFT == WP_SHAPE_TRIANGLE;
    lane_uint mesh = SCENE_FIELD(triangles, is_mesh ? shape & WP_SHAPE_INDEX_MASK : (lane_uint)0u, mesh);
#endif
    lane_uint light = 0u;
    for (uint i = 0u; i < LIGHT_COUNT; ++i) {
        lane_int is_this = lights[i].shape == shape;
#ifdef WP_HAS_MESH_LIGHTS
        is_this = is_this ||
                  (is_mesh && lights[i].shape >> WP_SHAPE_TYPE_SHIFT == WP_SHAPE_TRIANGLE && lights[i].mesh == mesh);
#endif
        light = is_this ? (lane_uint)i : light;
    }
    return light;
}
#endif

/* The share of the emission at vertex v (reached along the ray from
 * `origin`) that the path counts: all of it after the camera or a specular
 * vertex, whose direction no light sample could have chosen, and at every
 * hit without next-event estimation (pure BSDF sampling); after a diffuse
 * vertex with next-event estimation, none (the light sample counts it) or,
 * with multiple importance sampling, the power heuristic's share of BSDF
 * sampling, whose density `bsdf_pdf` the bounce recorded. */
WP_FN real emission_weight(WP_SCENE_PARAMS, lane_uint shape, vec3 origin, Vertex v, lane_int after_specular,
                           real bsdf_pdf) {
#if defined(WP_MIS)
    real light_pdf =
        light_point_pdf(WP_SCENE_ARGS, light_of_shape(WP_SCENE_ARGS, shape), origin, v.surface.point, v.surface.normal);
    return after_specular ? REAL(1.0) : power_heuristic(bsdf_pdf, light_pdf);
#elif defined(WP_NEE)
    return after_specular ? REAL(1.0) : REAL(0.0);
#else
    return REAL(1.0);
#endif
}

/* The solid-angle density of scatter_diffuse's direction at cosine
 * `cos_theta` from the shading normal. */
WP_FN real diffuse_pdf(real cos_theta) {
#ifdef WP_UNIFORM_HEMISPHERE
    return uniform_hemisphere_pdf();
#else
    return cosine_hemisphere_pdf(cos_theta);
#endif
}

#ifdef WP_NEE
/* A point sampled on light `light`, with its material and magnitude
 * (offset.h). Every light kind in the scene is sampled and each lane keeps
 * its own kind's; a lane whose light is of another kind reads that kind's
 * arrays at index 0. u and v place the point; u_triangle picks a mesh
 * light's triangle in proportion to area. */
typedef struct {
    LightSample sample;
    lane_uint material;
    real magnitude;
} LightPoint;

WP_FN LightPoint select_light_point(lane_int choose_a, LightPoint a, LightPoint b) {
    LightPoint p;
    p.sample = select_light_sample(choose_a, a.sample, b.sample);
    p.material = choose_a ? a.material : b.material;
    p.magnitude = choose_a ? a.magnitude : b.magnitude;
    return p;
}

WP_FN LightPoint sample_light_shape(WP_SCENE_PARAMS, lane_uint light, vec3 x, real u, real v, real u_triangle) {
    lane_uint shape = SCENE_FIELD(lights, light, shape);
    lane_uint index = shape & WP_SHAPE_INDEX_MASK, type = shape >> WP_SHAPE_TYPE_SHIFT;
    LightPoint p, kind;
    p.sample.point = p.sample.normal = make_vec3(REAL(0.0), REAL(0.0), REAL(0.0));
    p.sample.pdf_solid_angle = REAL(0.0);
    p.material = 0u;
    p.magnitude = REAL(0.0);
#ifdef WP_HAS_SPHERE_LIGHTS
    {
        lane_int is_sphere = type == WP_SHAPE_SPHERE;
        lane_uint i = is_sphere ? index : (lane_uint)0u;
        vec3 center = SCENE_FIELD(spheres, i, center);
        real radius = SCENE_FIELD(spheres, i, radius);
        kind.sample = sample_sphere(center, radius, x, u, v);
        kind.material = SCENE_FIELD(spheres, i, material);
        kind.magnitude = sphere_magnitude(center, radius);
        p = select_light_point(is_sphere, kind, p);
    }
#endif
#ifdef WP_HAS_QUAD_LIGHTS
    {
        lane_int is_quad = type == WP_SHAPE_QUAD;
        lane_uint i = is_quad ? index : (lane_uint)0u;
        vec3 corner = SCENE_FIELD(quads, i, corner), edge1 = SCENE_FIELD(quads, i, edge1);
        vec3 edge2 = SCENE_FIELD(quads, i, edge2);
        kind.sample = sample_quad(corner, edge1, edge2, x, u, v);
        kind.material = SCENE_FIELD(quads, i, material);
        kind.magnitude = quad_magnitude(corner, edge1, edge2);
        p = select_light_point(is_quad, kind, p);
    }
#endif
#ifdef WP_HAS_MESH_LIGHTS
    {
        lane_int is_mesh = type == WP_SHAPE_TRIANGLE;
        lane_uint first = is_mesh ? index : (lane_uint)0u;
        lane_uint count = is_mesh ? SCENE_FIELD(lights, light, triangle_count) : (lane_uint)0u;
        lane_uint k = select_light_in_range(light_triangle_cdf, first, count, u_triangle);
        vec3 p0 = SCENE_FIELD(light_triangles, k, p0), p1 = SCENE_FIELD(light_triangles, k, p1);
        vec3 p2 = SCENE_FIELD(light_triangles, k, p2);
        kind.sample = sample_triangle(p0, p1, p2, SCENE_FIELD(lights, light, area), x, u, v);
        kind.material = SCENE_FIELD(light_triangles, k, material);
        kind.magnitude = triangle_magnitude(p0, p1, p2);
        p = select_light_point(is_mesh, kind, p);
    }
#endif
    return p;
}

/* Samples one light for the diffuse vertex (x, nf, ns); returns where the
 * sample carries light, with the shadow ray and the contribution it adds when
 * unoccluded (the outputs hold no ray elsewhere). */
WP_FN lane_int sample_direct_light(WP_SCENE_PARAMS, lane_uint pixel, lane_uint sample, lane_uint bounce, vec3 x,
                                   real x_error, vec3 nf, vec3 ns, vec3 weight, vec3 *shadow_origin,
                                   vec3 *shadow_direction, real *shadow_distance, vec3 *contribution) {
    uint seed = scene->seed;
    lane_uint light = select_light(light_cdf, LIGHT_COUNT, rng_uniform(seed, pixel, sample, bounce, DIM_LIGHT_SELECT));
    real pmf = light_selection_pmf(light_cdf, light);
#ifdef WP_HAS_MESH_LIGHTS
    real u_triangle = rng_uniform(seed, pixel, sample, bounce, DIM_LIGHT_TRIANGLE);
#else
    real u_triangle = REAL(0.0);
#endif
    LightPoint p = sample_light_shape(WP_SCENE_ARGS, light, x, rng_uniform(seed, pixel, sample, bounce, DIM_LIGHT_U),
                                      rng_uniform(seed, pixel, sample, bounce, DIM_LIGHT_V), u_triangle);
    LightSample ls = p.sample;
    Material emitter = material_at(materials, p.material);
    vec3 wi = v3_normalize(v3_sub(ls.point, x));
    real cos_surface = v3_dot(wi, ns);
    lane_int light_faces_x = v3_dot(ls.normal, v3_sub(x, ls.point)) > REAL(0.0);
    lane_int carries = ls.pdf_solid_angle != REAL(0.0) && cos_surface > REAL(0.0) && same_side(wi, nf) &&
                       (emitter.two_sided || light_faces_x);
    vec3 from = offset_ray_origin(x, nf, x_error);
    vec3 to = offset_ray_origin(ls.point, v3_select(light_faces_x, ls.normal, v3_neg(ls.normal)),
                                shadow_target_error(x, ls.point, p.magnitude));
    vec3 along = v3_sub(to, from);
    *shadow_distance = v3_length(along);
    *shadow_direction = v3_div(along, *shadow_distance);
    *shadow_origin = from;
    real light_pdf = ls.pdf_solid_angle * pmf;
    /* in the reference's order of operations */
    *contribution = v3_div(v3_scale(v3_mul(v3_scale(weight, WP_INV_PI), emitter.emission), cos_surface), light_pdf);
#ifdef WP_MIS
    *contribution = v3_scale(*contribution, power_heuristic(light_pdf, diffuse_pdf(cos_surface)));
#endif
    return carries;
}
#endif

typedef struct {
    vec3 direction;
    vec3 weight;      /* throughput factor */
    vec3 leave_side;  /* geometric normal on the side the new ray leaves into */
    real pdf;         /* solid-angle density of a diffuse direction (0 for specular ones, whose density is a delta) */
    real eta_squared; /* eta^2 of a refraction, whose weight is 1/eta^2; else 1 (roulette_survival) */
    lane_uint specular;
    lane_int valid; /* the direction leaves on leave_side (same_side): else the path ends */
} Scattered;

WP_FN Scattered select_scattered(lane_int choose_a, Scattered a, Scattered b) {
    Scattered s;
    s.direction = v3_select(choose_a, a.direction, b.direction);
    s.weight = v3_select(choose_a, a.weight, b.weight);
    s.leave_side = v3_select(choose_a, a.leave_side, b.leave_side);
    s.pdf = choose_a ? a.pdf : b.pdf;
    s.eta_squared = choose_a ? a.eta_squared : b.eta_squared;
    s.specular = choose_a ? a.specular : b.specular;
    s.valid = choose_a ? a.valid : b.valid;
    return s;
}

#ifdef WP_HAS_DIFFUSE
WP_FN Scattered scatter_diffuse(Material m, vec3 nf, vec3 ns, real u, real v) {
    Scattered s;
#ifdef WP_UNIFORM_HEMISPHERE
    vec3 in_frame = sample_uniform_hemisphere(u, v);       /* `local` is an OpenCL keyword */
    s.weight = v3_scale(m.albedo, REAL(2.0) * in_frame.z); /* albedo/pi * cos / (1/(2 pi)) */
#else
    vec3 in_frame = sample_cosine_hemisphere(u, v);
    s.weight = m.albedo;
#endif
    s.direction = frame_to_world(frame_from_normal(ns), in_frame);
    s.leave_side = nf;
    s.pdf = diffuse_pdf(in_frame.z);
    s.eta_squared = REAL(1.0);
    s.specular = 0u;
    s.valid = same_side(s.direction, nf);
    return s;
}
#endif

#ifdef WP_HAS_MIRROR
WP_FN Scattered scatter_mirror(Material m, vec3 d, vec3 nf, vec3 ns) {
    Scattered s;
    s.direction = reflect_direction(d, ns);
    s.weight = m.reflectance;
    s.leave_side = nf;
    s.pdf = REAL(0.0);
    s.eta_squared = REAL(1.0);
    s.specular = 1u;
    s.valid = same_side(v3_neg(d), ns) && same_side(s.direction, nf);
    return s;
}
#endif

#ifdef WP_HAS_GLASS
/* Fresnel chooses reflection or refraction; refraction scales radiance by 1/eta^2. */
WP_FN Scattered scatter_glass(Material m, vec3 d, vec3 nf, vec3 ns, lane_int entering, real u_lobe) {
    real eta = entering ? m.ior : REAL(1.0) / m.ior;
    real reflectance = fresnel_dielectric(-v3_dot(d, ns), eta);
    vec3 refracted;
    lane_int refracts = u_lobe >= reflectance && refract_direction(d, ns, eta, &refracted);
    Scattered s;
    s.specular = 1u;
    s.pdf = REAL(0.0);
    s.eta_squared = refracts ? eta * eta : REAL(1.0);
    s.direction = v3_select(refracts, refracted, reflect_direction(d, ns));
    s.weight = v3_div(make_vec3(REAL(1.0), REAL(1.0), REAL(1.0)), refracts ? eta * eta : REAL(1.0));
    s.leave_side = v3_select(refracts, v3_neg(nf), nf);
    s.valid = same_side(v3_neg(d), ns) && same_side(s.direction, s.leave_side);
    return s;
}
#endif

/* BSDF sampling at bounce `bounce` of vertex v, reached along d, for its
 * material's type (every kind in the scene is sampled; each lane keeps its
 * material's). */
WP_FN Scattered scatter_vertex(Vertex v, vec3 d, uint seed, lane_uint px, lane_uint s, lane_uint bounce) {
    Material m = v.material;
    Scattered scattered;
    scattered.direction = scattered.weight = scattered.leave_side = make_vec3(REAL(0.0), REAL(0.0), REAL(0.0));
    scattered.pdf = REAL(0.0);
    scattered.eta_squared = REAL(1.0);
    scattered.specular = 0u;
    scattered.valid = 0;
#ifdef WP_HAS_DIFFUSE
    scattered = select_scattered(m.type == WP_MATERIAL_DIFFUSE,
                                 scatter_diffuse(m, v.nf, v.ns, rng_uniform(seed, px, s, bounce, DIM_BSDF_U),
                                                 rng_uniform(seed, px, s, bounce, DIM_BSDF_V)),
                                 scattered);
#endif
#ifdef WP_HAS_MIRROR
    scattered = select_scattered(m.type == WP_MATERIAL_MIRROR, scatter_mirror(m, d, v.nf, v.ns), scattered);
#endif
#ifdef WP_HAS_GLASS
    scattered = select_scattered(
        m.type == WP_MATERIAL_GLASS,
        scatter_glass(m, d, v.nf, v.ns, v.front, rng_uniform(seed, px, s, bounce, DIM_BSDF_LOBE)), scattered);
#endif
    return scattered;
}

/* Russian roulette once new_depth reaches rr_depth: survival probability
 * roulette_survival(T, eta_scale), and T /= survival when the path survives. */
WP_FN lane_int survives_roulette(vec3 *throughput, real eta_scale, uint seed, lane_uint px, lane_uint s,
                                 lane_uint bounce, lane_uint new_depth, uint rr_depth) {
    lane_int plays = new_depth >= rr_depth;
    real survival = roulette_survival(*throughput, eta_scale);
    lane_int survives = rng_uniform(seed, px, s, bounce, DIM_ROULETTE) < survival;
    *throughput = v3_select(plays, v3_div(*throughput, survival), *throughput);
    return !plays || survives;
}

#endif
