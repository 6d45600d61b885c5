/* Textures, as Mitsuba 3 defines them: where a hit lies in texture space
 * (its uv: Mitsuba's parameterisation of spheres and rectangles, a mesh's
 * interpolated vertex uvs) and what a texture holds there. A `bitmap` is
 * read with its wrap mode and filter exactly as Mitsuba's (checked against
 * Mitsuba 3.9.1 in tests/shared/texture_test.cpp): texel (x, y) covers
 * [x, x + 1] / width by [y, y + 1] / height, its centre at +0.5, row 0 at
 * v = 0 (no flip); bilinear blends the four texels around
 * uv * size - 0.5. A `checkerboard` is color0 where the fractional parts
 * of u and v are both above 1/2 or both not, else color1. Both first map
 * the uv by their to_uv, an affine map u' = m0 u + m1 v + m2,
 * v' = m3 u + m4 v + m5. Only arithmetic, floor and sqrt: the same values
 * in every backend. */
#ifndef WP_SHARED_TEXTURE_H
#define WP_SHARED_TEXTURE_H

#include "shared/prelude.h"
#include "shared/special_functions.h"

#define WP_TEXTURE_BITMAP 0u
#define WP_TEXTURE_CHECKERBOARD 1u
#define WP_FILTER_BILINEAR 0u
#define WP_FILTER_NEAREST 1u
#define WP_WRAP_REPEAT 0u
#define WP_WRAP_MIRROR 1u
#define WP_WRAP_CLAMP 2u
/* A material parameter that is its constant, not a texture. */
#define WP_NO_TEXTURE 0xffffffffu

/* A texture as device memory holds it (one table for the scene; the bitmaps'
 * texels in one buffer of linear RGB, 3 values per texel, row by row). */
typedef struct {
    uint type;              /* WP_TEXTURE_* */
    uint filter, wrap;      /* bitmap: WP_FILTER_*, WP_WRAP_* */
    uint width, height;     /* bitmap */
    uint first_texel;       /* bitmap: its texel (0, 0) in the texel buffer */
    real_element to_uv[6];  /* m0..m5 above */
    real_element color0[3]; /* checkerboard */
    real_element color1[3];
} TextureDescriptor;

/* A mesh triangle's vertex uvs, parallel to the triangles. A mesh without
 * uvs has (0, 0), (1, 0), (0, 1): its uv is then the hit's barycentric
 * coordinates (b1, b2), as Mitsuba's. */
typedef struct {
    real_element uv0[2], uv1[2], uv2[2];
} TriangleUVs;

/* A texture's fields, per lane. */
typedef struct {
    lane_uint type, filter, wrap, width, height, first_texel;
    real to_uv[6];
    vec3 color0, color1;
} Texture;

typedef struct {
    real u, v;
} TextureUV;

WP_FN TextureUV make_texture_uv(real u, real v) {
    TextureUV uv;
    uv.u = u, uv.v = v;
    return uv;
}

/* Mitsuba's sphere: u the azimuth atan2(y, x) in turns, v the polar angle
 * from +z over pi, of the unit normal (the sphere's own axes are the
 * world's: spheres are a centre and a radius). */
WP_FN TextureUV sphere_uv(vec3 normal) {
    real rho = sqrt(normal.x * normal.x + normal.y * normal.y);
    return make_texture_uv(atan2_turns(normal.y, normal.x), REAL(2.0) * atan2_turns(rho, normal.z));
}

/* A quad's point corner + u edge1 + v edge2 (Mitsuba's rectangle maps its
 * corner (-1, -1) to uv (0, 0), +x to u, +y to v; the converter writes the
 * quad so). */
WP_FN TextureUV quad_uv(vec3 corner, vec3 edge1, vec3 edge2, vec3 p) {
    vec3 n = v3_cross(edge1, edge2), d = v3_sub(p, corner);
    real n2 = v3_dot(n, n);
    return make_texture_uv(v3_dot(v3_cross(d, edge2), n) / n2, v3_dot(v3_cross(edge1, d), n) / n2);
}

/* The uv at barycentric coordinates (b1, b2) of a triangle with vertex uvs
 * uv0, uv1, uv2. */
WP_FN TextureUV triangle_uv(TextureUV uv0, TextureUV uv1, TextureUV uv2, real b1, real b2) {
    real b0 = REAL(1.0) - b1 - b2;
    return make_texture_uv(b0 * uv0.u + b1 * uv1.u + b2 * uv2.u, b0 * uv0.v + b1 * uv1.v + b2 * uv2.v);
}

WP_FN TextureUV texture_transform(Texture t, TextureUV uv) {
    return make_texture_uv(t.to_uv[0] * uv.u + t.to_uv[1] * uv.v + t.to_uv[2],
                           t.to_uv[3] * uv.u + t.to_uv[4] * uv.v + t.to_uv[5]);
}

