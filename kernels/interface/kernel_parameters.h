/* Every kernel's parameter list, declared once. The kernels expand a list
 * into their parameters (WP_PARAMETERS, kernels/device/parameters.h) and the
 * host into argument indices (src/opencl/kernel_arguments.h), so a parameter
 * added to a list moves every later index on both sides at once; no index is
 * counted by hand.
 *
 * A list takes two macros, FIRST(type, name) for its first entry and
 * NEXT(type, name) for the others, so that an expansion can put a comma
 * before every entry but the first. Types are OpenCL C; the host reads only
 * the names. */
#ifndef WP_INTERFACE_KERNEL_PARAMETERS_H
#define WP_INTERFACE_KERNEL_PARAMETERS_H

/* The scene's buffers (interface/scene_layout.h; the meshes' triangles and
 * BVH nodes of shared/triangle.h and shared/bvh.h; the mesh lights'
 * triangles, src/scene/mesh_lights.h; the roughplastics' tables of their
 * coat's transmittance, src/scene/plastic_constants.h; the textures, the texels
 * and the triangles' uvs of shared/texture.h, and which material parameters are
 * textured, interface/scene_layout.h; the environment map's texels and
 * distributions, shared/environment_map.h), first in every kernel that traces. */
#define WP_SCENE_PARAMETERS(FIRST, NEXT)                       \
    FIRST(__global const SceneHeader *, scene)                 \
    NEXT(__global const DeviceSphere *, spheres)               \
    NEXT(__global const DevicePlane *, planes)                 \
    NEXT(__global const DeviceQuad *, quads)                   \
    NEXT(__global const MeshTriangle *, triangles)             \
    NEXT(__global const TriangleNormals *, triangle_normals)   \
    NEXT(__global const BvhNode *, bvh_nodes)                  \
    NEXT(__global const DeviceMaterial *, materials)           \
    NEXT(__global const DeviceLight *, lights)                 \
    NEXT(__global const float *, light_cdf)                    \
    NEXT(__global const MeshTriangle *, light_triangles)       \
    NEXT(__global const float *, light_triangle_cdf)           \
    NEXT(__global const float *, roughplastic_transmittance)   \
    NEXT(__global const MaterialTextures *, material_textures) \
    NEXT(__global const TextureDescriptor *, textures)         \
    NEXT(__global const float *, texels)                       \
    NEXT(__global const TriangleUVs *, triangle_uvs)           \
    NEXT(__global const float *, environment_map)

/* round_pixels: the pixels the work items sample, ascending (every pixel
 * unless adaptive sampling has stopped some): work item w is pixel
 * round_pixels[w % round_pixel_count], sample w / round_pixel_count. */

/* generate, intersect, shade and intersect_shadow; the path
 * state's fields (interface/path_state.h) follow these. */
#define WP_STAGE_PARAMETERS(FIRST, NEXT)      \
    WP_SCENE_PARAMETERS(FIRST, NEXT)          \
    NEXT(__global uint *, queues)             \
    NEXT(__global uint *, counts)             \
    NEXT(uint, capacity)                      \
    NEXT(ulong, pass_start)                   \
    NEXT(uint, pass_size)                     \
    NEXT(__global const uint *, round_pixels) \
    NEXT(uint, round_pixel_count)             \
    NEXT(__global float *, pass_radiance)     \
    NEXT(__global uint *, slot_nonfinite)

/* SPPM's grid and update kernels (photon_grid.cl, sppm_update.cl); SPPM's
 * state (interface/sppm_state.h) follows these, as it follows the path state
 * in the stage kernels. counts: the counters of interface/queues.h. */
#define WP_SPPM_KERNEL_PARAMETERS(FIRST, NEXT) \
    FIRST(__global const SceneHeader *, scene) \
    NEXT(__global uint *, counts)

#define WP_MEGAKERNEL_PARAMETERS(FIRST, NEXT) \
    WP_SCENE_PARAMETERS(FIRST, NEXT)          \
    NEXT(ulong, pass_start)                   \
    NEXT(uint, pass_size)                     \
    NEXT(__global const uint *, round_pixels) \
    NEXT(uint, round_pixel_count)             \
    NEXT(__global float *, pass_radiance)     \
    NEXT(__global uint *, counts)

#define WP_INTERSECT_BOUND_PARAMETERS(FIRST, NEXT) \
    WP_SCENE_PARAMETERS(FIRST, NEXT)               \
    NEXT(uint, ray_count)                          \
    NEXT(__global float *, hit_t)

/* film: the exact sums of kernels/shared/film_sum.h, WP_FILM_LIMBS limbs per
 * channel and pixel (accumulate.cl). */
#define WP_ACCUMULATE_PARAMETERS(FIRST, NEXT)   \
    FIRST(ulong, pass_start)                    \
    NEXT(uint, pass_size)                       \
    NEXT(uint, pixel_count)                     \
    NEXT(__global const uint *, round_pixels)   \
    NEXT(uint, round_pixel_count)               \
    NEXT(__global const float *, pass_radiance) \
    NEXT(__global ulong *, film)

#define WP_COMPACT_COUNT_PARAMETERS(FIRST, NEXT) \
    FIRST(__global uint *, queues)               \
    NEXT(uint, capacity)                         \
    NEXT(uint, queue_mask)                       \
    NEXT(uint, clear_mask)                       \
    NEXT(__global uint *, block_counts)

#define WP_COMPACT_SCAN_PARAMETERS(FIRST, NEXT) \
    FIRST(uint, capacity)                       \
    NEXT(uint, queue_mask)                      \
    NEXT(__global uint *, block_counts)         \
    NEXT(__global uint *, counts)

#define WP_COMPACT_WRITE_PARAMETERS(FIRST, NEXT) \
    FIRST(__global uint *, queues)               \
    NEXT(uint, capacity)                         \
    NEXT(uint, queue_mask)                       \
    NEXT(uint, clear_mask)                       \
    NEXT(__global const uint *, block_counts)

#define WP_COUNT_DEPTHS_PARAMETERS(FIRST, NEXT) \
    FIRST(__global const uint *, queues)        \
    NEXT(__global uint *, counts)               \
    NEXT(uint, capacity)                        \
    NEXT(uint, queue)                           \
    NEXT(uint, histogram_offset)                \
    NEXT(uint, depth_after_vertex)              \
    NEXT(__global const uint *, depth)

#endif
