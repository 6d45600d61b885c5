/* The scene as flat device buffers, shared by the host (src/opencl/scene_upload.cpp)
 * and the kernels. Only 4-byte float and uint fields (no float3, whose
 * size and alignment differ between OpenCL C and C++), so both sides lay the
 * structs out identically; the host static_asserts the sizes.
 * In C++ this file is included inside a namespace that defines `uint`. */
#ifndef WP_INTERFACE_SCENE_LAYOUT_H
#define WP_INTERFACE_SCENE_LAYOUT_H

/* hit_shape packs the shape type into the top three bits and the index
 * below. WP_NO_HIT's type bits (7) name no shape, so code that decodes a stale
 * or missed hit (an inactive lane's) reads every array at index 0. */
#define WP_SHAPE_SPHERE 0u
#define WP_SHAPE_PLANE 1u
#define WP_SHAPE_QUAD 2u
#define WP_SHAPE_TRIANGLE 3u /* a mesh triangle, by its index in the BVH's leaf order */
/* Not shapes: the types of DeviceLight.shape for the environment (Scene's
 * LightKind::Environment), the light table's last light, for a
 * directional light, and for a point light (a spot included). */
#define WP_LIGHT_ENVIRONMENT 4u
#define WP_LIGHT_DIRECTIONAL 5u
#define WP_LIGHT_POINT 6u
#define WP_SHAPE_TYPE_SHIFT 29u
#define WP_SHAPE_INDEX_MASK 0x1fffffffu
#define WP_NO_HIT 0xffffffffu

#define WP_MATERIAL_DIFFUSE 0u
#define WP_MATERIAL_MIRROR 1u
#define WP_MATERIAL_GLASS 2u
#define WP_MATERIAL_EMITTER 3u
#define WP_MATERIAL_CONDUCTOR 4u
#define WP_MATERIAL_ROUGH_CONDUCTOR 5u
#define WP_MATERIAL_ROUGH_DIELECTRIC 6u
#define WP_MATERIAL_THIN_DIELECTRIC 7u
#define WP_MATERIAL_PLASTIC 8u
#define WP_MATERIAL_ROUGH_PLASTIC 9u

typedef struct {
    float camera_right[3], camera_up[3], camera_forward[3];
    float tan_half_fov_y, aspect;
    float background[3]; /* the environment's radiance */
    uint filter_type;    /* the camera's pixel filter (shared/pixel_filter.h): WP_FILTER_*, and its constants */
    float filter_radius, filter_scale, filter_erf_radius;
    uint width, height, spp, max_depth, rr_depth, seed;
    uint sphere_count, plane_count, quad_count, light_count;
    uint photons;            /* sppm: photons per iteration */
    float sppm_alpha;        /* sppm: the fraction of new photons a pixel keeps (shared/sppm.h) */
    float sppm_radius;       /* sppm: every pixel's first radius; 0: from its footprint (sppm_first_radius) */
    float sppm_pixel_spread; /* sppm: the pixel's angle, the camera ray cone's spread (sppm_footprint) */
    /* the environment map's (shared/environment_map.h: EnvironmentMapLayout;
     * its data in the scene buffer `environment`), zero without one */
    uint environment_width, environment_height;
    float environment_to_world[9];
} SceneHeader;

typedef struct {
    float center[3];
    float radius;
    uint material;
} DeviceSphere;

typedef struct {
    float point[3];
    float normal[3];
    uint material;
} DevicePlane;

typedef struct {
    float corner[3], edge1[3], edge2[3];
    float plane_normal[3], plane_w[3]; /* quad_plane(edge1, edge2), shared/geometry.h */
    uint material;
} DeviceQuad;

