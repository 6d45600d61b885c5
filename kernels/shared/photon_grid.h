/* SPPM's grid of visible points (docs/architecture.md, "Photon mapping"):
 * cubic cells whose side is a little more than the largest diameter, so that
 * a visible point's sphere meets at most two cells along each axis (eight in
 * all), hashed into a table (Teschner et al., "Optimized Spatial Hashing for
 * Collision Detection of Deformable Objects", 2003). Each visible point is
 * listed in the buckets of the cells its sphere meets, once per bucket, so
 * that a photon finds every visible point whose sphere holds it in its own
 * cell's bucket, and each once. The wavefront fills the buckets by a
 * counting sort on the device, the reference in a loop; both place a cell
 * with these functions, so they find the same visible points. */
#ifndef WP_SHARED_PHOTON_GRID_H
#define WP_SHARED_PHOTON_GRID_H

#include "shared/prelude.h"

/* Cells per axis are counted from the grid's origin up to this, so that a
 * coordinate converts to an integer whatever the scene's extent. */
#define WP_GRID_MOST_CELLS REAL(16777216.0) /* 2^24 */
/* A visible point's sphere is widened by this fraction when its cells are
 * found (so that float rounding cannot leave out a cell a photon within
 * reach falls in), and the cell side exceeds the largest diameter by more. */
#define WP_GRID_SPHERE_MARGIN REAL(0.0009765625) /* 2^-10 */

typedef struct {
    vec3 origin;    /* the visible points' lowest corner, less the largest radius */
    real cell_size; /* 2 (1 + 2 WP_GRID_SPHERE_MARGIN) times the largest radius */
} GridFrame;

/* The buckets of a grid over the visible points of `pixels` pixels: the
 * power of two at or above their number (a load of at most one cell per
 * bucket on a surface seen pixel by pixel). */
WP_FN uint photon_grid_buckets(uint pixels) {
    uint buckets = 1u;
    while (buckets < pixels && buckets < 0x80000000u) buckets <<= 1u;
    return buckets;
}

/* The grid over visible points whose lowest coordinates are `lowest` and
 * whose largest radius is `largest_radius` (> 0). */
WP_FN GridFrame grid_frame(vec3 lowest, real largest_radius) {
    GridFrame frame;
    frame.origin = v3_sub(lowest, make_vec3(largest_radius, largest_radius, largest_radius));
    frame.cell_size = REAL(2.0) * (REAL(1.0) + REAL(2.0) * WP_GRID_SPHERE_MARGIN) * largest_radius;
    return frame;
}

/* The cell coordinate of x along one axis, clamped to [0, WP_GRID_MOST_CELLS]:
 * points outside the visible points' reach land in some cell and find no
 * visible point near enough. */
WP_FN lane_uint grid_coordinate(real x, real origin, real cell_size) {
    return TO_LANE_UINT(wp_clamp(floor((x - origin) / cell_size), REAL(0.0), WP_GRID_MOST_CELLS));
}

/* The bucket of the cell (x, y, z) in a table of `buckets` (a power of two). */
WP_FN lane_uint grid_bucket(lane_uint x, lane_uint y, lane_uint z, uint buckets) {
    return ((x * 73856093u) ^ (y * 19349663u) ^ (z * 83492791u)) & (buckets - 1u);
}

/* The bucket of the cell holding x. */
WP_FN lane_uint grid_bucket_of(GridFrame frame, vec3 x, uint buckets) {
    return grid_bucket(grid_coordinate(x.x, frame.origin.x, frame.cell_size),
                       grid_coordinate(x.y, frame.origin.y, frame.cell_size),
                       grid_coordinate(x.z, frame.origin.z, frame.cell_size), buckets);
}

/* The cells a visible point's (widened) sphere meets along one axis: `low`
 * and, where `two`, low + 1. */
typedef struct {
    lane_uint low;
    lane_int two;
} GridSpan;

WP_FN GridSpan grid_span(real center, real radius, real origin, real cell_size) {
    real reach = radius * (REAL(1.0) + WP_GRID_SPHERE_MARGIN);
    GridSpan span;
    span.low = grid_coordinate(center - reach, origin, cell_size);
    span.two = grid_coordinate(center + reach, origin, cell_size) > span.low;
    return span;
}

/* Cell i (0 to 7) of a sphere whose cells span sx, sy, sz: bit 0 of i
 * steps along x, bit 1 along y, bit 2 along z. */
WP_FN lane_int sphere_cell_exists(GridSpan sx, GridSpan sy, GridSpan sz, uint i) {
    return ((i & 1u) == 0u || sx.two) && ((i & 2u) == 0u || sy.two) && ((i & 4u) == 0u || sz.two);
}

WP_FN lane_uint sphere_cell_bucket(GridSpan sx, GridSpan sy, GridSpan sz, uint i, uint buckets) {
    return grid_bucket(sx.low + (i & 1u), sy.low + ((i >> 1u) & 1u), sz.low + ((i >> 2u) & 1u), buckets);
}

/* The k-th (0 to 7) of the cells the sphere of radius `radius` about
 * `center` may meet: its bucket, and whether the visible point is listed
 * there: the cell is one the sphere meets and no earlier one of its cells
 * has the same bucket (so that a photon never finds it twice). */
typedef struct {
    lane_uint bucket;
    lane_int listed;
} GridCell;

WP_FN GridCell grid_cell_of_sphere(GridFrame frame, vec3 center, real radius, uint buckets, uint k) {
    GridSpan sx = grid_span(center.x, radius, frame.origin.x, frame.cell_size);
    GridSpan sy = grid_span(center.y, radius, frame.origin.y, frame.cell_size);
    GridSpan sz = grid_span(center.z, radius, frame.origin.z, frame.cell_size);
    GridCell cell;
    cell.bucket = sphere_cell_bucket(sx, sy, sz, k, buckets);
    cell.listed = sphere_cell_exists(sx, sy, sz, k);
    for (uint i = 0u; i < k; ++i)
        cell.listed = cell.listed &&
                      !(sphere_cell_exists(sx, sy, sz, i) && sphere_cell_bucket(sx, sy, sz, i, buckets) == cell.bucket);
    return cell;
}

/* The cells of a sphere, for loops over them. */
#define WP_GRID_CELLS_PER_SPHERE 8u

#endif
