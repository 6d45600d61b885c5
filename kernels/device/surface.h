/* The surface and the material a path's ray hit, read per lane: every
 * shape kind compiled in is evaluated and each lane keeps its own kind's. */
#ifndef WP_DEVICE_SURFACE_H
#define WP_DEVICE_SURFACE_H

#include "device/features.h"
#include "device/lane_memory.h"
#include "device/parameters.h"
#include "shared/hit_point.h"
#include "shared/materials/bsdf.h"
#ifdef WP_HAS_MICROFACET
#include "shared/materials/microfacet.h"
#endif
#ifdef WP_HAS_PLASTIC
#include "shared/materials/plastic.h"
#endif
#ifdef WP_HAS_ROUGH_PLASTIC
#include "shared/materials/roughplastic.h"
#endif
#ifdef WP_HAS_MASK
#include "shared/materials/mask.h"
#endif
#include "shared/prelude.h"
#ifdef WP_HAS_TEXTURES
#include "shared/texture.h"
#endif
#ifdef WP_PERTURBS_NORMALS
#include "shared/normal_map.h"
#endif
#ifdef WP_HAS_ANISOTROPIC_ROUGHNESS
#include "shared/surface_tangents.h"
#endif

typedef struct {
    vec3 point;
    vec3 normal;  /* geometric: outward (sphere), the plane's, normalize(edge1 x edge2) (quad), the front (triangle) */
    vec3 shading; /* on normal's side: the interpolated vertex normal on triangles that have them, else normal */
    lane_uint material;
    real error; /* bound on the point's distance from the surface (shared/hit_point.h) */
#ifdef WP_HAS_TEXTURES
    TextureUV uv; /* shared/texture.h; (0, 0) on planes; found by vertex_at only where some lane is textured */
#endif
} Surface;

#ifdef WP_HAS_SHADING_NORMALS
/* The shading normal at `point` of `shape` with geometric normal `normal`
 * (shared/triangle.h); `normal` itself on shapes other than triangles. */
WP_FN vec3 shading_normal(WP_SCENE_PARAMS, lane_uint shape, vec3 normal, vec3 point) {
    lane_int is_triangle = shape >> WP_SHAPE_TYPE_SHIFT == WP_SHAPE_TRIANGLE;
    lane_uint i = is_triangle ? shape & WP_SHAPE_INDEX_MASK : (lane_uint)0u;
    vec3 shading = triangle_shading_normal(SCENE_FIELD(triangles, i, p0), SCENE_FIELD(triangles, i, p1),
                                           SCENE_FIELD(triangles, i, p2), SCENE_FIELD(triangle_normals, i, n0),
                                           SCENE_FIELD(triangle_normals, i, n1), SCENE_FIELD(triangle_normals, i, n2),
                                           normal, point);
    return v3_select(is_triangle, shading, normal);
}
#endif

#ifdef WP_HAS_TEXTURES
/* The uv of the hit at `point` (geometric normal `normal`) of `shape`
 * (shared/texture.h): every shape kind in the scene is evaluated and each
 * lane keeps its own kind's. */
WP_FN TextureUV surface_uv(WP_SCENE_PARAMS, lane_uint shape, vec3 point, vec3 normal) {
    lane_uint index = shape & WP_SHAPE_INDEX_MASK;
    lane_uint type = shape >> WP_SHAPE_TYPE_SHIFT;
    TextureUV uv = make_texture_uv(REAL(0.0), REAL(0.0));
#ifdef WP_HAS_SPHERES
    {
        TextureUV sphere = sphere_uv(normal);
        lane_int is_sphere = type == WP_SHAPE_SPHERE;
        uv.u = is_sphere ? sphere.u : uv.u, uv.v = is_sphere ? sphere.v : uv.v;
    }
#endif
#ifdef WP_HAS_QUADS
    {
        lane_int is_quad = type == WP_SHAPE_QUAD;
        lane_uint i = is_quad ? index : (lane_uint)0u;
        TextureUV quad =
            quad_uv(SCENE_FIELD(quads, i, corner), SCENE_FIELD(quads, i, edge1), SCENE_FIELD(quads, i, edge2), point);
        uv.u = is_quad ? quad.u : uv.u, uv.v = is_quad ? quad.v : uv.v;
    }
#endif
#ifdef WP_HAS_MESHES
    {
        lane_int is_triangle = type == WP_SHAPE_TRIANGLE;
        lane_uint i = is_triangle ? index : (lane_uint)0u;
        TriangleBarycentrics b = triangle_barycentrics(SCENE_FIELD(triangles, i, p0), SCENE_FIELD(triangles, i, p1),
                                                       SCENE_FIELD(triangles, i, p2), point);
        lane_uint words = i * WP_STRUCT_WORDS(triangle_uvs);
        TextureUV uv0 = make_texture_uv(gather(&triangle_uvs->uv0[0], words), gather(&triangle_uvs->uv0[1], words));
        TextureUV uv1 = make_texture_uv(gather(&triangle_uvs->uv1[0], words), gather(&triangle_uvs->uv1[1], words));
        TextureUV uv2 = make_texture_uv(gather(&triangle_uvs->uv2[0], words), gather(&triangle_uvs->uv2[1], words));
        TextureUV triangle = triangle_uv(uv0, uv1, uv2, b.b1, b.b2);
        uv.u = is_triangle ? triangle.u : uv.u, uv.v = is_triangle ? triangle.v : uv.v;
    }
#endif
    return uv;
}
#endif

