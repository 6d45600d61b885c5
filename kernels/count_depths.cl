/* --profile only: rays per path depth. Counts the depths of the paths in one
 * queue (RAY before intersect, SHADOW once shade has filled it) into a
 * histogram in `counts` (the last bin takes every deeper ray). A ray's depth
 * is its path's `depth` less `depth_after_vertex`: 0 for an extension ray, 1
 * for a shadow ray, since shade has counted the ray's vertex already. A kernel of
 * its own, so that profiling leaves the stage kernels as they are: the
 * atomics and barriers counting needs would keep them from vectorising.
 * Each work group fills a histogram in local memory and adds it to the
 * global one with one atomic per non-empty bin. */
#include "device/parameters.h"
#include "interface/kernel_parameters.h"
#include "interface/queues.h"

__kernel __attribute__((reqd_work_group_size(WP_GROUP_SIZE, 1, 1))) void count_depths(
    WP_PARAMETERS(WP_COUNT_DEPTHS_PARAMETERS)) {
    __local uint group_histogram[WP_PROFILE_DEPTHS];
    for (uint i = get_local_id(0); i < WP_PROFILE_DEPTHS; i += get_local_size(0)) group_histogram[i] = 0u;
    barrier(CLK_LOCAL_MEM_FENCE);
    uint k = get_global_id(0);
    if (k < counts[queue])
        atomic_inc(
            &group_histogram[min(depth[queues[queue * capacity + k]] - depth_after_vertex, WP_PROFILE_DEPTHS - 1u)]);
    barrier(CLK_LOCAL_MEM_FENCE);
    for (uint i = get_local_id(0); i < WP_PROFILE_DEPTHS; i += get_local_size(0))
        if (group_histogram[i] != 0u) atomic_add(&counts[histogram_offset + i], group_histogram[i]);
}
