/* What a program is compiled for. The host passes the scene's features as
 * build options (src/opencl/kernel_options.cpp): WP_HAS_<kind> for each
 * shape, material and light kind in use, WP_NEE when next-event estimation
 * runs, WP_HOST_TRACED when the host traces the stages' rays,
 * WP_SHADOW_STAGE when the shadow rays go to their own stage,
 * WP_INTERSECT_AND_SHADE when one kernel traces and shades
 * (interface/stages.h), and, for small scenes, each kind's count as a
 * constant. Code for what the scene lacks is compiled out. This header
 * derives the rest. */
#ifndef WP_DEVICE_FEATURES_H
#define WP_DEVICE_FEATURES_H

/* A material with a delta lobe: paths carry whether their last bounce was
 * one. (The plastic has a delta lobe and a diffuse one: this and the next;
 * a mask's pass is a delta lobe.) */
#if defined(WP_HAS_MIRROR) || defined(WP_HAS_GLASS) || defined(WP_HAS_CONDUCTOR) || defined(WP_HAS_THIN_DIELECTRIC) || \
    defined(WP_HAS_PLASTIC) || defined(WP_HAS_MASK)
#define WP_HAS_SPECULAR
#endif
/* A material with a lobe of finite density: next-event estimation and
 * multiple importance sampling run at its vertices, and its BSDF sample
 * takes a pair of random numbers. */
#if defined(WP_HAS_DIFFUSE) || defined(WP_HAS_ROUGH_CONDUCTOR) || defined(WP_HAS_ROUGH_DIELECTRIC) || \
    defined(WP_HAS_PLASTIC) || defined(WP_HAS_ROUGH_PLASTIC)
#define WP_HAS_NON_SPECULAR
#endif
/* A lobe of finite density other than the Lambertian one (a rough
 * conductor or dielectric, a plastic's base under its coat): SPPM's visible
 * points on it keep their material and wo, to evaluate its f at the gather. */
#if defined(WP_HAS_ROUGH_CONDUCTOR) || defined(WP_HAS_ROUGH_DIELECTRIC) || defined(WP_HAS_PLASTIC) || \
    defined(WP_HAS_ROUGH_PLASTIC)
#define WP_HAS_GLOSSY
#endif
/* More than one kind of BSDF: each kind's code then runs only where some
 * lane of the vector has it (path_vertex.h, lanes_have_kind). */
#if (defined(WP_HAS_DIFFUSE) + defined(WP_HAS_MIRROR) + defined(WP_HAS_GLASS) + defined(WP_HAS_CONDUCTOR) + \
     defined(WP_HAS_ROUGH_CONDUCTOR) + defined(WP_HAS_ROUGH_DIELECTRIC) + defined(WP_HAS_THIN_DIELECTRIC) + \
     defined(WP_HAS_PLASTIC) + defined(WP_HAS_ROUGH_PLASTIC)) > 1
#define WP_HAS_MIXED_MATERIALS
#endif
/* A normalmap or bumpmap adapter: hits perturb their shading normal
 * (shared/normal_map.h), and the nested BSDF carries the terminator term. */
#if defined(WP_HAS_NORMAL_MAP) || defined(WP_HAS_BUMP_MAP)
#define WP_PERTURBS_NORMALS
#endif
/* A vertex that may not scatter at all (Vertex.shades): an arrival below a
 * normal or bump map's perturbed normal, the back of a one-sided material. */
#if defined(WP_PERTURBS_NORMALS) || defined(WP_HAS_ONE_SIDED)
#define WP_VERTEX_MAY_NOT_SHADE
#endif
/* The complex index and reflectance factor of conductor and roughconductor. */
#if defined(WP_HAS_CONDUCTOR) || defined(WP_HAS_ROUGH_CONDUCTOR)
#define WP_HAS_CONDUCTORS
#endif
/* A dielectric interface: an index of refraction, a random choice between
 * reflection and transmission, and the dielectric Fresnel code. */
