/* SPPM's state beside the path state (docs/architecture.md, "Photon
 * mapping"), declared once: per pixel its visible point of the iteration,
 * its progressive estimate (its radius is 0 until its first visible point
 * sets it and its footprint there: sppm_first_radius, shared/sppm.h) and
 * what the iteration's photons brought it, and the grid over the visible
 * points. Every entry is one device buffer
 * (structure of arrays; a vec3 entry holds three planes of `size` floats),
 * which exists only with the sppm integrator. The list expands into the
 * host's buffers (src/wavefront/sppm_state.cpp), the parameters of the
 * stage kernels (after the path state's) and of the grid and update kernels
 * (WP_SPPM_PARAMS, device/parameters.h), and the table in
 * docs/architecture.md.
 *
 * X(type, name, size, feature, written by, read by): type uint, float or
 * vec3; the kernel files (kernels/<file>.cl) that write and read it, through
 * SPPM_WRITE and SPPM_READ (device/sppm_pixels.h) or SPPM_ARRAY ("host":
 * read by the host only, for the summary); size:
 *   PIXELS    one per pixel;
 *   DEPOSITS  WP_FILM_WORDS per pixel and channel: the photon flux of the
 *             iteration, summed exactly by film_words_add (shared/film_sum.h);
 *   BUCKETS   one per bucket of the grid (shared/photon_grid.h) and one more;
 *   BLOCKS    one per block of WP_GRID_SCAN_BLOCK buckets and one more: the
 *             counting sort's prefix sum;
 *   ENTRIES   WP_GRID_CELLS_PER_SPHERE per pixel: the buckets' lists;
 *   FRAME     four: the grid's origin (x, y, z) and cell size (0: no
 *             visible point);
 * feature, when the entry exists besides the sppm integrator:
 *   ALWAYS    every scene;
 *   GLOSSY    the scene has a non-specular material other than diffuse
 *             (WP_HAS_GLOSSY, device/features.h): a visible point's material
 *             (visible_material_word, shared/sppm.h) and the direction back
 *             along its camera path, whose f the photons evaluate;
 *   GLOSSY_TEXTURES  GLOSSY and some material parameter is textured
 *             (WP_HAS_TEXTURES): the visible point's uv, where the photons
 *             look its material's textures up. */
#ifndef WP_INTERFACE_SPPM_STATE_H
#define WP_INTERFACE_SPPM_STATE_H

#define WP_SPPM_STATE(X)                                                                             \
    X(vec3, visible_point, PIXELS, ALWAYS, "shade intersect_and_shade", "shade_photons photon_grid") \
    X(vec3, visible_normal, PIXELS, ALWAYS, "shade intersect_and_shade", "shade_photons")            \
    X(vec3, visible_geometric_normal, PIXELS, ALWAYS, "shade intersect_and_shade", "shade_photons")  \
    X(vec3, visible_weight, PIXELS, ALWAYS, "shade intersect_and_shade", "shade_photons")            \
    X(uint, visible_depth, PIXELS, ALWAYS, "shade intersect_and_shade", "shade_photons photon_grid") \
    X(uint, visible_material, PIXELS, GLOSSY, "shade intersect_and_shade", "shade_photons")          \
    X(vec3, visible_wo, PIXELS, GLOSSY, "shade intersect_and_shade", "shade_photons")                \
    X(float, visible_u, PIXELS, GLOSSY_TEXTURES, "shade intersect_and_shade", "shade_photons")       \
    X(float, visible_v, PIXELS, GLOSSY_TEXTURES, "shade intersect_and_shade", "shade_photons")       \
    X(float, sppm_count, PIXELS, ALWAYS, "sppm_update", "sppm_update")                               \
    X(float, sppm_radius, PIXELS, ALWAYS, "shade intersect_and_shade sppm_update",                   \
      "shade intersect_and_shade shade_photons photon_grid sppm_update")                             \
    X(float, sppm_footprint, PIXELS, ALWAYS, "shade intersect_and_shade", "host")                    \
    X(vec3, sppm_flux, PIXELS, ALWAYS, "sppm_update", "sppm_update")                                 \
    X(uint, iteration_photons, PIXELS, ALWAYS, "shade_photons", "sppm_update")                       \
    X(uint, iteration_flux, DEPOSITS, ALWAYS, "shade_photons", "sppm_update")                        \
    X(float, grid_frame, FRAME, ALWAYS, "photon_grid", "shade_photons photon_grid")                  \
    X(uint, grid_counts, BUCKETS, ALWAYS, "photon_grid", "photon_grid")                              \
    X(uint, grid_block_sums, BLOCKS, ALWAYS, "photon_grid", "photon_grid")                           \
    X(uint, grid_starts, BUCKETS, ALWAYS, "photon_grid", "shade_photons photon_grid")                \
    X(uint, grid_entries, ENTRIES, ALWAYS, "photon_grid", "shade_photons")

/* Buckets per block of the counting sort's prefix sum (photon_grid.cl). */
#define WP_GRID_SCAN_BLOCK 256u

#endif
