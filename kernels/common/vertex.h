/* The work at one path vertex, shared by the wavefront's stage kernels and
 * the megakernel so that both compute exactly the reference's estimator
 * (docs/architecture.md, "Conventions"): the camera ray, emission seen at a
 * hit, the light sample of next-event estimation, BSDF sampling and Russian
 * roulette. Needs wavefront.h (scene layout, Surface) first. */
#ifndef WP_VERTEX_H
#define WP_VERTEX_H

/* The camera ray direction of sample s of pixel px (the camera is at the origin). */
WP_FN vec3 camera_ray_direction(__global const SceneHeader *scene, uint px, uint s) {
    uint x = px % scene->width, y = px / scene->width;
    real u0 = rng_uniform(scene->seed, px, s, 0u, DIM_FILM_X);
    real u1 = rng_uniform(scene->seed, px, s, 0u, DIM_FILM_Y);
    return camera_direction(vec3_at(scene->camera_right), vec3_at(scene->camera_up), vec3_at(scene->camera_forward),
                            scene->tan_half_fov_y, scene->aspect, ((real)x + u0) / (real)scene->width,
                            ((real)y + u1) / (real)scene->height);
}

/* Emission the path adds at a hit: when the material emits towards the ray
 * (or is two-sided) and the previous vertex was the camera or specular, or
 * at every hit when NEE is off (-DWP_NEE_OFF). */
WP_FN vec3 emission_seen(__global const DeviceMaterial *m, real cos_incident, int after_specular, vec3 throughput) {
    vec3 emission = vec3_at(m->emission);
    int emits = emission.x > REAL(0.0) || emission.y > REAL(0.0) || emission.z > REAL(0.0);
#ifdef WP_NEE_OFF
    after_specular = 1; /* pure BSDF sampling: no light sample accounts for this emission */
#endif
    int seen = emits && (m->two_sided || cos_incident < REAL(0.0)) && after_specular;
    return v3_select(seen, v3_mul(throughput, emission), make_vec3(REAL(0.0), REAL(0.0), REAL(0.0)));
}

/* Samples one light for the diffuse vertex (x, nf); returns 1 with the shadow
 * ray and the contribution it adds when unoccluded, 0 when the sample carries
 * nothing. */
#ifdef WP_HAS_NEE
WP_FN int sample_direct_light(WP_SCENE_PARAMS, uint pixel, uint sample, uint bounce, vec3 x, real x_error, vec3 nf,
                              vec3 weight,
                              vec3 *shadow_origin, vec3 *shadow_direction, real *shadow_distance,
                              vec3 *contribution) {
    uint seed = scene->seed;
    uint light = select_light(light_cdf, LIGHT_COUNT, rng_uniform(seed, pixel, sample, bounce, DIM_LIGHT_SELECT));
    real pmf = light_selection_pmf(light_cdf, light);
    real u = rng_uniform(seed, pixel, sample, bounce, DIM_LIGHT_U);
    real v = rng_uniform(seed, pixel, sample, bounce, DIM_LIGHT_V);
    uint index = lights[light].shape & WP_SHAPE_INDEX_MASK;
    LightSample ls;
    uint material = 0u;
    real magnitude = REAL(0.0);
#ifdef WP_HAS_SPHERE_LIGHTS
    if ((lights[light].shape >> WP_SHAPE_TYPE_SHIFT) == WP_SHAPE_SPHERE) {
        vec3 center = vec3_at(spheres[index].center);
        ls = sample_sphere(center, spheres[index].radius, x, u, v);
        material = spheres[index].material;
        magnitude = sphere_magnitude(center, spheres[index].radius);
    }
#endif
#ifdef WP_HAS_QUAD_LIGHTS
    if ((lights[light].shape >> WP_SHAPE_TYPE_SHIFT) == WP_SHAPE_QUAD) {
        vec3 corner = vec3_at(quads[index].corner), edge1 = vec3_at(quads[index].edge1);
        vec3 edge2 = vec3_at(quads[index].edge2);
        ls = sample_quad(corner, edge1, edge2, x, u, v);
        material = quads[index].material;
        magnitude = quad_magnitude(corner, edge1, edge2);
    }
#endif
    if (ls.pdf_solid_angle == REAL(0.0)) return 0;
    vec3 wi = v3_normalize(v3_sub(ls.point, x));
    real cos_surface = v3_dot(wi, nf);
    int light_faces_x = v3_dot(ls.normal, v3_sub(x, ls.point)) > REAL(0.0);
    if (!(cos_surface > REAL(0.0)) || !(materials[material].two_sided || light_faces_x)) return 0;
    vec3 from = offset_ray_origin(x, nf, x_error);
    vec3 to = offset_ray_origin(ls.point, v3_select(light_faces_x, ls.normal, v3_neg(ls.normal)),
                                shadow_target_error(x, ls.point, magnitude));
    vec3 along = v3_sub(to, from);
    *shadow_distance = v3_length(along);
    *shadow_direction = v3_div(along, *shadow_distance);
    *shadow_origin = from;
    /* in the reference's order of operations */
    *contribution = v3_div(v3_scale(v3_mul(v3_scale(weight, WP_INV_PI), vec3_at(materials[material].emission)),
                                    cos_surface),
                           ls.pdf_solid_angle * pmf);
    return 1;
}
#endif

