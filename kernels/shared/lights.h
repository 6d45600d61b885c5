/* Lights: a point sampled on a light, the density of each shape's sampling
 * beside its sampler (a mesh light's: shared/triangle.h), the choice of a
 * light in proportion to its power, and which light a hit shape belongs to. */
#ifndef WP_SHARED_LIGHTS_H
#define WP_SHARED_LIGHTS_H

#include "shared/prelude.h"
#include "shared/sampling.h"

/* A point sampled on a light, with everything next-event estimation needs. */
typedef struct {
    vec3 point;           /* on the light's surface */
    vec3 normal;          /* the light's outward (or edge1 x edge2) unit normal at point */
    real pdf_solid_angle; /* density of the direction from the reference point; 0 = no sample */
} LightSample;

/* A point on a light's surface, uniform by area, with the light's unit
 * normal there: where a light sample aims (the samplers below add its
 * density) and where a photon starts (shared/photons.h). */
typedef struct {
    vec3 point, normal;
} AreaPoint;

WP_FN LightSample light_sample_at(AreaPoint at, real pdf_solid_angle) {
    LightSample s;
    s.point = at.point;
    s.normal = at.normal;
    s.pdf_solid_angle = pdf_solid_angle;
    return s;
}

/* Converts an area density at `point` to a solid-angle density seen from `reference`. */
WP_FN real area_to_solid_angle_pdf(real pdf_area, vec3 reference, vec3 point, vec3 normal) {
    vec3 to_reference = v3_sub(reference, point);
    real distance_squared = v3_dot(to_reference, to_reference);
    real cos_light = fabs(v3_dot(normal, to_reference)) / sqrt(distance_squared);
    return cos_light > REAL(0.0) ? pdf_area * distance_squared / cos_light : REAL(0.0);
}

/* The area of the parallelogram spanned by edge1 and edge2. */
WP_FN real quad_area(vec3 edge1, vec3 edge2) { return v3_length(v3_cross(edge1, edge2)); }

/* The solid-angle density with which sample_quad, from `reference`, picks
 * the direction towards `point` (unit normal `normal`) on the quad. */
WP_FN real quad_light_pdf(vec3 edge1, vec3 edge2, vec3 reference, vec3 point, vec3 normal) {
    return area_to_solid_angle_pdf(REAL(1.0) / quad_area(edge1, edge2), reference, point, normal);
}

/* Uniform by area over the parallelogram corner + u*edge1 + v*edge2. */
WP_FN AreaPoint quad_point(vec3 corner, vec3 edge1, vec3 edge2, real u1, real u2) {
    AreaPoint p;
    p.point = v3_add_scaled(v3_add_scaled(corner, u1, edge1), u2, edge2);
    p.normal = v3_div(v3_cross(edge1, edge2), quad_area(edge1, edge2));
    return p;
}

WP_FN LightSample sample_quad(vec3 corner, vec3 edge1, vec3 edge2, vec3 reference, real u1, real u2) {
    AreaPoint p = quad_point(corner, edge1, edge2, u1, u2);
    return light_sample_at(p, quad_light_pdf(edge1, edge2, reference, p.point, p.normal));
}

WP_FN real sphere_area(real radius) { return REAL(4.0) * WP_PI * radius * radius; }

WP_FN real sphere_area_pdf(real radius) { return REAL(1.0) / sphere_area(radius); }

/* Uniform by area over the whole sphere, with its outward normal. */
WP_FN AreaPoint sphere_point(vec3 center, real radius, real u1, real u2) {
    real z = REAL(1.0) - REAL(2.0) * u1;
    AreaPoint p;
    p.normal = polar_vec3(safe_sqrt(REAL(1.0) - z * z), u2, z);
    p.point = v3_add_scaled(center, radius, p.normal);
    return p;
}

/* sphere_point as a light sample (used from inside or on the sphere). */
WP_FN LightSample sample_sphere_area(vec3 center, real radius, vec3 reference, real u1, real u2) {
    AreaPoint p = sphere_point(center, radius, u1, u2);
    return light_sample_at(p, area_to_solid_angle_pdf(sphere_area_pdf(radius), reference, p.point, p.normal));
}

/* Uniform over the cone of directions the sphere subtends from an outside
 * reference point (pbrt-v4, Sphere::Sample): every sample sees the sphere.
 * 1 - cos(theta) is kept as such and never formed by subtracting cosines,
 * which cancels to zero in float for small, distant lights:
 * 1 - cos(theta_max) = sin^2 / (1 + cos), and for the sampled angle
 * sin^2(theta) = (1 - cos)(1 + cos). Exact at every cone size (pbrt's
 * small-angle branch instead approximates 1 - cos by sin^2 / 2, a bias of up
 * to 1.7e-4 near its 1.5 degree switch). */
typedef struct {
    vec3 to_center;
    real distance, sin_theta_max, sin2_theta_max, one_minus_cos_theta_max;
} SphereCone;

