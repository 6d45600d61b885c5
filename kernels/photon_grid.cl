/* SPPM's grid of visible points (shared/photon_grid.h), built on the device
 * every iteration by a counting sort, without linked lists: grid_bounds
 * finds the frame (one work group: the visible points' lowest corner and
 * largest radius; min and max are exact, so the frame is the same however
 * they are grouped), grid_count counts each bucket's visible points (an
 * atomic increment per listed cell), the three grid_scan kernels turn the
 * counts into each bucket's first entry (a prefix sum over blocks of
 * WP_GRID_SCAN_BLOCK buckets) and grid_fill writes each visible point into
 * its buckets. The order within a bucket depends on the atomics, which
 * changes nothing: each pixel's gathering is exact whatever the order
 * photons meet it (shade_photons.cl). Every kernel takes the work item's
 * WP_LANES pixels (device/sppm_pixels.h) or one block. */
#include "device/parameters.h"
#include "device/photon_vertex.h"
#include "device/sppm_pixels.h"
#include "interface/kernel_parameters.h"
#include "shared/photon_grid.h"
#include "shared/sppm.h"

#ifdef WP_SPPM
/* The least and greatest of the lanes (exact). */
#if WP_LANES == 1
WP_FN float lanes_min(real x) { return x; }
WP_FN float lanes_max(real x) { return x; }
#else
#define WP_MIN_LANE(s, k) least = fmin(least, x.s);
#define WP_MAX_LANE(s, k) greatest = fmax(greatest, x.s);
WP_LANE_FN float lanes_min(real x) {
    float least = x.s0;
    WP_FOR_LANES(WP_MIN_LANE)
    return least;
}
WP_LANE_FN float lanes_max(real x) {
    float greatest = x.s0;
    WP_FOR_LANES(WP_MAX_LANE)
    return greatest;
}
#undef WP_MIN_LANE
#undef WP_MAX_LANE
#endif

/* The first lane's value (of a computation that is the same in every lane). */
#if WP_LANES == 1
#define FIRST_LANE(x) (x)
#else
#define FIRST_LANE(x) ((x).s0)
#endif

WP_FN uint grid_bucket_count(__global const SceneHeader *scene) {
    return photon_grid_buckets(scene_pixel_count(scene));
}
#endif

__kernel __attribute__((reqd_work_group_size(WP_GROUP_SIZE, 1, 1))) void grid_bounds(WP_SPPM_PARAMS) {
#ifdef WP_SPPM
    __local float low_x[WP_GROUP_SIZE], low_y[WP_GROUP_SIZE], low_z[WP_GROUP_SIZE], largest[WP_GROUP_SIZE];
    uint pixels = scene_pixel_count(scene), me = get_local_id(0);
    real lx = WP_REAL_MAX, ly = WP_REAL_MAX, lz = WP_REAL_MAX, radius = REAL(0.0);
    for (uint first = me * WP_LANES; first < pixels; first += WP_GROUP_SIZE * WP_LANES) {
        lane_uint pixel = first + lane_numbers();
        Lanes own = pixel_lanes(pixel, pixel < pixels, pixels);
        lane_int visible = own.active && SPPM_READ(visible_depth, own) != WP_NO_VISIBLE_POINT;
        vec3 p = SPPM_READ(visible_point, own);
        lx = visible ? fmin(lx, p.x) : lx;
        ly = visible ? fmin(ly, p.y) : ly;
        lz = visible ? fmin(lz, p.z) : lz;
        radius = visible ? fmax(radius, SPPM_READ(sppm_radius, own)) : radius;
    }
    low_x[me] = lanes_min(lx);
    low_y[me] = lanes_min(ly);
    low_z[me] = lanes_min(lz);
    largest[me] = lanes_max(radius);
    barrier(CLK_LOCAL_MEM_FENCE);
    if (me == 0u) {
        float x = low_x[0], y = low_y[0], z = low_z[0], r = largest[0];
        for (uint i = 1u; i < WP_GROUP_SIZE; ++i) {
            x = fmin(x, low_x[i]);
            y = fmin(y, low_y[i]);
            z = fmin(z, low_z[i]);
            r = fmax(r, largest[i]);
        }
        GridFrame frame = grid_frame(make_vec3((real)x, (real)y, (real)z), (real)r);
        __global float *out = SPPM_OUT(grid_frame);
        out[0] = FIRST_LANE(frame.origin.x);
        out[1] = FIRST_LANE(frame.origin.y);
        out[2] = FIRST_LANE(frame.origin.z);
        out[3] = r > 0.0f ? FIRST_LANE(frame.cell_size) : 0.0f;
    }
#endif
}

