/* Direction and light sampling. Local frames have z along the normal. */
#ifndef WP_SHARED_SAMPLING_H
#define WP_SHARED_SAMPLING_H

#include "shared/prelude.h"

typedef struct {
    vec3 tangent, bitangent, normal;
} Frame;

/* Branchless orthonormal basis: Duff et al., "Building an Orthonormal Basis,
 * Revisited" (JCGT 2017). `n` must be unit length. */
WP_FN Frame frame_from_normal(vec3 n) {
    real sign = copysign(REAL(1.0), n.z);
    real a = REAL(-1.0) / (sign + n.z);
    real b = n.x * n.y * a;
    Frame frame;
    frame.tangent = make_vec3(REAL(1.0) + sign * n.x * n.x * a, sign * b, -sign * n.x);
    frame.bitangent = make_vec3(b, sign + n.y * n.y * a, -n.y);
    frame.normal = n;
    return frame;
}

WP_FN vec3 frame_to_world(Frame frame, vec3 local_direction) {
    return v3_add(v3_add(v3_scale(frame.tangent, local_direction.x), v3_scale(frame.bitangent, local_direction.y)),
                  v3_scale(frame.normal, local_direction.z));
}

typedef struct {
    real cos_value, sin_value;
} CosSin;

/* cos and sin of the angle 2 pi u, u in [0, 1]: reduced to the nearest
 * quarter turn and a remainder x in [-pi/4, pi/4], where Taylor polynomials
 * through x^15 and x^16 are exact to 5e-17, below double's rounding.
 * Written out instead of calling cos and sin, which PoCL cannot vectorise,
 * and computed the same way on both sides. */
WP_FN CosSin cos_sin_turns(real u) {
    real quarter_turns = floor(REAL(4.0) * u + REAL(0.5));
    real x = (REAL(4.0) * u - quarter_turns) * (WP_PI / REAL(2.0));
    real x2 = x * x;
    /* Horner form; the coefficients are (-1)^k / (2k+1)! and (-1)^k / (2k)!. */
    real s = REAL(-1.0) / REAL(1307674368000.0);
    s = s * x2 + REAL(1.0) / REAL(6227020800.0);
    s = s * x2 - REAL(1.0) / REAL(39916800.0);
    s = s * x2 + REAL(1.0) / REAL(362880.0);
    s = s * x2 - REAL(1.0) / REAL(5040.0);
    s = s * x2 + REAL(1.0) / REAL(120.0);
    s = s * x2 - REAL(1.0) / REAL(6.0);
    s = (s * x2 + REAL(1.0)) * x;
    real c = REAL(1.0) / REAL(20922789888000.0);
    c = c * x2 - REAL(1.0) / REAL(87178291200.0);
    c = c * x2 + REAL(1.0) / REAL(479001600.0);
    c = c * x2 - REAL(1.0) / REAL(3628800.0);
    c = c * x2 + REAL(1.0) / REAL(40320.0);
    c = c * x2 - REAL(1.0) / REAL(720.0);
    c = c * x2 + REAL(1.0) / REAL(24.0);
    c = c * x2 - REAL(1.0) / REAL(2.0);
    c = c * x2 + REAL(1.0);
    lane_int quadrant = TO_LANE_INT(quarter_turns) & 3; /* rotate (c, s) by quadrant quarter turns */
    CosSin r;
    r.cos_value = quadrant == 0 ? c : quadrant == 1 ? -s : quadrant == 2 ? -c : s;
    r.sin_value = quadrant == 0 ? s : quadrant == 1 ? c : quadrant == 2 ? -s : -c;
    return r;
}

/* The point at radius r and angle 2 pi u of the plane z = z, as a vector. */
WP_FN vec3 polar_vec3(real r, real u, real z) {
    CosSin phi = cos_sin_turns(u);
    return make_vec3(r * phi.cos_value, r * phi.sin_value, z);
}

/* Malley's method: pdf = cos(theta) / pi over the hemisphere. */
WP_FN vec3 sample_cosine_hemisphere(real u1, real u2) { return polar_vec3(sqrt(u1), u2, safe_sqrt(REAL(1.0) - u1)); }

WP_FN real cosine_hemisphere_pdf(real cos_theta) { return fmax(cos_theta, REAL(0.0)) * WP_INV_PI; }

