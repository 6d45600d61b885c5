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

/* The frame about unit n whose tangent is `direction` made orthogonal to n
 * (Gram-Schmidt) and normalized, and whose bitangent is n x tangent: Mitsuba
 * 3's shading frame (SurfaceInteraction::initialize_sh_frame) where
 * `direction` is the surface's dp/du. Where `direction` has no part
 * orthogonal to n (it is zero, or exactly along n) the tangent is
 * `fallback`, a unit vector orthogonal to n. */
WP_FN Frame frame_along(vec3 n, vec3 direction, vec3 fallback) {
    vec3 tangent = v3_sub(direction, v3_scale(n, v3_dot(n, direction)));
    real length = v3_length(tangent);
    lane_int has_tangent = length > REAL(0.0);
    Frame frame;
    frame.tangent = v3_select(has_tangent, v3_scale(tangent, REAL(1.0) / (has_tangent ? length : REAL(1.0))), fallback);
    frame.bitangent = v3_cross(n, frame.tangent);
    frame.normal = n;
    return frame;
}

WP_FN vec3 frame_to_world(Frame frame, vec3 local_direction) {
    return v3_add(v3_add(v3_scale(frame.tangent, local_direction.x), v3_scale(frame.bitangent, local_direction.y)),
                  v3_scale(frame.normal, local_direction.z));
}

/* The inverse of frame_to_world: a world direction's coordinates in the frame. */
WP_FN vec3 frame_to_local(Frame frame, vec3 world_direction) {
    return make_vec3(v3_dot(world_direction, frame.tangent), v3_dot(world_direction, frame.bitangent),
                     v3_dot(world_direction, frame.normal));
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

/* The t in [0, 1) whose density is proportional to the line from a at
 * t = 0 to b at t = 1 (a, b >= 0, not both 0), by inverting its cumulative
 * (a t + (b - a) t^2 / 2) / ((a + b) / 2) = u: the root
 * t = u (a + b) / (a + sqrt((1 - u) a^2 + u b^2)), in the form that does not
 * cancel where a and b are close (pbrt-v4's SampleLinear). */
WP_FN real sample_linear(real u, real a, real b) {
    real denominator = a + sqrt((REAL(1.0) - u) * a * a + u * b * b);
    real t = denominator > REAL(0.0) ? u * (a + b) / denominator : u;
    return wp_clamp(t, REAL(0.0), REAL(1.0) - WP_UNIT_ROUNDOFF);
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

WP_FN real uniform_hemisphere_pdf(void) { return REAL(0.5) * WP_INV_PI; }

/* pdf = 1 / (4 pi) over the sphere. */
WP_FN vec3 sample_uniform_sphere(real u1, real u2) {
    real z = REAL(1.0) - REAL(2.0) * u1;
    return polar_vec3(safe_sqrt(REAL(1.0) - z * z), u2, z);
}

WP_FN real uniform_sphere_pdf(void) { return REAL(0.25) * WP_INV_PI; }

#endif