typedef struct {
    float albedo[3];      /* diffuse */
    float reflectance[3]; /* mirror */
    float emission[3];    /* diffuse (optional) and emitter */
    float ior;            /* glass, roughdielectric, thindielectric, the plastics: inside over outside */
    uint type;            /* WP_MATERIAL_* */
    uint two_sided;       /* emission on both sides */
    /* conductor and roughconductor: the complex index eta + i k, and the
     * reflection's factor */
    float eta[3], k[3], specular_reflectance[3];
    /* roughconductor, roughdielectric: WP_MICROFACET_* (shared/materials/microfacet.h) and
     * the roughness along the shading frame's tangents */
    uint distribution;
    float alpha_u, alpha_v;
    /* plastic and roughplastic (besides albedo, their diffuse_reflectance, ior
     * and specular_reflectance): the constants the host computes
     * (src/scene/plastic_constants.h), and roughplastic's table of t, where
     * it starts in roughplastic_transmittance */
    float inv_eta_2, internal_reflectance, specular_sampling_weight;
    uint nonlinear, transmittance_offset;
    float bump_scale; /* a `bumpmap` adapter's: its height texture's gradient times this (shared/normal_map.h) */
    float opacity;    /* a `mask` adapter's (shared/materials/mask.h); 1 on every other material */
    uint one_sided;   /* black where a path meets the back (Mitsuba's BSDFs outside a twosided) */
} DeviceMaterial;

/* The material parameters that may be textured (docs/scene-format.md),
 * src/scene/scene.h's TexturedParameter in the same order: the albedo (the
 * diffuse albedo, the plastics' diffuse_reflectance: DeviceMaterial's
 * albedo), the conductors' and plastics' specular_reflectance, and the
 * roughconductor's and roughdielectric's roughness along each tangent
 * (alpha_u, alpha_v), a `normalmap` adapter's map, a `bumpmap` adapter's
 * height (shared/normal_map.h) and a `mask` adapter's opacity
 * (shared/materials/mask.h). */
#define WP_TEXTURED_ALBEDO 0
#define WP_TEXTURED_SPECULAR_REFLECTANCE 1
#define WP_TEXTURED_ALPHA_U 2
#define WP_TEXTURED_ALPHA_V 3
#define WP_TEXTURED_NORMAL_MAP 4
#define WP_TEXTURED_BUMP_MAP 5
#define WP_TEXTURED_OPACITY 6
#define WP_TEXTURED_PARAMETERS 7

/* Which of a material's parameters are textured: per WP_TEXTURED_*, an
 * index into the textures (shared/texture.h), or WP_NO_TEXTURE where the
 * parameter is the material's constant. Parallel to the materials. */
typedef struct {
    uint texture[WP_TEXTURED_PARAMETERS];
} MaterialTextures;

typedef struct {
    uint shape;          /* WP_SHAPE_SPHERE or WP_SHAPE_QUAD, index included as in hit_shape; a mesh:
                          * WP_SHAPE_TRIANGLE with its first triangle in light_triangles as the index;
                          * the environment (constant or a map): WP_LIGHT_ENVIRONMENT, index 0; a directional light:
                          * WP_LIGHT_DIRECTIONAL, index 0; a point or spot light: WP_LIGHT_POINT, index 0 */
    uint triangle_count; /* a mesh: its triangles in light_triangles (and light_triangle_cdf) */
    float area;          /* a mesh: its area */
    uint mesh;           /* a mesh: its index in the scene's meshes (MeshTriangle.mesh of its triangles) */
    float to_light[3];   /* a directional light: the unit direction towards it */
    float emitted[3];    /* a directional light's irradiance; a point light's intensity (a spot's on its axis) */
    float position[3];   /* a point light's */
    float axis[3];       /* a spot's: the unit direction its cone points in */
    /* A spot's cone (spot_falloff): the cosines of its cutoff angle and of its
     * beam width, the cutoff angle in radians and one over the cutoff angle
     * minus the beam width (0 where they are equal). A point light's cosines
     * are -2, below every direction's: its falloff is 1 everywhere. */
    float cos_cutoff, cos_beam, cutoff_angle, inv_transition_width;
} DeviceLight;

#endif