typedef struct {
    vec3 direction;
    vec3 weight;      /* throughput factor */
    vec3 leave_side;  /* normal on the side the new ray leaves into */
    uint specular;
} Scattered;

WP_FN Scattered scatter_diffuse(__global const DeviceMaterial *m, vec3 nf, real u, real v) {
    Scattered s;
#ifdef WP_UNIFORM_HEMISPHERE
    vec3 in_frame = sample_uniform_hemisphere(u, v); /* `local` is an OpenCL keyword */
    s.weight = v3_scale(vec3_at(m->albedo), REAL(2.0) * in_frame.z); /* albedo/pi * cos / (1/(2 pi)) */
#else
    vec3 in_frame = sample_cosine_hemisphere(u, v);
    s.weight = vec3_at(m->albedo);
#endif
    s.direction = frame_to_world(frame_from_normal(nf), in_frame);
    s.leave_side = nf;
    s.specular = 0u;
    return s;
}

#ifdef WP_HAS_MIRROR
WP_FN Scattered scatter_mirror(__global const DeviceMaterial *m, vec3 d, vec3 nf) {
    Scattered s;
    s.direction = reflect_direction(d, nf);
    s.weight = vec3_at(m->reflectance);
    s.leave_side = nf;
    s.specular = 1u;
    return s;
}
#endif

#ifdef WP_HAS_GLASS
/* Fresnel chooses reflection or refraction; refraction scales radiance by 1/eta^2. */
WP_FN Scattered scatter_glass(__global const DeviceMaterial *m, vec3 d, vec3 nf, int entering, real u_lobe) {
    Scattered s;
    real eta = entering ? m->ior : REAL(1.0) / m->ior;
    real reflectance = fresnel_dielectric(-v3_dot(d, nf), eta);
    s.specular = 1u;
    s.weight = make_vec3(REAL(1.0), REAL(1.0), REAL(1.0));
    s.leave_side = nf;
    s.direction = reflect_direction(d, nf);
    vec3 refracted;
    if (u_lobe >= reflectance && refract_direction(d, nf, eta, &refracted)) {
        s.direction = refracted;
        s.weight = v3_div(s.weight, eta * eta);
        s.leave_side = v3_neg(nf);
    }
    return s;
}
#endif

/* BSDF sampling at bounce `bounce` for the material's type. */
WP_FN Scattered scatter_vertex(__global const DeviceMaterial *m, vec3 d, vec3 nf, int entering, uint seed, uint px,
                               uint s, uint bounce) {
    Scattered scattered;
#ifdef WP_HAS_DIFFUSE
    if (m->type == WP_MATERIAL_DIFFUSE)
        return scatter_diffuse(m, nf, rng_uniform(seed, px, s, bounce, DIM_BSDF_U),
                                    rng_uniform(seed, px, s, bounce, DIM_BSDF_V));
#endif
#ifdef WP_HAS_MIRROR
    if (m->type == WP_MATERIAL_MIRROR) return scatter_mirror(m, d, nf);
#endif
#ifdef WP_HAS_GLASS
    if (m->type == WP_MATERIAL_GLASS)
        return scatter_glass(m, d, nf, entering, rng_uniform(seed, px, s, bounce, DIM_BSDF_LOBE));
#endif
    return scattered;
}

/* Russian roulette once new_depth reaches rr_depth: survival probability
 * clamp(max_component(T), 0.05, 1), and T /= survival when the path survives. */
WP_FN int survives_roulette(vec3 *throughput, uint seed, uint px, uint s, uint bounce, uint new_depth, uint rr_depth) {
    if (new_depth < rr_depth) return 1;
    real survival = wp_clamp(max_component(*throughput), REAL(0.05), REAL(1.0));
    int survives = rng_uniform(seed, px, s, bounce, DIM_ROULETTE) < survival;
    *throughput = v3_div(*throughput, survival);
    return survives;
}

#endif