/* The surface where the ray (origin, direction) hit `shape` at distance t
 * (shared/hit_point.h). Every shape kind in the scene is evaluated and each
 * lane keeps its own; a lane reads the arrays of the other kinds at index 0. */
WP_FN Surface surface_at(WP_SCENE_PARAMS, lane_uint shape, vec3 origin, vec3 direction, real t) {
    lane_uint index = shape & WP_SHAPE_INDEX_MASK;
    lane_uint type = shape >> WP_SHAPE_TYPE_SHIFT;
    HitPoint hit;
    hit.point = hit.normal = make_vec3(REAL(0.0), REAL(0.0), REAL(0.0));
    hit.error = REAL(0.0);
    lane_uint material = 0u;
#ifdef WP_HAS_SPHERES
    {
        lane_int is_sphere = type == WP_SHAPE_SPHERE;
        lane_uint i = is_sphere ? index : (lane_uint)0u;
        HitPoint h = sphere_hit(SCENE_FIELD(spheres, i, center), SCENE_FIELD(spheres, i, radius), origin, direction, t);
        hit = select_hit_point(is_sphere, h, hit);
        material = is_sphere ? SCENE_FIELD(spheres, i, material) : material;
    }
#endif
#ifdef WP_HAS_PLANES
    {
        lane_int is_plane = type == WP_SHAPE_PLANE;
        lane_uint i = is_plane ? index : (lane_uint)0u;
        HitPoint h = plane_hit(SCENE_FIELD(planes, i, point), SCENE_FIELD(planes, i, normal), origin, direction, t);
        hit = select_hit_point(is_plane, h, hit);
        material = is_plane ? SCENE_FIELD(planes, i, material) : material;
    }
#endif
#ifdef WP_HAS_QUADS
    {
        lane_int is_quad = type == WP_SHAPE_QUAD;
        lane_uint i = is_quad ? index : (lane_uint)0u;
        HitPoint h = quad_hit(SCENE_FIELD(quads, i, corner), SCENE_FIELD(quads, i, edge1), SCENE_FIELD(quads, i, edge2),
                              origin, direction, t);
        hit = select_hit_point(is_quad, h, hit);
        material = is_quad ? SCENE_FIELD(quads, i, material) : material;
    }
#endif
#ifdef WP_HAS_MESHES
    {
        lane_int is_triangle = type == WP_SHAPE_TRIANGLE;
        lane_uint i = is_triangle ? index : (lane_uint)0u;
        HitPoint h = triangle_hit(SCENE_FIELD(triangles, i, p0), SCENE_FIELD(triangles, i, p1),
                                  SCENE_FIELD(triangles, i, p2), origin, direction);
        hit = select_hit_point(is_triangle, h, hit);
        material = is_triangle ? SCENE_FIELD(triangles, i, material) : material;
    }
#endif
    Surface s;
    s.point = hit.point;
    s.normal = hit.normal;
    s.material = material;
    s.error = hit.error;
#ifdef WP_HAS_SHADING_NORMALS
    s.shading = shading_normal(WP_SCENE_ARGS, shape, s.normal, s.point);
#else
    s.shading = s.normal;
#endif
#ifdef WP_HAS_TEXTURES
    s.uv = make_texture_uv(REAL(0.0), REAL(0.0));
#endif
    return s;
}

