/* The environment map (Mitsuba 3's `envmap`): a latitude-longitude image
 * around the scene, looked up and importance-sampled the same way in every
 * backend.
 *
 * Mapping, as Mitsuba 3.9.1's (checked against it with one-hot maps): the
 * direction of (u, v) in the map's own frame is
 * (sin t sin p, cos t, -sin t cos p), p = 2 pi u, t = pi v, and to_world
 * turns it into the scene's. The image is W x H texels of linear RGB (the
 * scale applied), row 0 the file's top row; columns are centre-aligned and
 * wrap in u (texel x at u = (x + 1/2) / W), rows are corner-aligned
 * (row y at v = y / (H - 1)); the radiance between them is bilinear.
 *
 * Sampling (Mitsuba 3's envmap warp, Marginal2D): a density in (u, v)
 * that is bilinear between the texels, as the radiance is. Each texel has a
 * weight, its luminance times the mean of sin t over its band of rows (from
 * half a row above it to half a row below, within [0, pi]: sin t at an inner
 * row up to a common factor, and positive at the poles, so that light there
 * keeps a density); the host builds them in double
 * (src/scene/environment_layout.h), scaled so that their bilinear blend is
 * the density over [0, 1)^2. A cell (x, y), the patch between texel columns
 * x and x + 1 and rows y and y + 1 (u from (x + 1/2) / W, v from y / (H - 1)),
 * is chosen by its row from the marginal; v inside it follows the row's
 * density, linear between the sums of its two texel rows; the column is
 * chosen from the two rows' cumulative sums blended at that v, and u inside
 * it follows the density, linear at that v. The density per solid angle is
 * the (u, v) density over 2 pi^2 sin t, the Jacobian of the map.
 *
 * The map's data, one buffer: the texels (3 W H values); the texels'
 * densities (W H values); the marginal cumulative distribution over the
 * H - 1 rows of cells (H - 1 values, without its leading 0 and ending at 1,
 * as the light table's, select_light); then, for each of the H texel rows,
 * the cumulative sums of its W cells' edge densities, the mean of their two
 * texels' (W values, without the leading 0), in the densities' units. */
#ifndef WP_SHARED_ENVIRONMENT_MAP_H
#define WP_SHARED_ENVIRONMENT_MAP_H

#include "shared/prelude.h"
#include "shared/sampling.h"
#include "shared/texture.h"

/* The map's size and frame, the same in every lane. */
typedef struct {
    uint width, height;       /* texels; H >= 2 */
    real_element to_world[9]; /* row by row: world = to_world * in_map; orthogonal */
} EnvironmentMapLayout;

/* Where the parts of the map's data start. */
WP_FN uint environment_density_start(EnvironmentMapLayout map) { return 3u * map.width * map.height; }
WP_FN uint environment_marginal_start(EnvironmentMapLayout map) {
    return environment_density_start(map) + map.width * map.height;
}
WP_FN uint environment_row_sums_start(EnvironmentMapLayout map) {
    return environment_marginal_start(map) + map.height - 1u;
}

/* Entry i of two cumulative sequences, at start0 and start1, blended at t
 * (the two texel rows' sums at v; the marginal blends itself with itself at
 * t = 0, which is its own value). */
WP_FN real environment_blended(WP_GLOBAL const real_element *data, lane_uint start0, lane_uint start1, lane_uint i,
                               real t) {
    return (REAL(1.0) - t) * gather(data, start0 + i) + t * gather(data, start1 + i);
}

/* The first i < count with target < the blended sequence's entry i (the
 * interval holding target), by a binary search whose steps depend on
 * `count` alone (select_light's, from starts that differ between lanes).
 * A blend of two non-decreasing sequences is non-decreasing, rounded too. */
WP_FN lane_uint environment_search(WP_GLOBAL const real_element *data, lane_uint start0, lane_uint start1, uint count,
                                   real t, real target) {
    lane_uint first = 0u;
    for (uint remaining = count; remaining > 1u;) {
        uint step = remaining / 2u;
        first = target >= environment_blended(data, start0, start1, first + step - 1u, t) ? first + step : first;
        remaining -= step;
    }
    return first;
}

/* Where target falls in interval i of the blended sequence, in [0, 1): the
 * rest of the random number, for the point inside the interval. */
WP_INLINED_FN real environment_remainder(WP_GLOBAL const real_element *data, lane_uint start0, lane_uint start1,
                                         lane_uint i, real t, real target) {
    real below = i == 0u ? REAL(0.0) : environment_blended(data, start0, start1, i == 0u ? i : i - 1u, t);
    real mass = environment_blended(data, start0, start1, i, t) - below;
    real rest = mass > REAL(0.0) ? (target - below) / mass : REAL(0.0);
    return wp_clamp(rest, REAL(0.0), REAL(1.0) - WP_UNIT_ROUNDOFF);
}

