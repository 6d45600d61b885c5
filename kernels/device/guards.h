/* No NaN or Inf reaches the film: every addition to a path's radiance and
 * every new throughput is checked, and what is dropped is counted per stage
 * (docs/robustness.md, "Guards"). No atomics here: they would keep PoCL from
 * vectorising the stages. */
#ifndef WP_DEVICE_GUARDS_H
#define WP_DEVICE_GUARDS_H

#include "device/lane_memory.h"
#include "device/lanes.h"
#include "interface/queues.h"
#include "shared/prelude.h"

/* Adds `term` to the path's radiance unless the sum is not finite (a NaN or
 * Inf term, or an overflowing sum): then it is dropped and counted in
 * *dropped, which the caller adds to the stage's counter. */
WP_FN vec3 add_finite(vec3 radiance, vec3 term, lane_uint *dropped) {
    vec3 sum = v3_add(radiance, term);
    lane_int finite = vec3_is_finite(sum);
    *dropped += finite ? (lane_uint)0u : (lane_uint)1u;
    return v3_select(finite, sum, radiance);
}

/* Whether the throughput may carry the path on; a non-finite one ends it and is counted in *dropped. */
WP_FN lane_int throughput_is_finite(vec3 throughput, lane_uint *dropped) {
    lane_int finite = vec3_is_finite(throughput);
    *dropped += finite ? (lane_uint)0u : (lane_uint)1u;
    return finite;
}

/* Adds the lanes' dropped non-finite values to their slots' counters for the
 * stage (WP_COUNTER_NONFINITE_*): one counter per slot and stage, so no
 * atomics; the host sums them after each pass. */
WP_FN void count_nonfinite(__global uint *slot_nonfinite, uint stage_counter, Lanes lanes, lane_uint dropped) {
    add_where_nonzero(slot_nonfinite + (stage_counter - WP_COUNTER_NONFINITE_EMISSION) * lanes.capacity, lanes.slot,
                      lanes.active ? dropped : (lane_uint)0u);
}

#endif