/* A function that takes or returns a Vertex or a Material by value (every
 * field of the vertex's material, per lane): always inlined. Where LLVM's
 * inliner calls one instead, which it starts doing as a scene's kernel
 * grows (material kinds on no shape were enough), the struct is copied
 * through the stack at every call: 1.37x the kernels' instructions on
 * bench/scenes/materials.json (bench/results/analysis.md, "Materials
 * against Mitsuba 3"). */
#define WP_VERTEX_FN static inline __attribute__((always_inline))

/* A material's fields, per lane; only those of the material kinds in the scene. */
typedef struct {
    lane_uint type; /* WP_MATERIAL_* */
    lane_int two_sided;
#ifdef WP_HAS_ONE_SIDED
    lane_int one_sided; /* black from the back */
#endif
    vec3 emission;
#ifdef WP_HAS_DIFFUSE
    vec3 albedo;
#endif
#ifdef WP_HAS_MIRROR
    vec3 reflectance;
#endif
#ifdef WP_HAS_DIELECTRICS
    real ior;
#endif
#ifdef WP_HAS_CONDUCTORS
    vec3 eta, k, specular_reflectance;
#endif
#ifdef WP_HAS_MICROFACET
    Microfacet microfacet;
#endif
#ifdef WP_HAS_PLASTIC
    PlasticParams plastic;
#endif
#ifdef WP_HAS_ROUGH_PLASTIC
    RoughPlasticParams roughplastic; /* its table: the vertex's roughplastic_table */
#endif
#ifdef WP_HAS_MASK
    real opacity; /* mask_opacity's: 1 on a material that no mask wraps */
#endif
} Material;

/* Whether some lane of the vector has material kind `kind`: its code runs
 * only then (a vertex pays for the kinds its vector holds, not for every
 * kind compiled in: bench/results/analysis.md, "Materials against Mitsuba
 * 3"). With one kind of BSDF in the scene every lane that scatters has it,
 * and the test is compiled out. */
WP_FN int lanes_have_kind(lane_uint type, uint kind) {
#ifdef WP_HAS_MIXED_MATERIALS
    return lanes_any(type == kind);
#else
    return 1;
#endif
}

/* What a light's material emits: all that a light sample or a photon's
 * emission reads of it. */
typedef struct {
    vec3 emission;
    lane_int two_sided; /* emits from both sides */
} Emission;

WP_FN Emission emission_at(__global const DeviceMaterial *materials, lane_uint index) {
    Emission e;
    e.emission = SCENE_FIELD(materials, index, emission);
    e.two_sided = SCENE_FIELD(materials, index, two_sided) != 0u;
    return e;
}

/* A material's fields, per lane, each group loaded only where some lane's
 * kind reads it (lanes_have_kind): a gather costs a load per lane, and a
 * vertex pays for the kinds its vector holds. The lanes of other kinds
 * hold zeros, and a microfacet distribution of none (WP_MICROFACET_NONE, so
 * that they ask for no distribution's work) of roughness 1. The plastics'
 * constants are still loaded at every vertex: gating them wants one loader
 * of the fields their two structs share. */