/* A cell's position in the map: its column and row and the fractions
 * (fx, fy) of the way across it. */
typedef struct {
    lane_int column, row;
    real fx, fy;
} EnvironmentCellPoint;

/* The cell point of (u, v): columns centre-aligned and wrapping, rows
 * corner-aligned (v clamped to [0, 1]). */
WP_FN EnvironmentCellPoint environment_cell_point(EnvironmentMapLayout map, TextureUV uv) {
    real x = (uv.u - floor(uv.u)) * (real_element)(map.width) - REAL(0.5);
    real y = wp_clamp(uv.v, REAL(0.0), REAL(1.0)) * (real_element)(map.height - 1u);
    real x0 = floor(x), y0 = fmin(floor(y), (real_element)(map.height - 2u));
    EnvironmentCellPoint p;
    p.column = wrap_texel(floor_to_int(x0), (lane_int)(int)(map.width), WP_WRAP_REPEAT);
    p.row = floor_to_int(y0);
    p.fx = x - x0;
    p.fy = y - y0;
    return p;
}

/* The column to the right of a cell's (wrapping). */
WP_FN lane_int environment_next_column(EnvironmentMapLayout map, lane_int column) {
    return column + 1 == (lane_int)(int)(map.width) ? (lane_int)0 : column + 1;
}

/* The texel at column x (in [0, W)) of row y. */
WP_FN vec3 environment_texel(EnvironmentMapLayout map, WP_GLOBAL const real_element *data, lane_int x, lane_int y) {
    lane_uint index = TO_LANE_UINT(y * (lane_int)(int)(map.width) + x) * 3u;
    return gather_rgb(data, index);
}

/* The radiance at (u, v): bilinear between the four texels around it. */
WP_INLINED_FN vec3 environment_radiance_uv(EnvironmentMapLayout map, WP_GLOBAL const real_element *data, TextureUV uv) {
    EnvironmentCellPoint p = environment_cell_point(map, uv);
    lane_int next = environment_next_column(map, p.column);
    vec3 c00 = environment_texel(map, data, p.column, p.row), c10 = environment_texel(map, data, next, p.row);
    vec3 c01 = environment_texel(map, data, p.column, p.row + 1), c11 = environment_texel(map, data, next, p.row + 1);
    return bilinear_blend(c00, c10, c01, c11, p.fx, p.fy);
}

/* The direction d (world, unit) in the map's frame: to_world's transpose. */
WP_FN vec3 environment_local(EnvironmentMapLayout map, vec3 d) {
    const real_element *m = map.to_world;
    return make_vec3(m[0] * d.x + m[3] * d.y + m[6] * d.z, m[1] * d.x + m[4] * d.y + m[7] * d.z,
                     m[2] * d.x + m[5] * d.y + m[8] * d.z);
}

WP_FN vec3 environment_world(EnvironmentMapLayout map, vec3 in_map) {
    const real_element *m = map.to_world;
    return make_vec3(m[0] * in_map.x + m[1] * in_map.y + m[2] * in_map.z,
                     m[3] * in_map.x + m[4] * in_map.y + m[5] * in_map.z,
                     m[6] * in_map.x + m[7] * in_map.y + m[8] * in_map.z);
}

/* The (u, v) of a direction in the map's frame (unit), and its sin t. */
typedef struct {
    TextureUV uv;
    real sin_theta;
} EnvironmentPoint;

WP_FN EnvironmentPoint environment_point(vec3 in_map) {
    EnvironmentPoint p;
    p.sin_theta = sqrt(in_map.x * in_map.x + in_map.z * in_map.z);
    p.uv = make_texture_uv(atan2_turns(in_map.x, -in_map.z), REAL(2.0) * atan2_turns(p.sin_theta, in_map.y));
    return p;
}

/* The texel density at column x (in [0, W)) of row y. */
WP_FN real environment_texel_density(EnvironmentMapLayout map, WP_GLOBAL const real_element *data, lane_int x,
                                     lane_int y) {
    return gather(data, environment_density_start(map) + TO_LANE_UINT(y * (lane_int)(int)(map.width) + x));
}

/* The density along texel column x at fraction fy between rows y and
 * y + 1: a cell's left or right edge at v. */