/* x mod size, in [0, size), for size > 0, exactly. The quotient comes from
 * a division in real: for |x| < 2^24 both are exact in float and the
 * division rounds correctly, so its floor is the true quotient or one more,
 * which the last line corrects. An integer division (a loop over the lanes
 * in vector code, several times the rest's cost) only where some lane lies
 * beyond, at a uv of millions of texels. */
WP_FN lane_int floor_mod(lane_int x, lane_int size) {
    lane_int remainder = x - TO_LANE_INT(floor(TO_REAL(x) / TO_REAL(size))) * size; /* in [-size, size) */
    if (lanes_any(x >= (1 << 24) || x <= -(1 << 24))) remainder = x % size;         /* in (-size, size) */
    return remainder < 0 ? remainder + size : remainder;
}

/* Texel coordinate x (an integer) of a row or column of `size` texels
 * wrapped into [0, size) by WP_WRAP_*: repeat; mirror (-1 -> 0, size ->
 * size - 1); clamp to the edge. A mode's work is done only where some lane
 * has that mode. */
WP_FN lane_int wrap_texel(lane_int x, lane_int size, lane_uint wrap) {
    lane_int wrapped = x < 0 ? (lane_int)0 : (x >= size ? size - 1 : x); /* clamped */
    if (lanes_any(wrap == WP_WRAP_REPEAT)) wrapped = wrap == WP_WRAP_REPEAT ? floor_mod(x, size) : wrapped;
    if (lanes_any(wrap == WP_WRAP_MIRROR)) {
        lane_int reflected = floor_mod(x < 0 ? -x - 1 : x, size + size);
        reflected = reflected >= size ? size + size - 1 - reflected : reflected;
        wrapped = wrap == WP_WRAP_MIRROR ? reflected : wrapped;
    }
    return wrapped;
}

/* floor(x) as an integer, x first clamped to +-2^30 so that any uv (a huge
 * or non-finite one too) converts without overflow. */
WP_FN lane_int floor_to_int(real x) { return TO_LANE_INT(floor(wp_clamp(x, REAL(-1073741824.0), REAL(1073741824.0)))); }

/* The bilinear blend of the four texels around a point, c00 at (0, 0) and
 * c11 at (1, 1), at fractions (fx, fy) between them (bitmaps and
 * environment maps alike). */
WP_FN vec3 bilinear_blend(vec3 c00, vec3 c10, vec3 c01, vec3 c11, real fx, real fy) {
    vec3 row0 = v3_add(v3_scale(c00, REAL(1.0) - fx), v3_scale(c10, fx));
    vec3 row1 = v3_add(v3_scale(c01, REAL(1.0) - fx), v3_scale(c11, fx));
    return v3_add(v3_scale(row0, REAL(1.0) - fy), v3_scale(row1, fy));
}

/* The texel at column and row (wrapped already). */
WP_FN vec3 bitmap_texel(Texture t, WP_GLOBAL const real_element *texels, lane_int column, lane_int row) {
    lane_uint index = (t.first_texel + TO_LANE_UINT(row * TO_LANE_INT(t.width) + column)) * 3u;
    return gather_rgb(texels, index);
}

/* The four texels around a point of a bitmap (c00 at its lower column and
 * row) and the point's fractions (fx, fy) between them, for a bilinear
 * blend; the wrapped coordinates of the two columns and two rows are found
 * once each. */
typedef struct {
    vec3 c00, c10, c01, c11;
    real fx, fy;
} BilinearTexels;

WP_FN BilinearTexels bilinear_texels(Texture t, WP_GLOBAL const real_element *texels, real x, real y) {
    lane_int width = TO_LANE_INT(t.width), height = TO_LANE_INT(t.height);
    BilinearTexels b;
    x = x - REAL(0.5), y = y - REAL(0.5);
    real x0 = floor(x), y0 = floor(y);
    b.fx = x - x0, b.fy = y - y0;
    lane_int ix = floor_to_int(x0), iy = floor_to_int(y0);
    lane_int column0 = wrap_texel(ix, width, t.wrap), column1 = wrap_texel(ix + 1, width, t.wrap);
    lane_int row0 = wrap_texel(iy, height, t.wrap), row1 = wrap_texel(iy + 1, height, t.wrap);
    b.c00 = bitmap_texel(t, texels, column0, row0), b.c10 = bitmap_texel(t, texels, column1, row0);
    b.c01 = bitmap_texel(t, texels, column0, row1), b.c11 = bitmap_texel(t, texels, column1, row1);
    return b;
}

/* The nearest texel, or the bilinear blend of the four around uv, each
 * only where some lane's filter is that one. */