#ifdef WP_SPPM
/* Each `visible` lane's sphere (center, radius) counted into the buckets of
 * the cells it meets (an atomic increment per listed cell); with `fill`, also
 * written as `slot` at its bucket's start plus the count before it. */
WP_FN void list_sphere(GridFrame frame, vec3 center, real radius, lane_int visible, uint buckets,
                       volatile __global uint *counts, __global const uint *starts, __global uint *entries,
                       lane_uint slot, int fill) {
    for (uint k = 0u; k < WP_GRID_CELLS_PER_SPHERE; ++k) {
        GridCell cell = grid_cell_of_sphere(frame, center, radius, buckets, k);
        lane_int listed = visible && cell.listed;
        lane_uint before = atomic_increment_where(counts, cell.bucket, listed);
        if (fill) store_where(entries, gather(starts, cell.bucket) + before, listed, slot);
    }
}
#endif

/* The work item's pixels' visible points listed in the grid (list_sphere). */
#define WP_LIST_VISIBLE_POINTS(fill)                                                                              \
    Lanes own = own_pixel_lanes(scene_pixel_count(scene));                                                        \
    lane_int visible = own.active && SPPM_READ(visible_depth, own) != WP_NO_VISIBLE_POINT;                        \
    list_sphere(read_grid_frame(SPPM_IN(grid_frame)), SPPM_READ(visible_point, own), SPPM_READ(sppm_radius, own), \
                visible, grid_bucket_count(scene), SPPM_OUT(grid_counts), SPPM_IN(grid_starts),                   \
                SPPM_OUT(grid_entries), own.slot, fill)

__kernel __attribute__((reqd_work_group_size(WP_GROUP_SIZE, 1, 1))) void grid_count(WP_SPPM_PARAMS) {
#ifdef WP_SPPM
    WP_LIST_VISIBLE_POINTS(0);
#endif
}

/* The counting sort's prefix sum: block b's total, the blocks' exclusive
 * prefix sum (one work item; the last entry the total), then each bucket's
 * first entry, with the counts reset for grid_fill to count up again. */
__kernel void grid_scan_blocks(WP_SPPM_PARAMS) {
#ifdef WP_SPPM
    uint block = get_global_id(0), buckets = grid_bucket_count(scene);
    uint first = block * WP_GRID_SCAN_BLOCK, end = min(buckets, first + WP_GRID_SCAN_BLOCK);
    if (first >= buckets) return;
    __global const uint *counts_in = SPPM_IN(grid_counts);
    uint sum = 0u;
    for (uint b = first; b < end; ++b) sum += counts_in[b];
    SPPM_OUT(grid_block_sums)[block] = sum;
#endif
}

__kernel void grid_scan_top(WP_SPPM_PARAMS) {
#ifdef WP_SPPM
    uint buckets = grid_bucket_count(scene), blocks = (buckets + WP_GRID_SCAN_BLOCK - 1u) / WP_GRID_SCAN_BLOCK;
    if (get_global_id(0) != 0u) return;
    __global uint *sums = SPPM_OUT(grid_block_sums);
    uint running = 0u;
    for (uint block = 0u; block < blocks; ++block) {
        uint n = sums[block];
        sums[block] = running;
        running += n;
    }
    SPPM_OUT(grid_starts)[buckets] = running;
#endif
}

__kernel void grid_scan_write(WP_SPPM_PARAMS) {
#ifdef WP_SPPM
    uint block = get_global_id(0), buckets = grid_bucket_count(scene);
    uint first = block * WP_GRID_SCAN_BLOCK, end = min(buckets, first + WP_GRID_SCAN_BLOCK);
    if (first >= buckets) return;
    __global uint *counts_out = SPPM_OUT(grid_counts), *starts = SPPM_OUT(grid_starts);
    uint running = SPPM_IN(grid_block_sums)[block];
    for (uint b = first; b < end; ++b) {
        starts[b] = running;
        running += counts_out[b];
        counts_out[b] = 0u;
    }
#endif
}

__kernel __attribute__((reqd_work_group_size(WP_GROUP_SIZE, 1, 1))) void grid_fill(WP_SPPM_PARAMS) {
#ifdef WP_SPPM
    WP_LIST_VISIBLE_POINTS(1);
#endif
}
