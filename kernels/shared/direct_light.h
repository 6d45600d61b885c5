/* Next-event estimation at a vertex of a non-specular material: what one
 * point sampled on a light adds there, and the shadow ray that decides
 * whether it does. The choice of the light and of its point, which read the
 * scene, and the material's value and density for the direction to the
 * point, are the caller's. */
#ifndef WP_SHARED_DIRECT_LIGHT_H
#define WP_SHARED_DIRECT_LIGHT_H

#include "shared/estimator.h"
#include "shared/lights.h"
#include "shared/prelude.h"
#include "shared/special_functions.h"

typedef struct {
    ShadowRay shadow;
    vec3 contribution; /* added to the path where the shadow ray is unoccluded */
    lane_int carries;  /* the sample can carry light to the vertex: else there is no shadow ray to trace */
} DirectLight;

/* The direction from the vertex x to the light sample `ls`. */
WP_FN vec3 direct_light_direction(LightSample ls, vec3 x) { return v3_normalize(v3_sub(ls.point, x)); }

/* The light sample at the vertex x (error bound x_error, normals nf and ns
 * on the path's side) of a material that reflects only or, where
 * `transmits`, also transmits (then a light behind the surface counts, seen
 * and reached from the other side): the point `ls` on a light of magnitude
 * `light_magnitude` (offset.h), in direction wi (direct_light_direction),
 * chosen with probability `selection_pmf`, whose material has `emission` and
 * is `two_sided`. `throughput_f` is the path's throughput times the
 * material's f for wi, `bsdf_pdf` the density with which BSDF sampling
 * would have chosen wi (the other strategy of multiple importance sampling). */
typedef struct {
    vec3 nf, ns;
} SideNormals;

/* The vertex's normals nf and ns on the side that the direction wi leaves
 * into: turned where the material `transmits` and wi leaves behind it. */
WP_FN SideNormals light_side_normals(vec3 nf, vec3 ns, lane_int transmits, vec3 wi) {
    lane_int behind = transmits && v3_dot(wi, nf) < REAL(0.0);
    SideNormals side;
    side.nf = v3_select(behind, v3_neg(nf), nf);
    side.ns = v3_select(behind, v3_neg(ns), ns);
    return side;
}

WP_FN DirectLight direct_light(vec3 x, real x_error, vec3 nf, vec3 ns, lane_int transmits, vec3 wi, vec3 throughput_f,
                               real bsdf_pdf, LightSample ls, real light_magnitude, real selection_pmf, vec3 emission,
                               lane_int two_sided, int mis, int shading_normals) {
    SideNormals side = light_side_normals(nf, ns, transmits, wi);
    vec3 side_nf = side.nf, side_ns = side.ns;
    lane_int faces_vertex = light_faces(ls.normal, ls.point, x);
    real light_pdf = light_sample_pdf(selection_pmf, ls.pdf_solid_angle);
    real weight = light_sample_weight(light_pdf, bsdf_pdf, mis);
    DirectLight direct;
    direct.shadow = shadow_ray(x, x_error, side_nf, ls.point, ls.normal, faces_vertex, light_magnitude);
    direct.contribution = light_sample_contribution(throughput_f, emission, v3_dot(wi, side_ns), light_pdf, weight);
    direct.carries =
        light_sample_carries(ls.pdf_solid_angle, wi, side_nf, side_ns, two_sided, faces_vertex, shading_normals);
    return direct;
}

/* The light sample at vertex x (as direct_light's) of a light at infinity
 * in direction wi, of radiance `radiance` there, chosen with density
 * `light_pdf` (selection included; a delta light's: its selection
 * probability, with `mis` 0, since BSDF sampling never finds it). Its
 * shadow ray leaves x and ends nowhere: nothing may lie anywhere along it. */
