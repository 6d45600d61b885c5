/* Spawned-ray origins without a fixed epsilon: Waechter and Binder, "A Fast
 * and Robust Method for Avoiding Self-Intersection" (Ray Tracing Gems, ch. 6).
 * The point moves along the geometric normal by a fixed number of ULPs of its
 * own coordinates, so the offset scales with the scene's magnitude; near the
 * origin, where ULPs vanish, a tiny absolute step takes over. The constants
 * are the chapter's for float; the double build keeps the same relative
 * offset by scaling the ULP count with the extra mantissa bits. */

#define WP_OFFSET_ORIGIN REAL(0.03125)
#define WP_OFFSET_FLOAT_SCALE (REAL(1.52587890625e-05) / (real)((real_bits)1 << (WP_REAL_MANTISSA_BITS - 24)))
#define WP_OFFSET_INT_SCALE (REAL(256.0) * (real)((real_bits)1 << (WP_REAL_MANTISSA_BITS - 24)))

WP_FN real offset_coordinate(real p, real n) {
    real_bits of_i = (real_bits)(WP_OFFSET_INT_SCALE * n);
    real p_i = bits_as_real(real_as_bits(p) + (p < REAL(0.0) ? -of_i : of_i));
    return fabs(p) < WP_OFFSET_ORIGIN ? p + WP_OFFSET_FLOAT_SCALE * n : p_i;
}

/* `n` is the unit geometric normal pointing to the side the ray leaves into. */
WP_FN vec3 offset_ray_origin(vec3 p, vec3 n) {
    return make_vec3(offset_coordinate(p.x, n.x), offset_coordinate(p.y, n.y), offset_coordinate(p.z, n.z));
}
