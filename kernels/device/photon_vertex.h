/* The work at one photon vertex (SPPM's photon stages, interface/stages.h):
 * a photon leaving a light, and what it adds to the visible points near
 * where it lands. What is computed is the shared code's (shared/photons.h,
 * shared/sppm.h, shared/photon_grid.h), which the reference calls too
 * (src/reference/photon_tracer.h, sppm_renderer.cpp); this header reads each
 * lane's scene data, as device/path_vertex.h does for camera paths. */
#ifndef WP_DEVICE_PHOTON_VERTEX_H
#define WP_DEVICE_PHOTON_VERTEX_H

#include "device/lane_memory.h"
#include "device/lanes.h"
#include "device/light_ranges.h"
#include "device/parameters.h"
#include "device/path_vertex.h"
#include "device/sppm_pixels.h"
#include "device/surface.h"
#include "shared/lights.h"
#include "shared/photon_grid.h"
#include "shared/photons.h"
#include "shared/prelude.h"
#include "shared/rng.h"
#include "shared/sppm.h"
#include "shared/triangle.h"

/* The iteration whose photon pass runs: its photons are the pass's work
 * items, iteration i's the P from i P on (P the photons per iteration). */
WP_FN uint photon_pass_iteration(__global const SceneHeader *scene, ulong pass_start) {
    return (uint)(pass_start / scene->photons);
}

/* Where a photon leaves light `light`: a point uniform by area on its shape
 * (light_shape; u, v place the point, u_triangle picks a mesh light's
 * triangle in proportion to area), with the light's area. */
typedef struct {
    AreaPoint at;
    real area;
} EmissionPoint;

WP_FN EmissionPoint select_emission_point(lane_int choose_a, EmissionPoint a, EmissionPoint b) {
    EmissionPoint p;
    p.at.point = v3_select(choose_a, a.at.point, b.at.point);
    p.at.normal = v3_select(choose_a, a.at.normal, b.at.normal);
    p.area = choose_a ? a.area : b.area;
    return p;
}

WP_FN EmissionPoint emission_point(LightShape l, real u, real v) {
    EmissionPoint p, kind;
    p.at.point = p.at.normal = make_vec3(REAL(0.0), REAL(0.0), REAL(0.0));
    p.area = REAL(0.0);
#ifdef WP_HAS_SPHERE_LIGHTS
    kind.at = sphere_point(l.center, l.radius, u, v);
    kind.area = sphere_area(l.radius);
    p = select_emission_point(l.type == WP_SHAPE_SPHERE, kind, p);
#endif
#ifdef WP_HAS_QUAD_LIGHTS
    kind.at = quad_point(l.corner, l.edge1, l.edge2, u, v);
    kind.area = quad_area(l.edge1, l.edge2);
    p = select_emission_point(l.type == WP_SHAPE_QUAD, kind, p);
#endif
#ifdef WP_HAS_MESH_LIGHTS
    kind.at = triangle_point(l.p0, l.p1, l.p2, u, v);
    kind.area = l.mesh_area;
    p = select_emission_point(l.type == WP_SHAPE_TRIANGLE, kind, p);
#endif
    return p;
}

/* Photon `photon` of SPPM iteration `iteration`, from a light chosen by
 * power (emit_photon). */
WP_FN EmittedPhoton emit_scene_photon(WP_SCENE_PARAMS, uint iteration, lane_uint photon) {
    uint seed = scene->seed;
    lane_uint light =
        select_light(light_cdf, LIGHT_COUNT, photon_uniform(seed, iteration, photon, 0u, DIM_PHOTON_LIGHT_SELECT));
#ifdef WP_HAS_MESH_LIGHTS
    real u_triangle = photon_uniform(seed, iteration, photon, 0u, DIM_PHOTON_LIGHT_TRIANGLE);
#else
    real u_triangle = REAL(0.0);
#endif
    LightShape shape = light_shape(WP_SCENE_ARGS, light, u_triangle);
    EmissionPoint e = emission_point(shape, photon_uniform(seed, iteration, photon, 0u, DIM_PHOTON_POINT_U),
                                     photon_uniform(seed, iteration, photon, 0u, DIM_PHOTON_POINT_V));
    Emission emitter = emission_at(materials, shape.material);
    return emit_photon(e.at, shape_point_error(shape.magnitude), e.area, light_selection_pmf(light_cdf, light),
                       emitter.emission, emitter.two_sided,
                       photon_uniform(seed, iteration, photon, 0u, DIM_PHOTON_SIDE),
                       photon_uniform(seed, iteration, photon, 0u, DIM_PHOTON_DIRECTION_U),
                       photon_uniform(seed, iteration, photon, 0u, DIM_PHOTON_DIRECTION_V));
}

#ifdef WP_HAS_NON_SPECULAR
/* What a visible point makes of a photon arriving along wi
 * (photon_deposit's first and third arguments): the camera path's
 * throughput times its material's f, and whether the material transmits. */
typedef struct {
    vec3 throughput_f;
    lane_int transmits;
} VisibleBsdf;

/* For a visible point of weight `weight` (visible_point_weight) and shading
 * normal ns; with other materials than diffuse, also its material and side
 * (`material_word`, visible_material_word), its uv (u, v) where its
 * material is textured, the direction wo back along its camera path and its
 * geometric normal nf, from which f is evaluated as next-event estimation
 * evaluates it (vertex_bsdf_value). A diffuse one's weight holds its
 * (textured) albedo: f is diffuse_eval's. */
WP_FN VisibleBsdf visible_point_bsdf(WP_SCENE_PARAMS, lane_uint material_word, real u, real v, vec3 wo, vec3 nf,
                                     vec3 ns, vec3 weight, vec3 wi) {
    VisibleBsdf b;
#ifdef WP_HAS_GLOSSY
    Vertex at;
    lane_uint material = visible_material_index(material_word);
    at.material = material_at(materials, material);
#ifdef WP_HAS_TEXTURES
    at.material = textured_material(WP_SCENE_ARGS, at.material, material, parameter_textures(WP_SCENE_ARGS, material),
                                    make_texture_uv(u, v));
#endif
    at.front = visible_material_front(material_word);
    at.wo = wo;
    at.nf = nf;
    at.ns = ns;
#ifdef WP_HAS_ROUGH_PLASTIC
    at.roughplastic_table = roughplastic_transmittance;
#endif
    b.throughput_f = finite_visible_f(vertex_bsdf_value(at, wi, weight).throughput_f);
    b.transmits = vertex_transmits(at);
#ifdef WP_HAS_DIFFUSE
    b.throughput_f = v3_select(at.material.type == WP_MATERIAL_DIFFUSE, diffuse_eval(weight, ns, wi), b.throughput_f);
#endif
#else
    b.throughput_f = diffuse_eval(weight, ns, wi); /* every visible point is diffuse */
    b.transmits = 0;
#endif
    return b;
}
#endif

/* The grid's frame, as photon_grid.cl's grid_bounds wrote it. */
WP_FN GridFrame read_grid_frame(__global const float *frame) {
    GridFrame f;
    f.origin = uniform_vec3(frame);
    f.cell_size = (real)frame[3];
    return f;
}

#endif
