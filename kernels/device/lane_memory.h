/* Device memory at per-lane indices, beyond shared/prelude.h's gather: with
 * one lane plain loads and stores, with several one per lane (stores only
 * where their lane's condition holds). And the scene's structs read a field
 * at a time, per lane or for all lanes at once. */
#ifndef WP_DEVICE_LANE_MEMORY_H
#define WP_DEVICE_LANE_MEMORY_H

#include "shared/prelude.h"

#if WP_LANES == 1
WP_OVERLOAD WP_FN void store_where(__global float *p, lane_uint index, lane_int where, real value) {
    if (where) p[index] = value;
}
WP_OVERLOAD WP_FN void store_where(__global uint *p, lane_uint index, lane_int where, lane_uint value) {
    if (where) p[index] = value;
}
/* p[index] += value where value is not 0 (indices distinct across lanes). */
WP_FN void add_where_nonzero(__global uint *p, lane_uint index, lane_uint value) {
    if (value != 0u) p[index] += value;
}
#else
#define WP_STORE_LANE(s, k) \
    if (where.s) p[index.s] = value.s;
WP_OVERLOAD WP_LANE_FN void store_where(__global float *p, lane_uint index, lane_int where,
                                        real value){WP_FOR_LANES(WP_STORE_LANE)} WP_OVERLOAD WP_LANE_FN
    void store_where(__global uint *p, lane_uint index, lane_int where, lane_uint value){WP_FOR_LANES(WP_STORE_LANE)}
#undef WP_STORE_LANE
#define WP_ADD_LANE(s, k) \
    if (value.s != 0u) p[index.s] += value.s;
WP_LANE_FN void add_where_nonzero(__global uint *p, lane_uint index, lane_uint value) {
    WP_FOR_LANES(WP_ADD_LANE)
}
#undef WP_ADD_LANE
#endif

/* A float[3] member at per-lane word offsets from it. */
WP_OVERLOAD WP_LANE_FN vec3 gather(__global const float (*p)[3], lane_uint index) {
    return make_vec3(gather(&(*p)[0], index), gather(&(*p)[1], index), gather(&(*p)[2], index));
}

/* array[index].member for per-lane indices into an array of structs of
 * 4-byte fields (interface/scene_layout.h): a real, lane_uint or (for a
 * float[3] member) vec3, by the member's type. */
#define WP_STRUCT_WORDS(array) ((uint)(sizeof((array)[0]) / 4u))
#define SCENE_FIELD(array, index, member) gather(&(array)->member, (index)*WP_STRUCT_WORDS(array))

/* A float[3] the same for every lane (the scene header's, one shape's). */
WP_FN vec3 uniform_vec3(__global const float *p) { return make_vec3((real)p[0], (real)p[1], (real)p[2]); }

#endif
