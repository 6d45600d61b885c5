/* Smooth dielectric interface: exact unpolarised Fresnel reflectance, mirror
 * reflection and Snell refraction. */
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
