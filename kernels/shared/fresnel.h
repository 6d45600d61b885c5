/* Smooth interfaces: the exact unpolarised Fresnel reflectance of a
 * dielectric and of a conductor, mirror reflection and Snell refraction. */
#ifndef WP_SHARED_FRESNEL_H
#define WP_SHARED_FRESNEL_H

#include "shared/prelude.h"

/* Fraction of light reflected at an interface with relative index
 * eta = n_transmitted / n_incident, for cos_theta_i measured against the
 * normal on the incident side (a negative value swaps the media). Returns 1
 * under total internal reflection. */
WP_FN real fresnel_dielectric(real cos_theta_i, real eta) {
    cos_theta_i = wp_clamp(cos_theta_i, REAL(-1.0), REAL(1.0));
    eta = cos_theta_i < REAL(0.0) ? REAL(1.0) / eta : eta;
    cos_theta_i = fabs(cos_theta_i);
    real sin2_theta_i = REAL(1.0) - cos_theta_i * cos_theta_i;
    real sin2_theta_t = sin2_theta_i / (eta * eta);
    real cos_theta_t = safe_sqrt(REAL(1.0) - sin2_theta_t);
    real r_parallel = (eta * cos_theta_i - cos_theta_t) / (eta * cos_theta_i + cos_theta_t);
    real r_perpendicular = (cos_theta_i - eta * cos_theta_t) / (cos_theta_i + eta * cos_theta_t);
    real reflectance = (r_parallel * r_parallel + r_perpendicular * r_perpendicular) / REAL(2.0);
    return sin2_theta_t >= REAL(1.0) ? REAL(1.0) : reflectance;
}

/* Fraction of unpolarised light reflected by a conductor of complex index
 * eta + i k (relative to the medium outside, one colour channel), for
 * cos_theta_i in [0, 1] measured on the outside (clamped into it). With
 * a + i b = sqrt((eta + i k)^2 - sin^2) (the complex cosine of the refracted
 * wave times the index, a >= 0):
 *   R_s = (|a + i b|^2 - 2 a cos + cos^2) / (|a + i b|^2 + 2 a cos + cos^2),
 *   R_p = R_s (|a + i b|^2 cos^2 - 2 a cos sin^2 + sin^4)
 *           / (|a + i b|^2 cos^2 + 2 a cos sin^2 + sin^4),
 * the reflectance their mean (Born and Wolf, Principles of Optics, chapter
 * 14, optics of metals; in this form in Mitsuba 3's fresnel_conductor and pbrt-v3's
 * FrConductor). k = 0 gives fresnel_dielectric's value (total internal
 * reflection included); eta = 0, k = 1 (Mitsuba's material "none": a purely
 * imaginary index) gives 1 exactly at every angle, since then
 * |a + i b|^2 = -(eta^2 - k^2 - sin^2) and a = 0 without rounding. */
WP_FN real fresnel_conductor_channel(real cos_theta_i, real eta, real k) {
    real cos_theta = wp_clamp(cos_theta_i, REAL(0.0), REAL(1.0));
    real cos2 = cos_theta * cos_theta;
    real sin2 = REAL(1.0) - cos2;
    real real_part = eta * eta - k * k - sin2; /* of (eta + i k)^2 - sin^2, whose imaginary part is 2 eta k */
    real modulus = sqrt(real_part * real_part + REAL(4.0) * eta * eta * k * k); /* a^2 + b^2 */
    real a = safe_sqrt(REAL(0.5) * (modulus + real_part));
    real s_cross = REAL(2.0) * a * cos_theta;
    real r_s = (modulus + cos2 - s_cross) / (modulus + cos2 + s_cross);
    real p_square = modulus * cos2 + sin2 * sin2;
    real p_cross = s_cross * sin2;
    real r_p = r_s * (p_square - p_cross) / (p_square + p_cross);
    return REAL(0.5) * (r_s + r_p);
}

/* fresnel_conductor_channel for each colour channel of eta and k. */
WP_FN vec3 fresnel_conductor(real cos_theta_i, vec3 eta, vec3 k) {
    return make_vec3(fresnel_conductor_channel(cos_theta_i, eta.x, k.x),
                     fresnel_conductor_channel(cos_theta_i, eta.y, k.y),
                     fresnel_conductor_channel(cos_theta_i, eta.z, k.z));
}

/* Mirror direction of an incoming ray direction d about unit normal n. */
WP_FN vec3 reflect_direction(vec3 d, vec3 n) { return v3_add_scaled(d, REAL(-2.0) * v3_dot(d, n), n); }

/* Refracts ray direction d at unit normal n that faces the incident side
 * (dot(d, n) < 0), with eta = n_transmitted / n_incident. Returns false on
 * total internal reflection (*out then holds no direction), else true with
 * the unit transmitted direction in *out. */
WP_FN lane_int refract_direction(vec3 d, vec3 n, real eta, vec3* out) {
    real cos_theta_i = -v3_dot(d, n);
    real sin2_theta_t = (REAL(1.0) - cos_theta_i * cos_theta_i) / (eta * eta);
    real cos_theta_t = safe_sqrt(REAL(1.0) - sin2_theta_t);
    *out = v3_normalize(v3_add_scaled(v3_div(d, eta), cos_theta_i / eta - cos_theta_t, n));
    return sin2_theta_t < REAL(1.0);
}

#endif