/* pdf = 1 / (2 pi) over the hemisphere. */
WP_FN vec3 sample_uniform_hemisphere(real u1, real u2) {
    real z = u1;
    return polar_vec3(safe_sqrt(REAL(1.0) - z * z), u2, z);
}

/* Russian roulette's survival probability for a path of throughput
 * `throughput`, with the radiance scaling of its refractions factored out
 * (`eta_scale`, the product of eta^2 over them, as pbrt-v4's etaScale): a
 * path inside glass carries 1/eta^2 of its radiance until it leaves, and
 * should not be killed for it. Clamped to [0.05, 1], so a survivor's weight
 * grows at most 20-fold. */
WP_FN real roulette_survival(vec3 throughput, real eta_scale) {
    return wp_clamp(max_component(throughput) * eta_scale, REAL(0.05), REAL(1.0));
}

WP_FN real uniform_hemisphere_pdf(void) { return REAL(0.5) * WP_INV_PI; }

/* Veach's power heuristic (beta = 2) for one sample of the strategy of
 * density `f` against one of density `g`: f^2 / (f^2 + g^2), written as
 * 1 / (1 + (g/f)^2) so that no density is squared: a small light far away
 * has a solid-angle density above 1e19, whose square overflows float.
 * (g/f)^2 overflowing gives 0, as it should; f = 0 (the strategy cannot make
 * the sample) gives 0; the weights of the two strategies for one sample
 * still sum to 1 within a few ulps. */
WP_FN real power_heuristic(real f, real g) {
    real ratio = g / f;
    return f > REAL(0.0) ? REAL(1.0) / (REAL(1.0) + ratio * ratio) : REAL(0.0);
}

/* A point sampled on a light, with everything next-event estimation needs. */
typedef struct {
    vec3 point;           /* on the light's surface */
    vec3 normal;          /* the light's outward (or edge1 x edge2) unit normal at point */
    real pdf_solid_angle; /* density of the direction from the reference point; 0 = no sample */
} LightSample;

/* Converts an area density at `point` to a solid-angle density seen from `reference`. */
WP_FN real area_to_solid_angle_pdf(real pdf_area, vec3 reference, vec3 point, vec3 normal) {
    vec3 to_reference = v3_sub(reference, point);
    real distance_squared = v3_dot(to_reference, to_reference);
    real cos_light = fabs(v3_dot(normal, to_reference)) / sqrt(distance_squared);
    return cos_light > REAL(0.0) ? pdf_area * distance_squared / cos_light : REAL(0.0);
}

/* Uniform by area over the parallelogram corner + u*edge1 + v*edge2. */
WP_FN LightSample sample_quad(vec3 corner, vec3 edge1, vec3 edge2, vec3 reference, real u1, real u2) {
    vec3 n = v3_cross(edge1, edge2);
    real area = v3_length(n);
    LightSample s;
    s.point = v3_add_scaled(v3_add_scaled(corner, u1, edge1), u2, edge2);
    s.normal = v3_div(n, area);
    s.pdf_solid_angle = area_to_solid_angle_pdf(REAL(1.0) / area, reference, s.point, s.normal);
    return s;
}

WP_FN real sphere_area_pdf(real radius) { return REAL(1.0) / (REAL(4.0) * WP_PI * radius * radius); }

/* Uniform by area over the whole sphere (used from inside or on the sphere). */
WP_FN LightSample sample_sphere_area(vec3 center, real radius, vec3 reference, real u1, real u2) {
    real z = REAL(1.0) - REAL(2.0) * u1;
    LightSample s;
    s.normal = polar_vec3(safe_sqrt(REAL(1.0) - z * z), u2, z);
    s.point = v3_add_scaled(center, radius, s.normal);
    s.pdf_solid_angle = area_to_solid_angle_pdf(sphere_area_pdf(radius), reference, s.point, s.normal);
    return s;
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

/* Unit direction through the film point (x, y) in [0,1]^2 (y down) of a
 * pinhole camera with orthonormal basis right/up/forward and vertical field
 * of view given as tan(fov_y / 2). */
WP_FN vec3 camera_direction(vec3 right, vec3 up, vec3 forward, real tan_half_fov_y, real aspect, real x, real y) {
    real sx = (REAL(2.0) * x - REAL(1.0)) * tan_half_fov_y * aspect;
    real sy = (REAL(1.0) - REAL(2.0) * y) * tan_half_fov_y;
    return v3_normalize(v3_add_scaled(v3_add_scaled(forward, sx, right), sy, up));
}

#endif
