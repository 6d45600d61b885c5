/* Triangles of meshes: the watertight ray-triangle test of Woop, Benthin and
 * Wald ("Watertight Ray/Triangle Intersection", JCGT 2(1), 2013), in the form
 * pbrt-v4 uses (shapes.cpp, IntersectTriangle): translate the vertices to the
 * ray origin, permute so that the direction's largest component is z, shear
 * so that the ray becomes the +z axis, then decide with 2D edge functions,
 * which are evaluated identically for the two triangles sharing an edge, so
 * no ray passes between them. No division comes before the distance test.
 *
 * An edge function that is exactly 0 (the ray through an edge or vertex)
 * counts for both triangles there: both report the hit and the closest-hit
 * search keeps one, so the mesh stays watertight without the double
 * precision fallback of the paper (devices need not have fp64). Branch-free,
 * for any number of lanes. */
#ifndef WP_SHARED_TRIANGLE_H
#define WP_SHARED_TRIANGLE_H

#include "shared/lights.h"
#include "shared/offset.h"
#include "shared/prelude.h"

/* A mesh triangle as the kernels and the reference store it, in the order of
 * the BVH's leaves; front side: that of (p1 - p0) x (p2 - p0). */
typedef struct {
    real_element p0[3], p1[3], p2[3];
    uint material;
    uint mesh; /* index into Scene::meshes */
} MeshTriangle;

/* A mesh triangle's vertex normals from its file, in world space and unit
 * length, parallel to the triangles; all zero where the mesh has none (or
 * asks for face normals): such a triangle shades with its geometric normal. */
typedef struct {
    real_element n0[3], n1[3], n2[3];
} TriangleNormals;

/* v with its components rotated so that axis `z_axis` (0, 1, 2) comes last. */
WP_FN vec3 rotate_axes_to_z(vec3 v, lane_int z_is_x, lane_int z_is_y) {
    vec3 z_was_x = make_vec3(v.y, v.z, v.x), z_was_y = make_vec3(v.z, v.x, v.y);
    return v3_select(z_is_x, z_was_x, v3_select(z_is_y, z_was_y, v));
}

/* What the test needs of the ray's direction alone, the same for every
 * triangle it meets (a traversal computes it once): which axis becomes z
 * (the direction's largest component), and the shear that makes the ray the
 * +z axis. */
typedef struct {
    lane_int z_is_x, z_is_y;
    real shear_x, shear_y, scale_z;
} TriangleRay;

WP_FN TriangleRay triangle_ray(vec3 direction) {
    real ax = fabs(direction.x), ay = fabs(direction.y), az = fabs(direction.z);
    TriangleRay r;
    r.z_is_x = ax > ay && ax > az;
    r.z_is_y = !r.z_is_x && ay > az;
    vec3 d = rotate_axes_to_z(direction, r.z_is_x, r.z_is_y);
    r.shear_x = -d.x / d.z, r.shear_y = -d.y / d.z, r.scale_z = REAL(1.0) / d.z;
    return r;
}

/* The triangle as the ray sees it: the edge functions e0, e1, e2 (twice
 * the signed areas of the sub-triangles opposite p0, p1, p2 in the sheared
 * frame, so e_i / det are the hit's barycentric coordinates), their sum det,
 * and t_scaled = t * det. */
typedef struct {
    real e0, e1, e2, det, t_scaled;
} TriangleEdges;

WP_FN TriangleEdges ray_triangle_edges(TriangleRay ray, vec3 p0, vec3 p1, vec3 p2, vec3 origin) {
    vec3 a = rotate_axes_to_z(v3_sub(p0, origin), ray.z_is_x, ray.z_is_y);
    vec3 b = rotate_axes_to_z(v3_sub(p1, origin), ray.z_is_x, ray.z_is_y);
    vec3 c = rotate_axes_to_z(v3_sub(p2, origin), ray.z_is_x, ray.z_is_y);
    real ax2 = a.x + ray.shear_x * a.z, ay2 = a.y + ray.shear_y * a.z;
    real bx2 = b.x + ray.shear_x * b.z, by2 = b.y + ray.shear_y * b.z;
    real cx2 = c.x + ray.shear_x * c.z, cy2 = c.y + ray.shear_y * c.z;
    TriangleEdges e;
    e.e0 = bx2 * cy2 - by2 * cx2;
    e.e1 = cx2 * ay2 - cy2 * ax2;
    e.e2 = ax2 * by2 - ay2 * bx2;
    e.det = e.e0 + e.e1 + e.e2;
    e.t_scaled = e.e0 * (ray.scale_z * a.z) + e.e1 * (ray.scale_z * b.z) + e.e2 * (ray.scale_z * c.z);
    return e;
}

WP_FN TriangleEdges triangle_edges(vec3 p0, vec3 p1, vec3 p2, vec3 origin, vec3 direction) {
    return ray_triangle_edges(triangle_ray(direction), p0, p1, p2, origin);
}

/* The distance t in (0, t_max) at which the ray meets the triangle whose
 * edges it sees as e, or WP_INFINITY. */