WP_VERTEX_FN Material material_at(__global const DeviceMaterial *materials, lane_uint index) {
    Material m;
    m.type = SCENE_FIELD(materials, index, type);
    m.two_sided = SCENE_FIELD(materials, index, two_sided) != 0u;
#ifdef WP_HAS_ONE_SIDED
    m.one_sided = SCENE_FIELD(materials, index, one_sided) != 0u;
#endif
    m.emission = SCENE_FIELD(materials, index, emission);
    vec3 zero = make_vec3(REAL(0.0), REAL(0.0), REAL(0.0));
#ifdef WP_HAS_DIFFUSE
    m.albedo = lanes_have_kind(m.type, WP_MATERIAL_DIFFUSE) ? SCENE_FIELD(materials, index, albedo) : zero;
#endif
#ifdef WP_HAS_MIRROR
    m.reflectance = lanes_have_kind(m.type, WP_MATERIAL_MIRROR) ? SCENE_FIELD(materials, index, reflectance) : zero;
#endif
#ifdef WP_HAS_DIELECTRICS
    m.ior = REAL(0.0);
    if (lanes_have_kind(m.type, WP_MATERIAL_GLASS) || lanes_have_kind(m.type, WP_MATERIAL_ROUGH_DIELECTRIC) ||
        lanes_have_kind(m.type, WP_MATERIAL_THIN_DIELECTRIC))
        m.ior = SCENE_FIELD(materials, index, ior);
#endif
#ifdef WP_HAS_CONDUCTORS
    m.eta = m.k = m.specular_reflectance = zero;
    if (lanes_have_kind(m.type, WP_MATERIAL_CONDUCTOR) || lanes_have_kind(m.type, WP_MATERIAL_ROUGH_CONDUCTOR)) {
        m.eta = SCENE_FIELD(materials, index, eta);
        m.k = SCENE_FIELD(materials, index, k);
        m.specular_reflectance = SCENE_FIELD(materials, index, specular_reflectance);
    }
#endif
#ifdef WP_HAS_MICROFACET
    m.microfacet.distribution = WP_MICROFACET_NONE;
    m.microfacet.alpha_u = m.microfacet.alpha_v = REAL(1.0);
    if (lanes_have_kind(m.type, WP_MATERIAL_ROUGH_CONDUCTOR) || lanes_have_kind(m.type, WP_MATERIAL_ROUGH_DIELECTRIC) ||
        lanes_have_kind(m.type, WP_MATERIAL_ROUGH_PLASTIC)) {
        m.microfacet.distribution = SCENE_FIELD(materials, index, distribution);
        m.microfacet.alpha_u = SCENE_FIELD(materials, index, alpha_u);
        m.microfacet.alpha_v = SCENE_FIELD(materials, index, alpha_v);
    }
#endif
#ifdef WP_HAS_PLASTIC
    m.plastic.diffuse_reflectance = SCENE_FIELD(materials, index, albedo);
    m.plastic.specular_reflectance = SCENE_FIELD(materials, index, specular_reflectance);
    m.plastic.eta = SCENE_FIELD(materials, index, ior);
    m.plastic.inv_eta_2 = SCENE_FIELD(materials, index, inv_eta_2);
    m.plastic.fdr_int = SCENE_FIELD(materials, index, internal_reflectance);
    m.plastic.specular_sampling_weight = SCENE_FIELD(materials, index, specular_sampling_weight);
    m.plastic.nonlinear = SCENE_FIELD(materials, index, nonlinear) != 0u;
#endif
#ifdef WP_HAS_ROUGH_PLASTIC
    m.roughplastic.m = m.microfacet;
    m.roughplastic.diffuse_reflectance = SCENE_FIELD(materials, index, albedo);
    m.roughplastic.specular_reflectance = SCENE_FIELD(materials, index, specular_reflectance);
    m.roughplastic.eta = SCENE_FIELD(materials, index, ior);
    m.roughplastic.inv_eta_2 = SCENE_FIELD(materials, index, inv_eta_2);
    m.roughplastic.specular_sampling_weight = SCENE_FIELD(materials, index, specular_sampling_weight);
    m.roughplastic.internal_reflectance = SCENE_FIELD(materials, index, internal_reflectance);
    m.roughplastic.nonlinear = SCENE_FIELD(materials, index, nonlinear) != 0u;
    m.roughplastic.transmittance_offset = SCENE_FIELD(materials, index, transmittance_offset);
#endif
#ifdef WP_HAS_MASK
    m.opacity = SCENE_FIELD(materials, index, opacity);
#endif
    return m;
}

#ifdef WP_HAS_TEXTURES
/* Texture `index`'s fields, per lane: a bitmap's and a checkerboard's each
 * loaded only where some lane's texture is of that type, as material_at's
 * (the lanes of the other type then hold a checkerboard's 1 x 1 texels at
 * 0, or black, which texture_value does not read). */
