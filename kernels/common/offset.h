/* Spawned-ray origins without a fixed epsilon, after Waechter and Binder,
 * "A Fast and Robust Method for Avoiding Self-Intersection" (Ray Tracing
 * Gems, ch. 6): the point moves along the geometric normal by a fixed number
 * of float ULPs, so the offset scales with the scene's magnitude.
 *
 * The ULPs are those of the point's largest coordinate, for all three
 * components: a hit point's rounding error comes from all of its
 * coordinates, so a component near zero needs as large a step as the others.
 * The chapter's absolute floor near the origin (1/65536 below 1/32) is left
 * out: with camera-relative coordinates the viewer sits at the origin, and
 * that floor would be larger than a small scene. Scaling a scene by 2^k
 * scales every offset by exactly 2^k.
 *
 * The step is 256 float ULPs (2^-15 relative, as the chapter's int_scale);
 * the double build keeps the same relative step, so that both precisions
 * render the same geometry. */

#define WP_OFFSET_RELATIVE REAL(3.0517578125e-05) /* 2^-15 */

/* The largest power of two not above |x|; 0 for zero and subnormals. */
WP_FN real power_of_two_floor(real x) {
    return bits_as_real((real_as_bits(fabs(x)) >> (WP_REAL_MANTISSA_BITS - 1)) << (WP_REAL_MANTISSA_BITS - 1));
}

/* `n` is the unit geometric normal pointing to the side the ray leaves into. */
WP_FN vec3 offset_ray_origin(vec3 p, vec3 n) {
    real magnitude = fmax(fabs(p.x), fmax(fabs(p.y), fabs(p.z)));
    return p + (WP_OFFSET_RELATIVE * power_of_two_floor(magnitude)) * n;
}