WP_FN real triangle_distance(TriangleEdges e, real t_max) {
    lane_int mixed_signs = (e.e0 < REAL(0.0) || e.e1 < REAL(0.0) || e.e2 < REAL(0.0)) &&
                           (e.e0 > REAL(0.0) || e.e1 > REAL(0.0) || e.e2 > REAL(0.0));
    /* 0 < t_scaled / det < t_max, compared without dividing */
    real t_max_scaled = t_max * fabs(e.det);
    real t_signed = e.det < REAL(0.0) ? -e.t_scaled : e.t_scaled;
    lane_int in_range = t_signed > REAL(0.0) && t_signed < t_max_scaled;
    real t = e.t_scaled / e.det;
    lane_int hit = !mixed_signs && e.det != REAL(0.0) && in_range && t > REAL(0.0) && t < t_max;
    return hit ? t : WP_INFINITY;
}

/* Distance t in (0, t_max) at which the ray meets the triangle, or WP_INFINITY. */
WP_FN real intersect_triangle(vec3 p0, vec3 p1, vec3 p2, vec3 origin, vec3 direction, real t_max) {
    return triangle_distance(triangle_edges(p0, p1, p2, origin, direction), t_max);
}

WP_FN vec3 triangle_normal(vec3 p0, vec3 p1, vec3 p2) { return v3_normalize(v3_cross(v3_sub(p1, p0), v3_sub(p2, p0))); }

/* The barycentric coordinates b1, b2 (the weights of p1 and p2) of a point
 * p in the triangle's plane: its sub-triangles' areas over the triangle's. */
typedef struct {
    real b1, b2;
} TriangleBarycentrics;

WP_FN TriangleBarycentrics triangle_barycentrics(vec3 p0, vec3 p1, vec3 p2, vec3 p) {
    vec3 e1 = v3_sub(p1, p0), e2 = v3_sub(p2, p0), to_p = v3_sub(p, p0);
    vec3 area = v3_cross(e1, e2);
    real area_squared = v3_dot(area, area);
    TriangleBarycentrics b;
    b.b1 = v3_dot(v3_cross(to_p, e2), area) / area_squared;
    b.b2 = v3_dot(v3_cross(e1, to_p), area) / area_squared;
    return b;
}

/* The shading normal at point p of the triangle with geometric normal
 * `geometric`: the vertex normals n0, n1, n2 interpolated with p's
 * barycentric coordinates (from the areas p makes with the edges, stable for
 * thin triangles), normalised and turned to the geometric normal's side, so
 * that the front of a triangle is the same for both. Vertex normals that are
 * all zero, or that cancel, give the geometric normal. */
WP_FN vec3 triangle_shading_normal(vec3 p0, vec3 p1, vec3 p2, vec3 n0, vec3 n1, vec3 n2, vec3 geometric, vec3 p) {
    TriangleBarycentrics b = triangle_barycentrics(p0, p1, p2, p);
    real b1 = b.b1, b2 = b.b2;
    vec3 interpolated = v3_add(v3_add(v3_scale(n0, REAL(1.0) - b1 - b2), v3_scale(n1, b1)), v3_scale(n2, b2));
    real length = v3_length(interpolated);
    lane_int usable = length > REAL(0.0) && length < WP_INFINITY; /* false for NaN */
    vec3 shading = v3_select(usable, v3_div(interpolated, length), geometric);
    return v3_select(v3_dot(shading, geometric) < REAL(0.0), v3_neg(shading), shading);
}

/* The solid-angle density with which sample_triangle, from `reference`,
 * picks the direction towards `point` (unit normal `normal`) on a mesh light
 * of area mesh_area: every point of the mesh has the area density
 * 1 / mesh_area. */
WP_FN real mesh_light_pdf(real mesh_area, vec3 reference, vec3 point, vec3 normal) {
    return area_to_solid_angle_pdf(REAL(1.0) / mesh_area, reference, point, normal);
}

/* A point uniform by area on the triangle (the square-root warp,
 * b0 = 1 - sqrt(u1), b1 = u2 sqrt(u1)), with its front normal. */
WP_FN AreaPoint triangle_point(vec3 p0, vec3 p1, vec3 p2, real u1, real u2) {
    real root = sqrt(u1);
    real b0 = REAL(1.0) - root, b1 = u2 * root;
    AreaPoint p;
    p.point = v3_add(v3_add(v3_scale(p0, b0), v3_scale(p1, b1)), v3_scale(p2, REAL(1.0) - b0 - b1));
    p.normal = triangle_normal(p0, p1, p2);
    return p;
}

/* triangle_point as a light sample, the triangle having been chosen in
 * proportion to its area among a mesh's of total area mesh_area. */
WP_FN LightSample sample_triangle(vec3 p0, vec3 p1, vec3 p2, real mesh_area, vec3 reference, real u1, real u2) {
    AreaPoint p = triangle_point(p0, p1, p2, u1, u2);
    return light_sample_at(p, mesh_light_pdf(mesh_area, reference, p.point, p.normal));
}

/* The magnitude a triangle's points and intersections are computed from (offset.h). */
WP_FN real triangle_magnitude(vec3 p0, vec3 p1, vec3 p2) { return fmax(max_abs(p0), fmax(max_abs(p1), max_abs(p2))); }

#endif