WP_FN Texture texture_at(__global const TextureDescriptor *textures, lane_uint index) {
    Texture t;
    t.type = SCENE_FIELD(textures, index, type);
    lane_uint words = index * WP_STRUCT_WORDS(textures);
    for (int k = 0; k < 6; ++k) t.to_uv[k] = gather(&textures->to_uv[k], words);
    t.filter = t.wrap = t.first_texel = 0u;
    t.width = t.height = 1u;
    if (lanes_any(t.type == WP_TEXTURE_BITMAP)) {
        t.filter = SCENE_FIELD(textures, index, filter);
        t.wrap = SCENE_FIELD(textures, index, wrap);
        t.width = SCENE_FIELD(textures, index, width);
        t.height = SCENE_FIELD(textures, index, height);
        t.first_texel = SCENE_FIELD(textures, index, first_texel);
    }
    t.color0 = t.color1 = make_vec3(REAL(0.0), REAL(0.0), REAL(0.0));
    if (lanes_any(t.type == WP_TEXTURE_CHECKERBOARD)) {
        t.color0 = SCENE_FIELD(textures, index, color0);
        t.color1 = SCENE_FIELD(textures, index, color1);
    }
    return t;
}

/* The textures of a material's parameters, per WP_TEXTURED_*: an index
 * into the textures, or WP_NO_TEXTURE (MaterialTextures' row), per lane. */
typedef struct {
    lane_uint texture[WP_TEXTURED_PARAMETERS];
} ParameterTextures;

WP_FN ParameterTextures parameter_textures(WP_SCENE_PARAMS, lane_uint material) {
    ParameterTextures p;
    for (uint k = 0u; k < WP_TEXTURED_PARAMETERS; ++k)
        p.texture[k] = gather(&material_textures->texture[k], material * WP_STRUCT_WORDS(material_textures));
    return p;
}

/* Whether some parameter of the lane's material is textured. */
WP_FN lane_int has_texture(ParameterTextures p) {
    lane_int any = p.texture[0] != WP_NO_TEXTURE;
    for (uint k = 1u; k < WP_TEXTURED_PARAMETERS; ++k) any = any | (p.texture[k] != WP_NO_TEXTURE);
    return any;
}

/* The textures' entry `texture`, or any entry where it is WP_NO_TEXTURE
 * (the parameter functions then keep the constant). */
WP_INLINED_FN Texture parameter_texture(__global const TextureDescriptor *textures, lane_uint texture) {
    return texture_at(textures, texture != WP_NO_TEXTURE ? texture : (lane_uint)0u);
}

/* A colour parameter of texture `texture` at uv, `untextured` where it has
 * none (colour_parameter); a texture is read only where some lane's
 * material names one. */
WP_FN vec3 material_colour(WP_SCENE_PARAMS, lane_uint texture, TextureUV uv, vec3 untextured) {
    if (!lanes_any(texture != WP_NO_TEXTURE)) return untextured;
    return colour_parameter(untextured, texture, parameter_texture(textures, texture), texels, uv);
}

#if defined(WP_HAS_ROUGH_CONDUCTOR) || defined(WP_HAS_ROUGH_DIELECTRIC) || defined(WP_HAS_MASK)
/* A scalar parameter, as material_colour (scalar_parameter). */
WP_FN real material_scalar(WP_SCENE_PARAMS, lane_uint texture, TextureUV uv, real untextured) {
    if (!lanes_any(texture != WP_NO_TEXTURE)) return untextured;
    return scalar_parameter(untextured, texture, parameter_texture(textures, texture), texels, uv);
}
#endif

/* m, the fields of `material`, with its textured parameters (p) looked up
 * at uv (the lanes whose material has none keep its constants). */
WP_VERTEX_FN Material textured_material(WP_SCENE_PARAMS, Material m, lane_uint material, ParameterTextures p,
                                        TextureUV uv) {
#if defined(WP_HAS_DIFFUSE) || defined(WP_HAS_PLASTICS)
    vec3 albedo =
        material_colour(WP_SCENE_ARGS, p.texture[WP_TEXTURED_ALBEDO], uv, SCENE_FIELD(materials, material, albedo));
#endif
#if defined(WP_HAS_CONDUCTORS) || defined(WP_HAS_PLASTICS)
    vec3 specular = material_colour(WP_SCENE_ARGS, p.texture[WP_TEXTURED_SPECULAR_REFLECTANCE], uv,
                                    SCENE_FIELD(materials, material, specular_reflectance));
#endif
#ifdef WP_HAS_DIFFUSE
    m.albedo = albedo;
#endif
#ifdef WP_HAS_CONDUCTORS
    m.specular_reflectance = specular;
#endif
#ifdef WP_HAS_PLASTIC
    m.plastic.diffuse_reflectance = albedo;
    m.plastic.specular_reflectance = specular;
#endif
#ifdef WP_HAS_ROUGH_PLASTIC
    m.roughplastic.diffuse_reflectance = albedo;
    m.roughplastic.specular_reflectance = specular;
#endif
#if defined(WP_HAS_ROUGH_CONDUCTOR) || defined(WP_HAS_ROUGH_DIELECTRIC)
    /* roughplastic's roughness is untextured (Mitsuba's tables depend on it): m.roughplastic.m keeps it */
    m.microfacet.alpha_u = material_scalar(WP_SCENE_ARGS, p.texture[WP_TEXTURED_ALPHA_U], uv, m.microfacet.alpha_u);
    m.microfacet.alpha_v = material_scalar(WP_SCENE_ARGS, p.texture[WP_TEXTURED_ALPHA_V], uv, m.microfacet.alpha_v);
#endif
#ifdef WP_HAS_MASK
    m.opacity = mask_opacity(material_scalar(WP_SCENE_ARGS, p.texture[WP_TEXTURED_OPACITY], uv, m.opacity));
#endif
    return m;
}
#endif

