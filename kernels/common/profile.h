/* Rays per path depth for --profile (kernels built with -DWP_PROFILE): each
 * work group fills a histogram in local memory and adds it to the global one
 * in `counts` with one atomic per non-empty bin, so counting costs little.
 * Without WP_PROFILE both macros expand to nothing. */
#ifndef WP_PROFILE_H
#define WP_PROFILE_H

#ifdef WP_PROFILE
/* Every work item of the group must call it (it has barriers). */
WP_FN void count_by_depth(__global uint *histogram, int counted, uint depth, __local uint *group_histogram) {
    for (uint i = get_local_id(0); i < WP_PROFILE_DEPTHS; i += get_local_size(0)) group_histogram[i] = 0u;
    barrier(CLK_LOCAL_MEM_FENCE);
    if (counted) atomic_inc(&group_histogram[min(depth, WP_PROFILE_DEPTHS - 1u)]);
    barrier(CLK_LOCAL_MEM_FENCE);
    for (uint i = get_local_id(0); i < WP_PROFILE_DEPTHS; i += get_local_size(0))
        if (group_histogram[i] != 0u) atomic_add(&histogram[i], group_histogram[i]);
}
/* At the top of a kernel that counts. */
#define WP_DEPTH_HISTOGRAM_SCRATCH __local uint depth_histogram_scratch[WP_PROFILE_DEPTHS]
#define COUNT_BY_DEPTH(histogram_offset, counted, depth) \
    count_by_depth(counts + (histogram_offset), (counted), (depth), depth_histogram_scratch)
#else
#define WP_DEPTH_HISTOGRAM_SCRATCH
#define COUNT_BY_DEPTH(histogram_offset, counted, depth)
#endif

#endif
