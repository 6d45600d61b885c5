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

/* Where a photon leaves light `light`: a point uniform by area (u, v; a mesh
 * light's triangle by u_triangle, in proportion to area), the light's area,
 * the material that emits there and the magnitude its error comes from.
 * Every light kind in the scene is computed and each lane keeps its own. */
typedef struct {
    AreaPoint at;
    real area, magnitude;
    lane_uint material;
} EmissionPoint;

WP_FN EmissionPoint select_emission_point(lane_int choose_a, EmissionPoint a, EmissionPoint b) {
    EmissionPoint p;
    p.at.point = v3_select(choose_a, a.at.point, b.at.point);
    p.at.normal = v3_select(choose_a, a.at.normal, b.at.normal);
    p.area = choose_a ? a.area : b.area;
    p.magnitude = choose_a ? a.magnitude : b.magnitude;
    p.material = choose_a ? a.material : b.material;
    return p;
}

WP_FN EmissionPoint emission_point(WP_SCENE_PARAMS, lane_uint light, real u, real v, real u_triangle) {
    lane_uint shape = SCENE_FIELD(lights, light, shape);
    lane_uint index = shape & WP_SHAPE_INDEX_MASK, type = shape >> WP_SHAPE_TYPE_SHIFT;
    EmissionPoint p, kind;
    p.at.point = p.at.normal = make_vec3(REAL(0.0), REAL(0.0), REAL(0.0));
    p.area = p.magnitude = REAL(0.0);
    p.material = 0u;
#ifdef WP_HAS_SPHERE_LIGHTS
    {
        lane_int is_sphere = type == WP_SHAPE_SPHERE;
        lane_uint i = is_sphere ? index : (lane_uint)0u;
        vec3 center = SCENE_FIELD(spheres, i, center);
        real radius = SCENE_FIELD(spheres, i, radius);
        kind.at = sphere_point(center, radius, u, v);
        kind.area = sphere_area(radius);
        kind.magnitude = sphere_magnitude(center, radius);
        kind.material = SCENE_FIELD(spheres, i, material);
        p = select_emission_point(is_sphere, kind, p);
    }
#endif
#ifdef WP_HAS_QUAD_LIGHTS
    {
        lane_int is_quad = type == WP_SHAPE_QUAD;
        lane_uint i = is_quad ? index : (lane_uint)0u;
        vec3 corner = SCENE_FIELD(quads, i, corner), edge1 = SCENE_FIELD(quads, i, edge1);
        vec3 edge2 = SCENE_FIELD(quads, i, edge2);
        kind.at = quad_point(corner, edge1, edge2, u, v);
        kind.area = quad_area(edge1, edge2);
        kind.magnitude = quad_magnitude(corner, edge1, edge2);
        kind.material = SCENE_FIELD(quads, i, material);
        p = select_emission_point(is_quad, kind, p);
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
        kind.at = triangle_point(p0, p1, p2, u, v);
        kind.area = SCENE_FIELD(lights, light, area);
        kind.magnitude = triangle_magnitude(p0, p1, p2);
        kind.material = SCENE_FIELD(light_triangles, k, material);
        p = select_emission_point(is_mesh, kind, p);
    }
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
    EmissionPoint e =
        emission_point(WP_SCENE_ARGS, light, photon_uniform(seed, iteration, photon, 0u, DIM_PHOTON_POINT_U),
                       photon_uniform(seed, iteration, photon, 0u, DIM_PHOTON_POINT_V), u_triangle);
    Material emitter = material_at(materials, e.material);
    return emit_photon(e.at, shape_point_error(e.magnitude), e.area, light_selection_pmf(light_cdf, light),
                       emitter.emission, emitter.two_sided,
                       photon_uniform(seed, iteration, photon, 0u, DIM_PHOTON_SIDE),
                       photon_uniform(seed, iteration, photon, 0u, DIM_PHOTON_DIRECTION_U),
                       photon_uniform(seed, iteration, photon, 0u, DIM_PHOTON_DIRECTION_V));
}

/* The grid's frame, as photon_grid.cl's grid_bounds wrote it. */
WP_FN GridFrame read_grid_frame(__global const float *frame) {
    GridFrame f;
    f.origin = uniform_vec3(frame);
    f.cell_size = (real)frame[3];
    return f;
}

#endif