#ifdef WP_PERTURBS_NORMALS
/* The side's normal and no terminator term: a surface that no map bends. */
WP_FN NormalMapped side_as_mapped(vec3 side) {
    NormalMapped none;
    none.normal = side;
    none.terminator_alpha2 = REAL(0.0);
    return none;
}

/* m where the lane's material has a map (`texture`), else side_as_mapped. */
WP_FN NormalMapped where_mapped(lane_uint texture, vec3 side, NormalMapped m) {
    lane_int mapped = texture != WP_NO_TEXTURE;
    m.normal = v3_select(mapped, m.normal, side);
    m.terminator_alpha2 = mapped ? m.terminator_alpha2 : REAL(0.0);
    return m;
}
#endif

#if defined(WP_HAS_NORMAL_MAP) || defined(WP_HAS_ANISOTROPIC_ROUGHNESS)
/* dp/du at surface s of `shape` (shared/surface_tangents.h): every shape kind in
 * the scene is evaluated and each lane keeps its own kind's; zero on planes. */
WP_FN vec3 surface_dp_du(WP_SCENE_PARAMS, lane_uint shape, Surface s) {
    lane_uint index = shape & WP_SHAPE_INDEX_MASK;
    lane_uint type = shape >> WP_SHAPE_TYPE_SHIFT;
    vec3 dp_du = make_vec3(REAL(0.0), REAL(0.0), REAL(0.0));
#ifdef WP_HAS_SPHERES
    dp_du = v3_select(type == WP_SHAPE_SPHERE, sphere_dp_du(s.normal), dp_du);
#endif
#ifdef WP_HAS_QUADS
    {
        lane_int is_quad = type == WP_SHAPE_QUAD;
        dp_du = v3_select(is_quad, SCENE_FIELD(quads, is_quad ? index : (lane_uint)0u, edge1), dp_du);
    }
#endif
#ifdef WP_HAS_MESHES
    {
        lane_int is_triangle = type == WP_SHAPE_TRIANGLE;
        lane_uint i = is_triangle ? index : (lane_uint)0u;
        lane_uint words = i * WP_STRUCT_WORDS(triangle_uvs);
        vec3 triangle =
            triangle_dp_du(SCENE_FIELD(triangles, i, p0), SCENE_FIELD(triangles, i, p1), SCENE_FIELD(triangles, i, p2),
                           gather(&triangle_uvs->uv0[0], words), gather(&triangle_uvs->uv0[1], words),
                           gather(&triangle_uvs->uv1[0], words), gather(&triangle_uvs->uv1[1], words),
                           gather(&triangle_uvs->uv2[0], words), gather(&triangle_uvs->uv2[1], words));
        dp_du = v3_select(is_triangle, triangle, dp_du);
    }
#endif
    return dp_du;
}
#endif

#ifdef WP_HAS_NORMAL_MAP
/* The shading normal of surface s of `shape`, turned to wo's side (`side`),
 * perturbed by its material's normal map `texture` (shared/normal_map.h):
 * `side` itself, and no terminator term, where the material has none
 * (WP_NO_TEXTURE); the map is read only where some lane's material has one. */
