/* Direction and light sampling. Local frames have z along the normal. */

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
    return local_direction.x * frame.tangent + local_direction.y * frame.bitangent + local_direction.z * frame.normal;
}

/* Malley's method: pdf = cos(theta) / pi over the hemisphere. */
WP_FN vec3 sample_cosine_hemisphere(real u1, real u2) {
    real r = sqrt(u1);
    real phi = REAL(2.0) * WP_PI * u2;
    return make_vec3(r * cos(phi), r * sin(phi), safe_sqrt(REAL(1.0) - u1));
}

WP_FN real cosine_hemisphere_pdf(real cos_theta) { return fmax(cos_theta, REAL(0.0)) * WP_INV_PI; }

/* pdf = 1 / (2 pi) over the hemisphere. */
WP_FN vec3 sample_uniform_hemisphere(real u1, real u2) {
    real z = u1;
    real r = safe_sqrt(REAL(1.0) - z * z);
    real phi = REAL(2.0) * WP_PI * u2;
    return make_vec3(r * cos(phi), r * sin(phi), z);
}

/* A point sampled on a light, with everything next-event estimation needs. */
typedef struct {
    vec3 point;        /* on the light's surface */
    vec3 normal;       /* the light's outward (or edge1 x edge2) unit normal at point */
    real pdf_solid_angle; /* density of the direction from the reference point; 0 = no sample */
} LightSample;

/* Converts an area density at `point` to a solid-angle density seen from `reference`. */
WP_FN real area_to_solid_angle_pdf(real pdf_area, vec3 reference, vec3 point, vec3 normal) {
    vec3 to_reference = reference - point;
    real distance_squared = dot(to_reference, to_reference);
    real cos_light = fabs(dot(normal, to_reference)) / sqrt(distance_squared);
    return cos_light > REAL(0.0) ? pdf_area * distance_squared / cos_light : REAL(0.0);
}

/* Uniform by area over the parallelogram corner + u*edge1 + v*edge2. */
WP_FN LightSample sample_quad(vec3 corner, vec3 edge1, vec3 edge2, vec3 reference, real u1, real u2) {
    vec3 n = cross(edge1, edge2);
    real area = length(n);
    LightSample s;
    s.point = corner + u1 * edge1 + u2 * edge2;
    s.normal = n / area;
    s.pdf_solid_angle = area_to_solid_angle_pdf(REAL(1.0) / area, reference, s.point, s.normal);
    return s;
}

/* Uniform by area over the whole sphere (used from inside or on the sphere). */
WP_FN LightSample sample_sphere_area(vec3 center, real radius, vec3 reference, real u1, real u2) {
    real z = REAL(1.0) - REAL(2.0) * u1;
    real r = safe_sqrt(REAL(1.0) - z * z);
    real phi = REAL(2.0) * WP_PI * u2;
    LightSample s;
    s.normal = make_vec3(r * cos(phi), r * sin(phi), z);
    s.point = center + radius * s.normal;
    s.pdf_solid_angle =
        area_to_solid_angle_pdf(REAL(1.0) / (REAL(4.0) * WP_PI * radius * radius), reference, s.point, s.normal);
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
WP_FN LightSample sample_sphere_cone(vec3 center, real radius, vec3 reference, real u1, real u2) {
    vec3 to_center = center - reference;
    real distance = length(to_center);
    real sin_theta_max = radius / distance;
    real sin2_theta_max = sin_theta_max * sin_theta_max;
    real cos_theta_max = safe_sqrt(REAL(1.0) - sin2_theta_max);
    real one_minus_cos_theta_max = sin2_theta_max / (REAL(1.0) + cos_theta_max);
    real one_minus_cos_theta = u1 * one_minus_cos_theta_max;
    real cos_theta = REAL(1.0) - one_minus_cos_theta;
    real sin2_theta = one_minus_cos_theta * (REAL(2.0) - one_minus_cos_theta);
    /* Angle alpha at the centre between the axis and the sampled point. */
    real cos_alpha = sin2_theta / sin_theta_max + cos_theta * safe_sqrt(REAL(1.0) - sin2_theta / sin2_theta_max);
    real sin_alpha = safe_sqrt(REAL(1.0) - cos_alpha * cos_alpha);
    real phi = REAL(2.0) * WP_PI * u2;
    Frame frame = frame_from_normal(to_center / distance);
    vec3 local_direction = make_vec3(sin_alpha * cos(phi), sin_alpha * sin(phi), cos_alpha);
    LightSample s;
    s.normal = -frame_to_world(frame, local_direction);
    s.point = center + radius * s.normal;
    s.pdf_solid_angle = REAL(1.0) / (REAL(2.0) * WP_PI * one_minus_cos_theta_max);
    return s;
}

/* Cone sampling from outside; area sampling from inside or on the surface,
 * where the cone degenerates. Both are unbiased; the switch is a choice of
 * strategy, not a tolerance. */
WP_FN LightSample sample_sphere(vec3 center, real radius, vec3 reference, real u1, real u2) {
    vec3 to_center = center - reference;
    real distance_squared = dot(to_center, to_center);
    if (distance_squared > REAL(1.0001) * radius * radius) return sample_sphere_cone(center, radius, reference, u1, u2);
    return sample_sphere_area(center, radius, reference, u1, u2);
}

/* Index of the light whose cumulative-probability interval holds u.
 * cdf has `count` entries, increasing, the last equal to 1. */
WP_FN uint select_light(WP_GLOBAL const real* cdf, uint count, real u) {
    uint lo = 0u;
    uint hi = count - 1u;
    while (lo < hi) {
        uint mid = (lo + hi) / 2u;
        if (u < cdf[mid]) hi = mid;
        else lo = mid + 1u;
    }
    return lo;
}

/* Probability that select_light returns `index`. */
WP_FN real light_selection_pmf(WP_GLOBAL const real* cdf, uint index) {
    return index == 0u ? cdf[0] : cdf[index] - cdf[index - 1u];
}

/* Unit direction through the film point (x, y) in [0,1]^2 (y down) of a
 * pinhole camera with orthonormal basis right/up/forward and vertical field
 * of view given as tan(fov_y / 2). */
WP_FN vec3 camera_direction(vec3 right, vec3 up, vec3 forward, real tan_half_fov_y, real aspect, real x, real y) {
    real sx = (REAL(2.0) * x - REAL(1.0)) * tan_half_fov_y * aspect;
    real sy = (REAL(1.0) - REAL(2.0) * y) * tan_half_fov_y;
    return normalize(forward + sx * right + sy * up);
}
