/* The light CDF search (shared/sampling.h, select_light) over a part of a
 * CDF that differs from lane to lane: each mesh light's triangles. */
#ifndef WP_DEVICE_LIGHT_RANGES_H
#define WP_DEVICE_LIGHT_RANGES_H

#include "shared/prelude.h"

/* first + select_light(cdf + first, count, u) in each lane: the same steps,
 * a lane's search idle (its index held at `first`) once its part is down to
 * one entry, until every lane's is. A lane with count 0 gets `first`. */
WP_FN lane_uint select_light_in_range(__global const float *cdf, lane_uint first, lane_uint count, real u) {
    for (lane_uint remaining = count; lanes_any(remaining > 1u);) {
        lane_int searching = remaining > 1u;
        lane_uint step = searching ? remaining / 2u : (lane_uint)0u;
        lane_int above = u >= gather(cdf, searching ? first + step - 1u : first);
        first = above ? first + step : first; /* step is 0 in idle lanes */
        remaining -= step;
    }
    return first;
}

#endif