WP_FN real environment_column_density(EnvironmentMapLayout map, WP_GLOBAL const real_element *data, lane_int x,
                                      lane_int y, real fy) {
    return (REAL(1.0) - fy) * environment_texel_density(map, data, x, y) +
           fy * environment_texel_density(map, data, x, y + 1);
}

/* The density in (u, v) at a cell point: the bilinear blend of its four
 * texels' densities. */
WP_FN real environment_density_uv(EnvironmentMapLayout map, WP_GLOBAL const real_element *data,
                                  EnvironmentCellPoint p) {
    lane_int next = environment_next_column(map, p.column);
    real row0 = (REAL(1.0) - p.fx) * environment_texel_density(map, data, p.column, p.row) +
                p.fx * environment_texel_density(map, data, next, p.row);
    real row1 = (REAL(1.0) - p.fx) * environment_texel_density(map, data, p.column, p.row + 1) +
                p.fx * environment_texel_density(map, data, next, p.row + 1);
    return (REAL(1.0) - p.fy) * row0 + p.fy * row1;
}

/* The density per solid angle of a direction of density density_uv in
 * (u, v) and its sin t: over the map's Jacobian 2 pi^2 sin t. */
WP_FN real environment_solid_angle_pdf(real density_uv, real sin_theta) {
    return sin_theta > REAL(0.0) ? density_uv / (REAL(2.0) * WP_PI * WP_PI * sin_theta) : REAL(0.0);
}

/* The density per solid angle with which environment_sample picks the
 * world direction d (unit). */
WP_FN real environment_pdf(EnvironmentMapLayout map, WP_GLOBAL const real_element *data, vec3 d) {
    EnvironmentPoint p = environment_point(environment_local(map, d));
    return environment_solid_angle_pdf(environment_density_uv(map, data, environment_cell_point(map, p.uv)),
                                       p.sin_theta);
}

/* The radiance that arrives from world direction d (unit): what a ray
 * leaving the scene along d sees. */
WP_FN vec3 environment_radiance(EnvironmentMapLayout map, WP_GLOBAL const real_element *data, vec3 d) {
    return environment_radiance_uv(map, data, environment_point(environment_local(map, d)).uv);
}

/* A direction towards the environment, its radiance and its density per
 * solid angle (0 where it has none). */
typedef struct {
    vec3 direction, radiance;
    real pdf;
} EnvironmentSample;

/* The direction of (u1, u2) (in [0, 1)^2) by the bilinear density. */
WP_FN EnvironmentSample environment_sample(EnvironmentMapLayout map, WP_GLOBAL const real_element *data, real u1,
                                           real u2) {
    uint rows = map.height - 1u;
    lane_uint marginal = (lane_uint)environment_marginal_start(map);
    EnvironmentCellPoint p;
    lane_uint row = environment_search(data, marginal, marginal, rows, REAL(0.0), u1);
    p.row = TO_LANE_INT(row);
    lane_uint sums0 = environment_row_sums_start(map) + row * map.width, sums1 = sums0 + map.width;
    real row_sum0 = gather(data, sums0 + (map.width - 1u)), row_sum1 = gather(data, sums1 + (map.width - 1u));
    p.fy = sample_linear(environment_remainder(data, marginal, marginal, row, REAL(0.0), u1), row_sum0, row_sum1);
    real target = u2 * ((REAL(1.0) - p.fy) * row_sum0 + p.fy * row_sum1);
    lane_uint column = environment_search(data, sums0, sums1, map.width, p.fy, target);
    p.column = TO_LANE_INT(column);
    lane_int next = environment_next_column(map, p.column);
    real left = environment_column_density(map, data, p.column, p.row, p.fy);
    real right = environment_column_density(map, data, next, p.row, p.fy);
    p.fx = sample_linear(environment_remainder(data, sums0, sums1, column, p.fy, target), left, right);
    real u = (TO_REAL(column) + p.fx + REAL(0.5)) / (real_element)(map.width);
    u = u >= REAL(1.0) ? u - REAL(1.0) : u;
    real v = (TO_REAL(row) + p.fy) / (real_element)(rows);
    CosSin phi = cos_sin_turns(u), theta = cos_sin_turns(REAL(0.5) * v);
    vec3 in_map = make_vec3(theta.sin_value * phi.sin_value, theta.cos_value, -theta.sin_value * phi.cos_value);
    EnvironmentSample s;
    s.direction = environment_world(map, in_map);
    s.radiance = environment_radiance_uv(map, data, make_texture_uv(u, v));
    s.pdf = environment_solid_angle_pdf((REAL(1.0) - p.fx) * left + p.fx * right, theta.sin_value);
    return s;
}

#endif
