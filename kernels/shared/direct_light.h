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
WP_FN DirectLight direct_light(vec3 x, real x_error, vec3 nf, vec3 ns, lane_int transmits, vec3 wi, vec3 throughput_f,
                               real bsdf_pdf, LightSample ls, real light_magnitude, real selection_pmf, vec3 emission,
                               lane_int two_sided, int mis, int shading_normals) {
    lane_int behind = transmits && v3_dot(wi, nf) < REAL(0.0);
    vec3 side_nf = v3_select(behind, v3_neg(nf), nf), side_ns = v3_select(behind, v3_neg(ns), ns);
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

#endif
