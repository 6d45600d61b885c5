/* The `mask` adapter (Mitsuba 3's mask): an opacity o in [0, 1], maybe
 * textured, around a nested material. The surface scatters with the nested
 * material with probability o and lets the ray pass straight through
 * otherwise: f = o f_nested + (1 - o) delta(wi = -wo). As in Mitsuba, a
 * sample picks the pass with probability 1 - o (its weight is then 1, a
 * delta lobe) and the nested material's lobe with probability o (its weight
 * unchanged, its density times o), reusing the one uniform number for both
 * choices; f and the density that next-event estimation and MIS evaluate
 * are the nested material's times o. A pass is a bounce like any other: it
 * counts towards max_depth and the roulette, as Mitsuba's path integrator
 * counts it. Shadow rays are blocked by a mask's surface as by any other
 * (Mitsuba's too): light through it arrives by the pass, whose delta lobe
 * gives the emission it reaches its full weight, so the estimate stays
 * unbiased. Conventions: shared/materials/bsdf.h. */
#ifndef WP_SHARED_MATERIALS_MASK_H
#define WP_SHARED_MATERIALS_MASK_H

#include "shared/materials/bsdf.h"
#include "shared/prelude.h"

/* The opacity as the mask uses it: a texture's value clamped to [0, 1]
 * (Mitsuba's dr::clip; the readers hold constants to [0, 1]). */
WP_FN real mask_opacity(real opacity) { return fmin(fmax(opacity, REAL(0.0)), REAL(1.0)); }

/* Whether the uniform number u in [0, 1) lets the ray pass: u >= opacity,
 * probability 1 - opacity (never where opacity is 1). */
WP_FN lane_int mask_passes(real opacity, real u) { return u >= opacity; }

/* The nested material's lobe number where u < opacity: u / opacity, uniform
 * in [0, 1) again. It stays below 1 in float: u is at most the float below
 * opacity, opacity - ulp(opacity), and ulp(o) / o >= 2^-24 for any normal
 * float o, so u / opacity <= 1 - 2^-24, itself a float, and rounds to at
 * most it. Lanes that pass keep u (their quotient, maybe 0 / 0, is
 * discarded). */
WP_FN real mask_nested_lobe(real opacity, real u) { return mask_passes(opacity, u) ? u : u / opacity; }

/* The pass along d from the point whose geometric normal on the arriving
 * side is nf: the same direction, weight 1, leaving into the other side. */
WP_FN BsdfSample mask_pass_sample(vec3 d, vec3 nf) {
    BsdfSample s;
    s.direction = d;
    s.weight = make_vec3(REAL(1.0), REAL(1.0), REAL(1.0));
    s.leave_side = v3_neg(nf);
    s.pdf = REAL(0.0);
    s.eta_squared = REAL(1.0);
    s.specular = 1u;
    s.valid = 1;
    return s;
}

/* The mask's sample: the pass where `passes`, else the nested material's
 * sample `nested` (drawn with mask_nested_lobe's number) with its density
 * times the opacity, the probability of having chosen it. */
WP_FN BsdfSample mask_sample(real opacity, lane_int passes, BsdfSample nested, vec3 d, vec3 nf) {
    nested.pdf = nested.pdf * opacity;
    return select_bsdf_sample(passes, mask_pass_sample(d, nf), nested);
}

#endif
