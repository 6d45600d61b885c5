/* Device memory at per-lane indices (prelude.h): with several lanes a load
 * is one load per lane (a gather) and a store one store per lane where its
 * condition holds; with one lane they are plain loads and stores. */
#ifndef WP_LANE_MEMORY_H
#define WP_LANE_MEMORY_H

#if WP_LANES == 1
WP_FN real load_real(__global const float *p, lane_uint index) { return p[index]; }
WP_FN lane_uint load_uint(__global const uint *p, lane_uint index) { return p[index]; }
WP_FN void store_real(__global float *p, lane_uint index, lane_int where, real value) {
    if (where) p[index] = value;
}
WP_FN void store_uint(__global uint *p, lane_uint index, lane_int where, lane_uint value) {
    if (where) p[index] = value;
}
/* p[index] += value where value is not 0 (indices distinct across lanes). */
WP_FN void add_uint(__global uint *p, lane_uint index, lane_uint value) {
    if (value != 0u) p[index] += value;
}
#else
#define WP_LOAD_LANE(s) p[index.s],
WP_FN real load_real(__global const float *p, lane_uint index) {
    float values[WP_LANES] = {WP_FOR_LANES(WP_LOAD_LANE)};
    return vload8(0, values);
}
WP_FN lane_uint load_uint(__global const uint *p, lane_uint index) {
    uint values[WP_LANES] = {WP_FOR_LANES(WP_LOAD_LANE)};
    return vload8(0, values);
}
#undef WP_LOAD_LANE
#define WP_STORE_LANE(s) \
    if (where.s) p[index.s] = value.s;
WP_FN void store_real(__global float *p, lane_uint index, lane_int where, real value) { WP_FOR_LANES(WP_STORE_LANE) }
WP_FN void store_uint(__global uint *p, lane_uint index, lane_int where, lane_uint value) {
    WP_FOR_LANES(WP_STORE_LANE)
}
#undef WP_STORE_LANE
#define WP_ADD_LANE(s) \
    if (value.s != 0u) p[index.s] += value.s;
WP_FN void add_uint(__global uint *p, lane_uint index, lane_uint value) { WP_FOR_LANES(WP_ADD_LANE) }
#undef WP_ADD_LANE
#endif

/* array[index].member for per-lane indices into an array of structs of
 * 4-byte fields (scene_layout.h); member is a float or uint field, or one
 * component of a float[3]. */
#define WP_STRUCT_WORDS(array) ((uint)(sizeof((array)[0]) / 4u))
#define LOAD_MEMBER(array, index, member) load_real(&(array)->member, (index) * WP_STRUCT_WORDS(array))
#define LOAD_MEMBER_UINT(array, index, member) load_uint(&(array)->member, (index) * WP_STRUCT_WORDS(array))
#define LOAD_MEMBER_XYZ(array, index, member)                                               \
    make_vec3(LOAD_MEMBER(array, index, member[0]), LOAD_MEMBER(array, index, member[1]), \
              LOAD_MEMBER(array, index, member[2]))

#endif