WP_FN DirectLight distant_direct_light(vec3 x, real x_error, vec3 nf, vec3 ns, lane_int transmits, vec3 wi,
                                       vec3 throughput_f, real bsdf_pdf, real light_pdf, vec3 radiance, int mis,
                                       int shading_normals) {
    SideNormals side = light_side_normals(nf, ns, transmits, wi);
    DirectLight direct;
    direct.shadow.origin = offset_ray_origin(x, side.nf, x_error);
    direct.shadow.direction = wi;
    direct.shadow.distance = WP_REAL_MAX;
    direct.contribution = light_sample_contribution(throughput_f, radiance, v3_dot(wi, side.ns), light_pdf,
                                                    light_sample_weight(light_pdf, bsdf_pdf, mis));
    direct.carries = light_sample_carries(light_pdf, wi, side.nf, side.ns, 1, 1, shading_normals);
    return direct;
}

/* The share of a spot's intensity that leaves it in the unit direction d,
 * as Mitsuba 3's spot (falloff_curve): 1 within its beam (the angle to its
 * unit `axis` at most the beam width, cos_beam), falling linearly in that
 * angle to 0 at the cutoff angle (cos_cutoff, `cutoff_angle` in radians,
 * `inv_transition_width` one over the cutoff angle minus the beam width), 0
 * beyond. The angle is atan2(|axis x d|, axis . d), exact near the axis
 * where acos(axis . d) is not. A point light's cosines lie below -1: 1 in
 * every direction. */
WP_FN real spot_falloff(vec3 axis, vec3 d, real cos_cutoff, real cos_beam, real cutoff_angle,
                        real inv_transition_width) {
    real cos_theta = v3_dot(axis, d);
    real angle = REAL(2.0) * WP_PI * atan2_turns(v3_length(v3_cross(axis, d)), cos_theta);
    real falloff = cos_theta >= cos_beam ? REAL(1.0) : (cutoff_angle - angle) * inv_transition_width;
    return cos_theta > cos_cutoff ? falloff : REAL(0.0);
}

/* The light sample at vertex x (as direct_light's) of a point light at
 * `position`, in direction wi (direct_light_direction's towards it), whose
 * intensity towards x is `intensity` (a spot's falloff included), chosen
 * with probability `selection_pmf`: a delta light, found by next-event
 * estimation alone (no MIS), its density that probability; it adds
 * intensity / r^2 as radiance. Its shadow ray ends at the light, short of
 * it by the far-end offset of a shape light's (shadow_ray), and there is
 * none where no light leaves towards x. */
WP_FN DirectLight point_direct_light(vec3 x, real x_error, vec3 nf, vec3 ns, lane_int transmits, vec3 wi,
                                     vec3 throughput_f, real selection_pmf, vec3 position, vec3 intensity,
                                     int shading_normals) {
    SideNormals side = light_side_normals(nf, ns, transmits, wi);
    vec3 to_light = v3_sub(position, x);
    vec3 radiance = v3_div(intensity, v3_dot(to_light, to_light));
    DirectLight direct;
    direct.shadow = shadow_ray(x, x_error, side.nf, position, v3_neg(wi), 1, max_abs(position));
    direct.contribution =
        light_sample_contribution(throughput_f, radiance, v3_dot(wi, side.ns), selection_pmf, REAL(1.0));
    direct.carries =
        light_sample_carries(selection_pmf, wi, side.nf, side.ns, 1, 1, shading_normals) && emits(intensity);
    return direct;
}

/* `a` where `choose_a`, else `b`, in each lane. */
WP_FN DirectLight select_direct_light(lane_int choose_a, DirectLight a, DirectLight b) {
    DirectLight direct;
    direct.shadow.origin = v3_select(choose_a, a.shadow.origin, b.shadow.origin);
    direct.shadow.direction = v3_select(choose_a, a.shadow.direction, b.shadow.direction);
    direct.shadow.distance = choose_a ? a.shadow.distance : b.shadow.distance;
    direct.contribution = v3_select(choose_a, a.contribution, b.contribution);
    direct.carries = choose_a ? a.carries : b.carries;
    return direct;
}

#endif