WP_FN NormalMapped surface_normal_mapped(WP_SCENE_PARAMS, lane_uint shape, Surface s, lane_uint texture, vec3 side,
                                         vec3 wo) {
    if (!lanes_any(texture != WP_NO_TEXTURE)) return side_as_mapped(side);
    vec3 colour = texture_value(parameter_texture(textures, texture), texels, s.uv);
    return where_mapped(texture, side,
                        normal_mapped(s.shading, side, surface_dp_du(WP_SCENE_ARGS, shape, s), colour, wo));
}
#endif

#ifdef WP_HAS_BUMP_MAP
/* dp/du and dp/dv at surface s of `shape`, to their length
 * (shared/normal_map.h' bump_mapped): every shape kind in the scene is
 * evaluated and each lane keeps its own kind's; zero on planes. */
WP_FN SurfaceTangents surface_tangents(WP_SCENE_PARAMS, lane_uint shape, Surface s) {
    lane_uint index = shape & WP_SHAPE_INDEX_MASK;
    lane_uint type = shape >> WP_SHAPE_TYPE_SHIFT;
    SurfaceTangents tangents;
    tangents.dp_du = make_vec3(REAL(0.0), REAL(0.0), REAL(0.0));
    tangents.dp_dv = tangents.dp_du;
#ifdef WP_HAS_SPHERES
    {
        lane_int is_sphere = type == WP_SHAPE_SPHERE;
        SurfaceTangents sphere =
            sphere_tangents(s.normal, SCENE_FIELD(spheres, is_sphere ? index : (lane_uint)0u, radius));
        tangents.dp_du = v3_select(is_sphere, sphere.dp_du, tangents.dp_du);
        tangents.dp_dv = v3_select(is_sphere, sphere.dp_dv, tangents.dp_dv);
    }
#endif
#ifdef WP_HAS_QUADS
    {
        lane_int is_quad = type == WP_SHAPE_QUAD;
        lane_uint i = is_quad ? index : (lane_uint)0u;
        tangents.dp_du = v3_select(is_quad, SCENE_FIELD(quads, i, edge1), tangents.dp_du);
        tangents.dp_dv = v3_select(is_quad, SCENE_FIELD(quads, i, edge2), tangents.dp_dv);
    }
#endif
#ifdef WP_HAS_MESHES
    {
        lane_int is_triangle = type == WP_SHAPE_TRIANGLE;
        lane_uint i = is_triangle ? index : (lane_uint)0u;
        lane_uint words = i * WP_STRUCT_WORDS(triangle_uvs);
        vec3 p0 = SCENE_FIELD(triangles, i, p0), p1 = SCENE_FIELD(triangles, i, p1), p2 = SCENE_FIELD(triangles, i, p2);
        real u0 = gather(&triangle_uvs->uv0[0], words), v0 = gather(&triangle_uvs->uv0[1], words);
        real u1 = gather(&triangle_uvs->uv1[0], words), v1 = gather(&triangle_uvs->uv1[1], words);
        real u2 = gather(&triangle_uvs->uv2[0], words), v2 = gather(&triangle_uvs->uv2[1], words);
        tangents.dp_du = v3_select(is_triangle, triangle_dp_du(p0, p1, p2, u0, v0, u1, v1, u2, v2), tangents.dp_du);
        tangents.dp_dv = v3_select(is_triangle, triangle_dp_dv(p0, p1, p2, u0, v0, u1, v1, u2, v2), tangents.dp_dv);
    }
#endif
    return tangents;
}

/* The shading normal of surface s of `shape`, turned to wo's side (`side`),
 * bent by its material's bump map `texture` (shared/normal_map.h' bump_mapped,
 * the height's gradient times the material's bump_scale): `side` itself, and
 * no terminator term, where the material has none (WP_NO_TEXTURE); the map
 * is read only where some lane's material has one. */
WP_FN NormalMapped surface_bump_mapped(WP_SCENE_PARAMS, lane_uint shape, Surface s, lane_uint texture, vec3 side,
                                       vec3 wo) {
    if (!lanes_any(texture != WP_NO_TEXTURE)) return side_as_mapped(side);
    TextureUV gradient = texture_gradient(parameter_texture(textures, texture), texels, s.uv);
    real scale = SCENE_FIELD(materials, s.material, bump_scale);
    SurfaceTangents tangents = surface_tangents(WP_SCENE_ARGS, shape, s);
    return where_mapped(texture, side,
                        bump_mapped(s.normal, s.shading, side, tangents.dp_du, tangents.dp_dv, scale * gradient.u,
                                    scale * gradient.v, wo));
}
#endif