#if defined(WP_HAS_GLASS) || defined(WP_HAS_ROUGH_DIELECTRIC) || defined(WP_HAS_THIN_DIELECTRIC)
#define WP_HAS_DIELECTRICS
#endif
/* A refraction into another medium, which scales radiance by 1 / eta^2:
 * paths carry the product of eta^2 for the roulette (eta_scale). */
#if defined(WP_HAS_GLASS) || defined(WP_HAS_ROUGH_DIELECTRIC)
#define WP_HAS_REFRACTION
#endif
/* A microfacet distribution's parameters. */
#if defined(WP_HAS_ROUGH_CONDUCTOR) || defined(WP_HAS_ROUGH_DIELECTRIC) || defined(WP_HAS_ROUGH_PLASTIC)
#define WP_HAS_MICROFACET
#endif
/* A diffuse base under a dielectric coat: the dielectric Fresnel code. */
#if defined(WP_HAS_PLASTIC) || defined(WP_HAS_ROUGH_PLASTIC)
#define WP_HAS_PLASTICS
#endif
/* A material that picks one of its lobes with a random number (the BSDF
 * sample's `lobe`; a mask picks between its pass and the material it nests). */
#if defined(WP_HAS_DIELECTRICS) || defined(WP_HAS_PLASTICS) || defined(WP_HAS_MASK)
#define WP_HAS_LOBE_CHOICE
#endif

/* WP_IF_<feature>(...) keeps its arguments only when the path state
 * feature (interface/path_state.h) is compiled in. */
#define WP_IF_ALWAYS(...) __VA_ARGS__
#ifdef WP_HAS_SPECULAR
#define WP_IF_SPECULAR(...) __VA_ARGS__
#else
#define WP_IF_SPECULAR(...)
#endif
#ifdef WP_HAS_REFRACTION
#define WP_IF_REFRACTION(...) __VA_ARGS__
#else
#define WP_IF_REFRACTION(...)
#endif
#ifdef WP_NEE
#define WP_IF_NEE(...) __VA_ARGS__
#else
#define WP_IF_NEE(...)
#endif
#ifdef WP_MIS
#define WP_IF_MIS(...) __VA_ARGS__
#else
#define WP_IF_MIS(...)
#endif
#if defined(WP_NEE) && defined(WP_SHADOW_STAGE)
#define WP_IF_SHADOW_STAGE(...) __VA_ARGS__
#else
#define WP_IF_SHADOW_STAGE(...)
#endif
#if defined(WP_NEE) && defined(WP_HOST_TRACED)
#define WP_IF_HOST_SHADOWS(...) __VA_ARGS__
#else
#define WP_IF_HOST_SHADOWS(...)
#endif
#ifdef WP_SPPM
#define WP_IF_SPPM(...) __VA_ARGS__
#else
#define WP_IF_SPPM(...)
#endif
#ifdef WP_HAS_GLOSSY
#define WP_IF_GLOSSY(...) __VA_ARGS__
#else
#define WP_IF_GLOSSY(...)
#endif
#if defined(WP_HAS_GLOSSY) && defined(WP_HAS_TEXTURES)
#define WP_IF_GLOSSY_TEXTURES(...) __VA_ARGS__
#else
#define WP_IF_GLOSSY_TEXTURES(...)
#endif

/* Shape and light counts: compile-time constants where the host passes them
 * (small scenes), so the loops over them unroll into straight-line code that
 * runs as SIMD lanes; otherwise read from the scene header at run time. */
#ifdef WP_SPHERE_COUNT
#define SPHERE_COUNT WP_SPHERE_COUNT
#else
#define SPHERE_COUNT scene->sphere_count
#endif
#ifdef WP_PLANE_COUNT
#define PLANE_COUNT WP_PLANE_COUNT
#else
#define PLANE_COUNT scene->plane_count
#endif
#ifdef WP_QUAD_COUNT
#define QUAD_COUNT WP_QUAD_COUNT
#else
#define QUAD_COUNT scene->quad_count
#endif
#ifdef WP_LIGHT_COUNT
#define LIGHT_COUNT WP_LIGHT_COUNT
#else
#define LIGHT_COUNT scene->light_count
#endif

#endif
