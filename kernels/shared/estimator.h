/* The path estimator's terms at one vertex (docs/architecture.md,
 * "Conventions"), shared by the kernels' lanes and the reference's plain
 * loop: the emission a hit adds, the multiple importance sampling weights of
 * the two strategies that can find a light, the light sample's contribution
 * and shadow ray, and Russian roulette. The render's choices (`nee`: next-event
 * estimation runs; `mis`: with multiple importance sampling;
 * `shading_normals`) are arguments, the same for every lane. */
#ifndef WP_SHARED_ESTIMATOR_H
#define WP_SHARED_ESTIMATOR_H

#include "shared/materials/bsdf.h"
#include "shared/offset.h"
#include "shared/prelude.h"

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

/* The share of the emission found at a hit that the path counts: all of it
 * after the camera or a specular vertex (`after_specular`), whose direction no
 * light sample could have chosen, and at every hit without next-event
 * estimation (pure BSDF sampling); after a diffuse vertex with next-event
 * estimation none (the light sample counts it) or, with multiple importance
 * sampling, the power heuristic's share for the bounce, whose density
 * `bsdf_pdf` it recorded, against the light sample's `light_pdf` of the same
 * point (light_sample_pdf from the bounce's origin). */
WP_FN real emission_weight(lane_int after_specular, real bsdf_pdf, real light_pdf, int nee, int mis) {
    real shared_weight = mis ? power_heuristic(bsdf_pdf, light_pdf) : REAL(0.0);
    return after_specular || !nee ? REAL(1.0) : shared_weight;
}

/* The light sample's share of what it finds (1 without multiple importance
 * sampling): the power heuristic against the density `bsdf_pdf` with which
 * the vertex's BSDF sampling picks the same direction. */
WP_FN real light_sample_weight(real light_pdf, real bsdf_pdf, int mis) {
    return mis ? power_heuristic(light_pdf, bsdf_pdf) : REAL(1.0);
}

/* Whether a material of emission `emission` emits. */
WP_FN lane_int emits(vec3 emission) {
    return emission.x > REAL(0.0) || emission.y > REAL(0.0) || emission.z > REAL(0.0);
}

/* The radiance a path of throughput `throughput` adds where it hits a
 * material of emission `emission`: its `weight` (emission_weight) of it where
 * the material emits towards the path (the ray met the `front` of the
 * surface, or the material is `two_sided`), else none. */
WP_FN vec3 emission_seen(vec3 emission, lane_int two_sided, lane_int front, real weight, vec3 throughput) {
    lane_int seen = emits(emission) && (two_sided || front) && weight > REAL(0.0);
    return v3_select(seen, v3_scale(v3_mul(throughput, emission), weight), make_vec3(REAL(0.0), REAL(0.0), REAL(0.0)));
}

/* The radiance a path of throughput `throughput` adds where it leaves the
 * scene into an environment of radiance `radiance` in its direction: its
 * `weight` (emission_weight, with the environment's light sample density) of it. */
WP_FN vec3 environment_seen(vec3 throughput, vec3 radiance, real weight) {
    return v3_scale(v3_mul(throughput, radiance), weight);
}

/* Whether a light's side that `light_normal` points to faces x from
 * `light_point`. */
WP_FN lane_int light_faces(vec3 light_normal, vec3 light_point, vec3 x) {
    return v3_dot(light_normal, v3_sub(x, light_point)) > REAL(0.0);
}

/* Whether a light sample of density `pdf_solid_angle` in direction wi from
 * the vertex (normals nf, ns) can carry light there: it is a sample, wi lies
 * above ns and leaves on nf's side, and the light emits towards the vertex
 * (it is `two_sided` or `faces_vertex`, light_faces). */
WP_FN lane_int light_sample_carries(real pdf_solid_angle, vec3 wi, vec3 nf, vec3 ns, lane_int two_sided,
                                    lane_int faces_vertex, int shading_normals) {
    return pdf_solid_angle != REAL(0.0) && v3_dot(wi, ns) > REAL(0.0) && leaves_on_side(wi, nf, shading_normals) &&
           (two_sided || faces_vertex);
}

/* What a light sample adds to the path when unoccluded: `throughput_f` (the
 * path's throughput times the BSDF's value for wi) times the emission times
 * the cosine at the surface over the sample's density `light_pdf`, times its
 * `weight` (light_sample_weight). */
WP_FN vec3 light_sample_contribution(vec3 throughput_f, vec3 emission, real cos_surface, real light_pdf, real weight) {
    return v3_scale(v3_div(v3_scale(v3_mul(throughput_f, emission), cos_surface), light_pdf), weight);
}

typedef struct {
    vec3 origin, direction; /* direction: unit */
    real distance;          /* to the far end */
} ShadowRay;

/* The shadow ray from the vertex x (error bound x_error, geometric normal nf
 * on the side the ray leaves into) to the point `light_point` sampled on a
 * light of magnitude `light_magnitude` (offset.h), whose normal
 * `light_normal` faces x where `faces_vertex`: it leaves from x offset along
 * nf and ends at the light point offset towards x by shadow_target_error, so
 * that it stops short of the light even at a grazing angle. */
WP_FN ShadowRay shadow_ray(vec3 x, real x_error, vec3 nf, vec3 light_point, vec3 light_normal, lane_int faces_vertex,
                           real light_magnitude) {
    vec3 from = offset_ray_origin(x, nf, x_error);
    vec3 to = offset_ray_origin(light_point, v3_select(faces_vertex, light_normal, v3_neg(light_normal)),
                                shadow_target_error(x, light_point, light_magnitude));
    vec3 along = v3_sub(to, from);
    ShadowRay ray;
    ray.distance = v3_length(along);
    ray.direction = v3_div(along, ray.distance);
    ray.origin = from;
    return ray;
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

typedef struct {
    vec3 throughput; /* divided by the survival probability where the roulette played */
    lane_int survives;
} RouletteOutcome;

/* Russian roulette where it `plays` (the path's depth after scattering has
 * reached rr_depth): the path survives where u < roulette_survival, with its
 * throughput divided by that probability, so its expected value stays. */
WP_FN RouletteOutcome russian_roulette(vec3 throughput, real eta_scale, lane_int plays, real u) {
    real survival = roulette_survival(throughput, eta_scale);
    RouletteOutcome outcome;
    outcome.throughput = v3_select(plays, v3_div(throughput, survival), throughput);
    outcome.survives = !plays || u < survival;
    return outcome;
}

#endif
