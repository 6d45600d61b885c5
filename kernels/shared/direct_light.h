/* Next-event estimation at a diffuse vertex: what one point sampled on a
 * light adds there, and the shadow ray that decides whether it does. The
 * choice of the light and of its point, which read the scene, are the
 * caller's. */
#ifndef WP_SHARED_DIRECT_LIGHT_H
#define WP_SHARED_DIRECT_LIGHT_H

#include "shared/estimator.h"
#include "shared/lights.h"
#include "shared/materials/diffuse.h"
#include "shared/prelude.h"

typedef struct {
    ShadowRay shadow;
    vec3 contribution; /* added to the path where the shadow ray is unoccluded */
    lane_int carries;  /* the sample can carry light to the vertex: else there is no shadow ray to trace */
} DirectLight;

/* The light sample at the diffuse vertex x (error bound x_error, normals nf
 * and ns on the path's side) of albedo `albedo`, on a path of throughput
 * `throughput`: the point `ls` on a light of magnitude `light_magnitude`
 * (offset.h), chosen with probability `selection_pmf`, whose material has
 * `emission` and is `two_sided`. */
WP_FN DirectLight diffuse_direct_light(vec3 x, real x_error, vec3 nf, vec3 ns, vec3 throughput, vec3 albedo,
                                       LightSample ls, real light_magnitude, real selection_pmf, vec3 emission,
                                       lane_int two_sided, int uniform_hemisphere, int mis, int shading_normals) {
    vec3 wi = v3_normalize(v3_sub(ls.point, x));
    lane_int faces_vertex = light_faces(ls.normal, ls.point, x);
    real light_pdf = light_sample_pdf(selection_pmf, ls.pdf_solid_angle);
    real weight = light_sample_weight(light_pdf, diffuse_pdf(ns, wi, uniform_hemisphere), mis);
    DirectLight direct;
    direct.shadow = shadow_ray(x, x_error, nf, ls.point, ls.normal, faces_vertex, light_magnitude);
    direct.contribution = light_sample_contribution(diffuse_eval(v3_mul(throughput, albedo), ns, wi), emission,
                                                    v3_dot(wi, ns), light_pdf, weight);
    direct.carries = light_sample_carries(ls.pdf_solid_angle, wi, nf, ns, two_sided, faces_vertex, shading_normals);
    return direct;
}

#endif
