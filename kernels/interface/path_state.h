/* The wavefront's path state, declared once. Every field is one device buffer
 * with one row per path slot (structure of arrays); a vec3 field's buffer
 * holds three planes of `capacity` floats (x, then y, then z), so that each
 * component is read and written as consecutive slots. The list expands into
 * the host's buffers (src/wavefront/path_state.cpp), the kernels' parameter
 * lists (WP_PATH_STATE_PARAMS, kernels/device/parameters.h), the
 * bytes-per-path estimate and the table in docs/architecture.md, so adding a
 * field is one line here. Kernels reach a field through PATH_READ and
 * PATH_WRITE (kernels/device/lanes.h).
 *
 * X(type, name, feature, written by, read by), type uint, float or vec3,
 * where feature says when the buffer exists:
 *   ALWAYS   every scene;
 *   SPECULAR the scene has a material with a delta lobe (otherwise no
 *            bounce is specular and "previous vertex specular" is depth == 0);
 *   REFRACTION the scene has glass or a rough dielectric (refractions scale radiance);
 *   NEE      next-event estimation runs (render.nee on and a light in the scene);
 *   MIS      NEE runs at diffuse vertices with multiple importance sampling
 *            (render.mis on);
 *   SHADOW_STAGE  NEE runs and its shadow rays go to intersect_shadow
 *            (where the host traces them, and on GPUs; otherwise shade
 *            traces them itself: interface/stages.h);
 *   HIT_STAGE, INTERSECT_AND_SHADE  (stages only, interface/stages.h) intersect
 *            and shade run apart, or as one kernel;
 *   HOST_SHADOWS  NEE runs and the host traces the stages' rays
 *            (--intersector embree, interface/stages.h): the shadow rays'
 *            verdicts, which the host writes before intersect_shadow runs;
 *   SPPM     the integrator is sppm: a slot holds a camera path, or in the
 *            photon pass a photon (interface/stages.h), whose ray and hit
 *            take the same fields (origin, direction, throughput, depth,
 *            hit_t, hit_shape); a camera path keeps the distance it has
 *            travelled, for its pixel's footprint (sppm_footprint). */
#ifndef WP_INTERFACE_PATH_STATE_H
#define WP_INTERFACE_PATH_STATE_H

#define WP_PATH_STATE(X)                                                                               \
    X(uint, pixel, ALWAYS, "generate", "shade intersect_and_shade")                                    \
    X(uint, sample, ALWAYS, "generate", "shade intersect_and_shade")                                   \
    X(uint, pass_item, ALWAYS, "generate", "shade intersect_and_shade intersect_shadow")               \
    X(uint, depth, ALWAYS, "generate shade intersect_and_shade emit_photons shade_photons",            \
      "shade intersect_and_shade shade_photons")                                                       \
    X(vec3, origin, ALWAYS, "generate shade intersect_and_shade emit_photons shade_photons",           \
      "intersect shade intersect_and_shade intersect_photons shade_photons")                           \
    X(vec3, direction, ALWAYS, "generate shade intersect_and_shade emit_photons shade_photons",        \
      "intersect shade intersect_and_shade intersect_photons shade_photons")                           \
    X(vec3, throughput, ALWAYS, "generate shade intersect_and_shade emit_photons shade_photons",       \
      "shade intersect_and_shade shade_photons")                                                       \
    X(vec3, radiance, ALWAYS, "generate shade intersect_and_shade intersect_shadow",                   \
      "shade intersect_and_shade intersect_shadow")                                                    \
    X(float, hit_t, ALWAYS, "intersect intersect_and_shade intersect_photons",                         \
      "shade intersect_and_shade shade_photons")                                                       \
    X(uint, hit_shape, ALWAYS, "intersect intersect_and_shade intersect_photons",                      \
      "shade intersect_and_shade shade_photons")                                                       \
    X(uint, specular, SPECULAR, "generate shade intersect_and_shade", "shade intersect_and_shade")     \
    X(vec3, shadow_origin, SHADOW_STAGE, "shade intersect_and_shade", "intersect_shadow")              \
    X(vec3, shadow_direction, SHADOW_STAGE, "shade intersect_and_shade", "intersect_shadow")           \
    X(float, shadow_distance, SHADOW_STAGE, "shade intersect_and_shade", "intersect_shadow")           \
    X(vec3, shadow_radiance, SHADOW_STAGE, "shade intersect_and_shade", "intersect_shadow")            \
    X(uint, shadow_ends_path, SHADOW_STAGE, "shade intersect_and_shade", "intersect_shadow")           \
    X(uint, shadow_occluded, HOST_SHADOWS, "intersect_shadow", "intersect_shadow")                     \
    X(float, bsdf_pdf, MIS, "shade intersect_and_shade", "shade intersect_and_shade")                  \
    X(float, eta_scale, REFRACTION, "generate shade intersect_and_shade", "shade intersect_and_shade") \
    X(float, travelled, SPPM, "generate shade intersect_and_shade", "shade intersect_and_shade")       \
    X(uint, photon, SPPM, "emit_photons", "shade_photons")                                             \
    X(vec3, photon_flux, SPPM, "emit_photons", "shade_photons")

#endif
