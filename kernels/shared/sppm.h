/* Stochastic progressive photon mapping (Hachisuka and Jensen, 2009; the
 * form of pbrt-v4's SPPMIntegrator; docs/architecture.md, "Photon
 * mapping"): what a photon adds to a pixel's visible point, and each
 * pixel's update after an iteration. The visible points themselves are
 * written where the camera path first meets a non-specular surface (diffuse,
 * rough, or a plastic whose base its lobe choice took), the photons found
 * through the grid of shared/photon_grid.h, and the material's f evaluated,
 * by the caller. */
#ifndef WP_SHARED_SPPM_H
#define WP_SHARED_SPPM_H

#include "shared/materials/bsdf.h"
#include "shared/materials/diffuse.h"
#include "shared/prelude.h"

/* A pixel's visible point has no depth where its camera path met no
 * non-specular surface in the iteration (it left the scene, hit an emitter, or ended). */
#define WP_NO_VISIBLE_POINT 0xffffffffu

/* Whether SPPM's camera pass bounces once more from a visible point, to
 * add the emission it finds there: only where emission after a
 * non-specular vertex (which next-event estimation samples) can count (emission_weight, shared/estimator.h): without
 * next-event estimation, or with multiple importance sampling, whose light sample at the visible point counts only its
 * share. Photons add what arrives after more scattering. */
WP_FN int camera_pass_bounces_from_visible_point(int nee, int mis) { return !nee || mis; }

/* Whether a photon at x falls within the visible point at `center` of
 * radius `radius`. */
WP_FN lane_int photon_within(vec3 center, real radius, vec3 x) {
    vec3 d = v3_sub(x, center);
    return v3_dot(d, d) < radius * radius;
}

/* Whether a photon that has scattered `photon_depth` times may add to a
 * visible point `visible_depth` camera bounces deep: the path they join
 * scatters visible_depth + 1 + photon_depth times, at most max_depth as in
 * path tracing; a photon that has not scattered (depth 0) is direct light,
 * which the camera pass counts. */
WP_FN lane_int photon_depth_counts(lane_uint visible_depth, lane_uint photon_depth, uint max_depth) {
    return visible_depth != WP_NO_VISIBLE_POINT && photon_depth >= 1u && visible_depth + 1u + photon_depth <= max_depth;
}

/* What a photon carrying `power` along `direction` adds to the flux of a
 * visible point of normals nf and ns (on the camera's side) whose material
 * reflects or, where it `transmits`, also transmits: `throughput_f`, the
 * camera path's throughput times the material's f(wo, wi) for the photon's
 * wi = -direction (as next-event estimation evaluates it: radiance
 * transport), times power, where wi lies on nf's side (or behind it, where
 * the material transmits) with shading normals. The density estimate
 * counts flux per unit of geometric area, where the shading model wants the
 * cosine to ns: with shading normals each photon takes |wi.ns| / |wi.nf|
 * (the adjoint correction at the gathering vertex, shading_normal_adjoint).
 * A diffuse visible point's throughput_f is diffuse_eval of its weight (the
 * throughput times the albedo, textured where it is). */
WP_FN vec3 photon_deposit(vec3 throughput_f, vec3 nf, vec3 ns, lane_int transmits, vec3 direction, vec3 power,
                          int shading_normals) {
    vec3 wi = v3_neg(direction);
    lane_int behind = transmits && v3_dot(wi, nf) < REAL(0.0);
    lane_int arrives = leaves_on_side(wi, v3_select(behind, v3_neg(nf), nf), shading_normals);
    real correction = shading_normals ? fabs(v3_dot(wi, ns)) / fabs(v3_dot(wi, nf)) : (real)REAL(1.0);
    vec3 deposit = v3_scale(v3_mul(throughput_f, power), correction);
    return v3_select(arrives, deposit, make_vec3(REAL(0.0), REAL(0.0), REAL(0.0)));
}

/* A visible point's throughput times f (photon_deposit's first argument)
 * where it is finite, else 0: a deposit goes into an exact fixed-point sum,
 * which has no room for NaN or Inf (film_sum.h). A diffuse point's always
 * is; a microfacet's may not be at a grazing degenerate pair, which
 * next-event estimation drops the same way (add_finite). */