WP_FN SphereCone sphere_cone(vec3 center, real radius, vec3 reference) {
    SphereCone cone;
    cone.to_center = v3_sub(center, reference);
    cone.distance = v3_length(cone.to_center);
    cone.sin_theta_max = radius / cone.distance;
    cone.sin2_theta_max = cone.sin_theta_max * cone.sin_theta_max;
    real cos_theta_max = safe_sqrt(REAL(1.0) - cone.sin2_theta_max);
    cone.one_minus_cos_theta_max = cone.sin2_theta_max / (REAL(1.0) + cos_theta_max);
    return cone;
}

WP_FN real sphere_cone_pdf(SphereCone cone) { return REAL(1.0) / (REAL(2.0) * WP_PI * cone.one_minus_cos_theta_max); }

WP_FN LightSample sample_sphere_cone(vec3 center, real radius, vec3 reference, real u1, real u2) {
    SphereCone cone = sphere_cone(center, radius, reference);
    real one_minus_cos_theta = u1 * cone.one_minus_cos_theta_max;
    real cos_theta = REAL(1.0) - one_minus_cos_theta;
    real sin2_theta = one_minus_cos_theta * (REAL(2.0) - one_minus_cos_theta);
    /* Angle alpha at the centre between the axis and the sampled point. */
    real cos_alpha =
        sin2_theta / cone.sin_theta_max + cos_theta * safe_sqrt(REAL(1.0) - sin2_theta / cone.sin2_theta_max);
    real sin_alpha = safe_sqrt(REAL(1.0) - cos_alpha * cos_alpha);
    Frame frame = frame_from_normal(v3_div(cone.to_center, cone.distance));
    LightSample s;
    s.normal = v3_neg(frame_to_world(frame, polar_vec3(sin_alpha, u2, cos_alpha)));
    s.point = v3_add_scaled(center, radius, s.normal);
    s.pdf_solid_angle = sphere_cone_pdf(cone);
    return s;
}

WP_FN LightSample select_light_sample(lane_int choose_a, LightSample a, LightSample b) {
    LightSample s;
    s.point = v3_select(choose_a, a.point, b.point);
    s.normal = v3_select(choose_a, a.normal, b.normal);
    s.pdf_solid_angle = choose_a ? a.pdf_solid_angle : b.pdf_solid_angle;
    return s;
}

/* Cone sampling from outside; area sampling from inside or on the surface,
 * where the cone degenerates. Both are unbiased; the switch is a choice of
 * strategy, not a tolerance. Both are computed and one chosen, so that lanes
 * on either side run the same code. */
WP_FN lane_int sphere_cone_applies(vec3 center, real radius, vec3 reference) {
    vec3 to_center = v3_sub(center, reference);
    return v3_dot(to_center, to_center) > REAL(1.0001) * radius * radius;
}

WP_FN LightSample sample_sphere(vec3 center, real radius, vec3 reference, real u1, real u2) {
    return select_light_sample(sphere_cone_applies(center, radius, reference),
                               sample_sphere_cone(center, radius, reference, u1, u2),
                               sample_sphere_area(center, radius, reference, u1, u2));
}

/* The solid-angle density with which sample_sphere, from `reference`, picks
 * the direction towards `point` (outward normal `normal`) on the sphere. */
WP_FN real sphere_light_pdf(vec3 center, real radius, vec3 reference, vec3 point, vec3 normal) {
    return sphere_cone_applies(center, radius, reference)
               ? sphere_cone_pdf(sphere_cone(center, radius, reference))
               : area_to_solid_angle_pdf(sphere_area_pdf(radius), reference, point, normal);
}

/* Index of the light whose cumulative-probability interval holds u (the
 * first i with u < cdf[i]). cdf has `count` entries, increasing, the last
 * equal to 1. A binary search whose steps depend on `count` alone and whose
 * choices are selects, so a constant count unrolls it into vector code. */
WP_FN lane_uint select_light(WP_GLOBAL const real_element* cdf, uint count, real u) {
    lane_uint first = 0u; /* the answer lies in [first, first + remaining) */
    for (uint remaining = count; remaining > 1u;) {
        uint step = remaining / 2u;
        first = u >= gather(cdf, first + step - 1u) ? first + step : first;
        remaining -= step;
    }
    return first;
}

/* Probability that select_light returns `index`. */
WP_FN real light_selection_pmf(WP_GLOBAL const real_element* cdf, lane_uint index) {
    real below = gather(cdf, index == 0u ? index : index - 1u);
    return index == 0u ? gather(cdf, index) : gather(cdf, index) - below;
}

/* The density of a light sample: its light's selection probability times the
 * solid-angle density of its point. */
WP_FN real light_sample_pdf(real selection_pmf, real point_pdf) { return selection_pmf * point_pdf; }

/* The key by which a hit shape finds its light: a light and a shape of the
 * same kind match when their keys are equal. A triangle's light is its
 * mesh's, so its key is its mesh; any other shape's is its index. */
WP_FN lane_uint light_key(lane_int is_triangle, lane_uint index, lane_uint mesh) { return is_triangle ? mesh : index; }

#endif