WP_FN vec3 bitmap_value(Texture t, WP_GLOBAL const real_element *texels, TextureUV uv) {
    lane_int width = TO_LANE_INT(t.width), height = TO_LANE_INT(t.height);
    real x = uv.u * TO_REAL(t.width), y = uv.v * TO_REAL(t.height);
    lane_int nearest = t.filter == WP_FILTER_NEAREST;
    vec3 value = make_vec3(REAL(0.0), REAL(0.0), REAL(0.0));
    if (lanes_any(nearest)) {
        value = bitmap_texel(t, texels, wrap_texel(floor_to_int(x), width, t.wrap),
                             wrap_texel(floor_to_int(y), height, t.wrap));
    }
    if (lanes_any(!nearest)) {
        BilinearTexels b = bilinear_texels(t, texels, x, y);
        value = v3_select(nearest, value, bilinear_blend(b.c00, b.c10, b.c01, b.c11, b.fx, b.fy));
    }
    return value;
}

WP_FN vec3 checkerboard_value(Texture t, TextureUV uv) {
    lane_int u_high = uv.u - floor(uv.u) > REAL(0.5), v_high = uv.v - floor(uv.v) > REAL(0.5);
    return v3_select(u_high == v_high, t.color0, t.color1);
}

/* Texture t's value at the hit's uv. */
WP_INLINED_FN vec3 texture_value(Texture t, WP_GLOBAL const real_element *texels, TextureUV hit_uv) {
    TextureUV uv = texture_transform(t, hit_uv);
    lane_int checkerboard = t.type == WP_TEXTURE_CHECKERBOARD;
    vec3 value = checkerboard_value(t, uv);
    if (lanes_any(!checkerboard)) value = v3_select(checkerboard, value, bitmap_value(t, texels, uv));
    return value;
}

/* A material's colour parameter at a hit of uv `uv`: its constant
 * (`untextured`; `constant` is OpenCL C's address space), or where
 * the material gives it a texture (`texture`, an index into the textures, is
 * not WP_NO_TEXTURE) that texture's value there; t is the textures' entry
 * `texture` (any entry where there is none). Every backend reads every
 * textured colour parameter through this. */
WP_FN vec3 colour_parameter(vec3 untextured, lane_uint texture, Texture t, WP_GLOBAL const real_element *texels,
                            TextureUV uv) {
    return v3_select(texture != WP_NO_TEXTURE, texture_value(t, texels, uv), untextured);
}

/* A colour's luminance, as Mitsuba's eval_1 reads a bitmap's. */
WP_FN real texture_luminance(vec3 c) { return REAL(0.212671) * c.x + REAL(0.715160) * c.y + REAL(0.072169) * c.z; }

/* A material's scalar parameter (a roughness) at a hit of uv `uv`, as
 * colour_parameter: its constant, or its texture's value there read as
 * Mitsuba's eval_1 reads a colour texture: a bitmap's luminance, a
 * checkerboard's channel mean (checked against Mitsuba 3.9.1). */
WP_FN real scalar_parameter(real untextured, lane_uint texture, Texture t, WP_GLOBAL const real_element *texels,
                            TextureUV uv) {
    vec3 c = texture_value(t, texels, uv);
    real luminance = texture_luminance(c);
    real mean = (c.x + c.y + c.z) / REAL(3.0);
    real value = t.type == WP_TEXTURE_CHECKERBOARD ? mean : luminance;
    return texture != WP_NO_TEXTURE ? value : untextured;
}

/* The gradient of a bitmap's scalar value (its luminance, scalar_parameter)
 * over the hit's uv, as Mitsuba 3.9.1's eval_1_grad: with the bilinear
 * filter the exact derivative of the blend (per texel: times the width and
 * height), through to_uv to the hit's uv (the chain rule: d/du = m0 d/du' +
 * m3 d/dv', d/dv = m1 d/du' + m4 d/dv'); zero with the nearest filter.
 * (Mitsuba has no checkerboard gradient: the readers refuse one where a
 * gradient is needed.) */
WP_FN TextureUV texture_gradient(Texture t, WP_GLOBAL const real_element *texels, TextureUV hit_uv) {
    TextureUV uv = texture_transform(t, hit_uv);
    BilinearTexels b = bilinear_texels(t, texels, uv.u * TO_REAL(t.width), uv.v * TO_REAL(t.height));
    vec3 along_x = v3_add(v3_scale(v3_sub(b.c10, b.c00), REAL(1.0) - b.fy), v3_scale(v3_sub(b.c11, b.c01), b.fy));
    vec3 along_y = v3_add(v3_scale(v3_sub(b.c01, b.c00), REAL(1.0) - b.fx), v3_scale(v3_sub(b.c11, b.c10), b.fx));
    lane_int linear = t.filter == WP_FILTER_BILINEAR;
    real dx = linear ? texture_luminance(along_x) * TO_REAL(t.width) : REAL(0.0);
    real dy = linear ? texture_luminance(along_y) * TO_REAL(t.height) : REAL(0.0);
    return make_texture_uv(t.to_uv[0] * dx + t.to_uv[3] * dy, t.to_uv[1] * dx + t.to_uv[4] * dy);
}

#endif