WP_FN vec3 finite_visible_f(vec3 throughput_f) {
    return v3_select(vec3_is_finite(throughput_f), throughput_f, make_vec3(REAL(0.0), REAL(0.0), REAL(0.0)));
}

/* A visible point's material and the side of its surface the camera path
 * met (the rough dielectric's eval needs it) in one word: the material's
 * index times 2, plus 1 on the front (the side its geometric normal points
 * to). */
WP_FN lane_uint visible_material_word(lane_uint material, lane_int front) {
    return material * 2u + (front ? (lane_uint)1u : (lane_uint)0u);
}
WP_FN lane_uint visible_material_index(lane_uint word) { return word >> 1; }
WP_FN lane_int visible_material_front(lane_uint word) { return (word & 1u) != 0u; }

/* Each pixel's first gathering radius, from its footprint: the width of
 * the camera ray's cone where it meets the pixel's visible point (a ray
 * cone, as in Amanatides 1984 and Akenine-Moller et al. 2019). The cone
 * spreads by `pixel_spread` (the pixel's angle at the image's centre,
 * 2 tan(fov_y / 2) / height: sppm_pixel_spread, src/scene/scene.cpp) per
 * unit of the `distance` the camera path travelled to the point, summed over
 * every mirror and glass bounce before it. The bound through specular
 * bounces: exact through flat mirrors; through flat glass with parallel
 * faces (a window, a slab) at most the path length, since inside the glass
 * the cone spreads at most 1/eta as fast and leaves it as it came; a curved
 * mirror or lens changes the spread by its curvature, which the path length
 * does not follow (behind a convex mirror or a diverging lens the footprint
 * is wider, behind a focusing one narrower, down to the focus). The width is
 * taken across the ray: off the image's centre a pixel's angle is a little
 * smaller (cos^2 of the angle off the axis), and on a surface seen at a
 * grazing angle the footprint is longer along the view (1 / cos). So the
 * radius follows the pixel's size and the distance, and depends on neither
 * the scene's extent nor its units. */
#define WP_SPPM_FOOTPRINTS REAL(2.0) /* the first radius, in footprints */

/* The footprint of a pixel whose cone spreads by `pixel_spread` per unit of
 * distance at the visible point `distance` away along the camera path. */
WP_FN real sppm_footprint(real pixel_spread, real distance) { return pixel_spread * distance; }

/* The radius a pixel takes at its first visible point: `override_radius`
 * where set (> 0: render.sppm.radius, --initial-radius), otherwise
 * WP_SPPM_FOOTPRINTS footprints. Until a pixel has had a visible point its
 * radius is 0 (unset): it gathers nothing. */
WP_FN real sppm_first_radius(real override_radius, real footprint) {
    return override_radius > REAL(0.0) ? override_radius : WP_SPPM_FOOTPRINTS * footprint;
}

/* A pixel's progressive estimate: N (`count`, the photons it has kept),
 * the radius r and tau (`flux`, the flux gathered within it). */
typedef struct {
    real count, radius;
    vec3 flux;
} SppmPixel;

/* The update after an iteration in which `photons` (M) photons fell within
 * the radius and deposited `deposited` (Phi), with gamma = alpha:
 *   N' = N + alpha M,  r'^2 = r^2 N' / (N + M),  tau' = (tau + Phi) r'^2 / r^2,
 * so the radius shrinks as the photons come (Hachisuka and Jensen, eq. 7
 * and 11). Nothing changes where no photon came. */
WP_FN SppmPixel sppm_pixel_update(SppmPixel pixel, lane_uint photons, vec3 deposited, real alpha) {
    real m = TO_REAL(photons);
    real count = pixel.count + alpha * m;
    real shrink = count / (pixel.count + m); /* r'^2 / r^2 */
    lane_int came = photons > 0u;
    SppmPixel next;
    next.count = came ? count : pixel.count;
    next.radius = came ? pixel.radius * sqrt(shrink) : pixel.radius;
    next.flux = v3_select(came, v3_scale(v3_add(pixel.flux, deposited), shrink), pixel.flux);
    return next;
}

#endif