/* A path's vertex where its ray (origin, direction) hit `shape` at t. */
typedef struct {
    Surface surface;
    Material material;
    vec3 wo;        /* back along the ray: -direction */
    lane_int front; /* the ray met the side the geometric normal points to */
    vec3 nf;        /* the geometric normal on the ray's side: where spawned rays start */
    vec3 ns;        /* the shading normal on the same side: what BSDFs and cosines use */
#ifdef WP_PERTURBS_NORMALS
    vec3 ns_unperturbed;    /* ns before the material's normal or bump map: what its terminator term measures from */
    real terminator_alpha2; /* the map's terminator term (normal_map_terminator); 0: none */
#endif
#ifdef WP_VERTEX_MAY_NOT_SHADE
    lane_int shades; /* the material scatters the path at all (normal_map_shades, a one-sided material's front) */
#endif
#ifdef WP_HAS_ROUGH_PLASTIC
    __global const float *roughplastic_table; /* the scene's roughplastic_transmittance */
#endif
#ifdef WP_HAS_ANISOTROPIC_ROUGHNESS
    vec3 dp_du; /* the surface's: where an anisotropic material's alpha_u lies (microfacet_frame) */
#endif
} Vertex;

WP_VERTEX_FN Vertex vertex_at(WP_SCENE_PARAMS, lane_uint shape, vec3 origin, vec3 direction, real t) {
    Vertex v;
    v.surface = surface_at(WP_SCENE_ARGS, shape, origin, direction, t);
    v.material = material_at(materials, v.surface.material);
#ifdef WP_HAS_TEXTURES
    ParameterTextures parameters = parameter_textures(WP_SCENE_ARGS, v.surface.material);
    if (lanes_any(has_texture(parameters))) { /* a vector of untextured hits needs no uv */
        v.surface.uv = surface_uv(WP_SCENE_ARGS, shape, v.surface.point, v.surface.normal);
        v.material = textured_material(WP_SCENE_ARGS, v.material, v.surface.material, parameters, v.surface.uv);
    }
#endif
    v.wo = v3_neg(direction);
#ifdef WP_HAS_ROUGH_PLASTIC
    v.roughplastic_table = roughplastic_transmittance;
#endif
#ifdef WP_HAS_ANISOTROPIC_ROUGHNESS
    v.dp_du = surface_dp_du(WP_SCENE_ARGS, shape, v.surface);
#endif
    FacingNormals facing = normals_facing(direction, v.surface.normal, v.surface.shading);
    v.front = facing.front;
    v.nf = facing.nf;
    v.ns = facing.ns;
#ifdef WP_PERTURBS_NORMALS
    NormalMapped mapped;
    lane_int adapted; /* the material is a normalmap or a bumpmap (a material is at most one) */
#ifdef WP_HAS_NORMAL_MAP
    lane_uint normal_map = parameters.texture[WP_TEXTURED_NORMAL_MAP];
    mapped = surface_normal_mapped(WP_SCENE_ARGS, shape, v.surface, normal_map, v.ns, v.wo);
    adapted = normal_map != WP_NO_TEXTURE;
#else
    mapped.normal = v.ns;
    mapped.terminator_alpha2 = REAL(0.0);
    adapted = 0;
#endif
#ifdef WP_HAS_BUMP_MAP
    lane_uint bump_map = parameters.texture[WP_TEXTURED_BUMP_MAP];
    NormalMapped bumped = surface_bump_mapped(WP_SCENE_ARGS, shape, v.surface, bump_map, v.ns, v.wo);
    lane_int bumps = bump_map != WP_NO_TEXTURE;
    mapped.normal = v3_select(bumps, bumped.normal, mapped.normal);
    mapped.terminator_alpha2 = bumps ? bumped.terminator_alpha2 : mapped.terminator_alpha2;
    adapted = adapted || bumps;
#endif
    v.ns_unperturbed = v.ns;
    v.ns = mapped.normal;
    v.terminator_alpha2 = mapped.terminator_alpha2;
    v.shades = !adapted || normal_map_shades(v.wo, v.ns);
#elif defined(WP_VERTEX_MAY_NOT_SHADE)
    v.shades = 1;
#endif
#ifdef WP_HAS_ONE_SIDED
    v.shades = v.shades && (v.front || !v.material.one_sided);
#endif
    return v;
}

#endif
