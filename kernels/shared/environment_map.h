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
 * Sampling: a piecewise-constant density over W x (H - 1) cells in (u, v),
 * cell (x, y) the bilinear patch between texel columns x and x + 1 and rows
 * y and y + 1 (u from (x + 1/2) / W, v from y / (H - 1)), its weight the
 * mean luminance of its four corner texels times sin t at its centre; the
 * host builds it in double (src/scene/environment_layout.h). A cell is
 * chosen by its row (the marginal) and then its column (the row's
 * conditional), and the point in it is uniform. The density per solid
 * angle is the (u, v) density over 2 pi^2 sin t, the Jacobian of the map.
 *
 * The map's data, one buffer: the texels (3 W H values), the marginal
 * cumulative distribution over the H - 1 rows of cells (H - 1 values), then
 * each row's over its W cells (W (H - 1) values); each cumulative
 * distribution leaves out its leading 0 and ends at 1, as the light table's
 * (select_light). */
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

/* Where the cumulative distributions start in the map's data. */
WP_FN uint environment_marginal_start(EnvironmentMapLayout map) { return 3u * map.width * map.height; }
WP_FN uint environment_conditional_start(EnvironmentMapLayout map) {
    return environment_marginal_start(map) + map.height - 1u;
}

/* The first i < count with u < cdf[start + i] (the interval holding u), by a
 * binary search whose steps depend on `count` alone (select_light's, from a
 * start that differs between lanes). */
WP_FN lane_uint environment_search(WP_GLOBAL const real_element *data, lane_uint start, uint count, real u) {
    lane_uint first = 0u;
    for (uint remaining = count; remaining > 1u;) {
        uint step = remaining / 2u;
        first = u >= gather(data, start + first + step - 1u) ? first + step : first;
        remaining -= step;
    }
    return first;
}

/* Interval i of the cumulative distribution at start: where it begins and
 * its probability. */
typedef struct {
    real below, pmf;
} CdfInterval;

WP_FN CdfInterval environment_interval(WP_GLOBAL const real_element *data, lane_uint start, lane_uint i) {
    CdfInterval interval;
    interval.below = i == 0u ? REAL(0.0) : gather(data, i == 0u ? start : start + i - 1u);
    interval.pmf = gather(data, start + i) - interval.below;
    return interval;
}

/* The texel at column x (in [0, W)) of row y. */
WP_FN vec3 environment_texel(EnvironmentMapLayout map, WP_GLOBAL const real_element *data, lane_int x, lane_int y) {
    lane_uint index = TO_LANE_UINT(y * (lane_int)(int)(map.width) + x) * 3u;
    return gather_rgb(data, index);
}

/* The radiance at (u, v): bilinear between the centre-aligned columns
 * (u wraps) and the corner-aligned rows (v clamped to [0, 1]). */
WP_FN vec3 environment_radiance_uv(EnvironmentMapLayout map, WP_GLOBAL const real_element *data, TextureUV uv) {
    real x = (uv.u - floor(uv.u)) * (real_element)(map.width) - REAL(0.5);
    real y = wp_clamp(uv.v, REAL(0.0), REAL(1.0)) * (real_element)(map.height - 1u);
    real x0 = floor(x), y0 = fmin(floor(y), (real_element)(map.height - 2u));
    real fx = x - x0, fy = y - y0;
    lane_int ix = floor_to_int(x0), iy = floor_to_int(y0);
    lane_int width = (lane_int)(int)(map.width);
    lane_int column0 = wrap_texel(ix, width, WP_WRAP_REPEAT), column1 = wrap_texel(ix + 1, width, WP_WRAP_REPEAT);
    vec3 c00 = environment_texel(map, data, column0, iy), c10 = environment_texel(map, data, column1, iy);
    vec3 c01 = environment_texel(map, data, column0, iy + 1), c11 = environment_texel(map, data, column1, iy + 1);
    return bilinear_blend(c00, c10, c01, c11, fx, fy);
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

/* The density per solid angle of a direction at (u, v), sin t given: its
 * cell's probability times the cells' count, over 2 pi^2 sin t. */
WP_FN real environment_pdf_uv(EnvironmentMapLayout map, WP_GLOBAL const real_element *data, TextureUV uv,
                              real sin_theta) {
    uint rows = map.height - 1u;
    real x = (uv.u - floor(uv.u)) * (real_element)(map.width) - REAL(0.5);
    lane_int column = wrap_texel(floor_to_int(x), (lane_int)(int)(map.width), WP_WRAP_REPEAT);
    real y = wp_clamp(uv.v, REAL(0.0), REAL(1.0)) * (real_element)(rows);
    lane_uint row = TO_LANE_UINT(floor_to_int(fmin(y, (real_element)(rows - 1u))));
    CdfInterval row_interval = environment_interval(data, (lane_uint)environment_marginal_start(map), row);
    CdfInterval column_interval =
        environment_interval(data, environment_conditional_start(map) + row * map.width, TO_LANE_UINT(column));
    real density_uv = row_interval.pmf * column_interval.pmf * (real_element)(map.width * rows);
    return sin_theta > REAL(0.0) ? density_uv / (REAL(2.0) * WP_PI * WP_PI * sin_theta) : REAL(0.0);
}

/* The density per solid angle with which environment_sample picks the
 * world direction d (unit). */
WP_FN real environment_pdf(EnvironmentMapLayout map, WP_GLOBAL const real_element *data, vec3 d) {
    EnvironmentPoint p = environment_point(environment_local(map, d));
    return environment_pdf_uv(map, data, p.uv, p.sin_theta);
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

/* Where u falls in `interval`, in [0, 1): the rest of the random number,
 * for the point inside the cell. */
WP_FN real environment_remainder(CdfInterval interval, real u) {
    real rest = interval.pmf > REAL(0.0) ? (u - interval.below) / interval.pmf : REAL(0.0);
    return wp_clamp(rest, REAL(0.0), REAL(1.0) - WP_UNIT_ROUNDOFF);
}

WP_FN EnvironmentSample environment_sample(EnvironmentMapLayout map, WP_GLOBAL const real_element *data, real u1,
                                           real u2) {
    uint rows = map.height - 1u;
    lane_uint marginal = (lane_uint)environment_marginal_start(map);
    lane_uint row = environment_search(data, marginal, rows, u1);
    CdfInterval row_interval = environment_interval(data, marginal, row);
    real dv = environment_remainder(row_interval, u1);
    lane_uint conditional = environment_conditional_start(map) + row * map.width;
    lane_uint column = environment_search(data, conditional, map.width, u2);
    CdfInterval column_interval = environment_interval(data, conditional, column);
    real du = environment_remainder(column_interval, u2);
    real u = (TO_REAL(column) + du + REAL(0.5)) / (real_element)(map.width);
    u = u >= REAL(1.0) ? u - REAL(1.0) : u;
    real v = (TO_REAL(row) + dv) / (real_element)(rows);
    CosSin phi = cos_sin_turns(u), theta = cos_sin_turns(REAL(0.5) * v);
    vec3 in_map = make_vec3(theta.sin_value * phi.sin_value, theta.cos_value, -theta.sin_value * phi.cos_value);
    real density_uv = row_interval.pmf * column_interval.pmf * (real_element)(map.width * rows);
    EnvironmentSample s;
    s.direction = environment_world(map, in_map);
    s.radiance = environment_radiance_uv(map, data, make_texture_uv(u, v));
    s.pdf = theta.sin_value > REAL(0.0) ? density_uv / (REAL(2.0) * WP_PI * WP_PI * theta.sin_value) : REAL(0.0);
    return s;
}

#endif
