"""The mutants of scripts/mutation_study.py: small bugs in the estimator and its guards.

Each is (name, file, exact original snippet, replacement, what it changes, the
tests that claim to cover that code). The snippet must occur exactly once in
the file (mutation_study.py --check, a CTest test, fails when it does not).
The tests are those whose names or comments claim the code, not ones picked
because they are known to fail: the point is whether the suite catches the bug.
`note` says, for a mutant that survives, why (an equivalent change, or a gap
and what covers it), and for one killed only by a test added for the study,
which; the study writes it into docs/mutation-study.md.
"""
from dataclasses import dataclass, field


@dataclass(frozen=True)
class GTest:
    """Tests of one test program (its CMake target under tests/), by gtest filter."""
    binary: str
    filter: str


@dataclass(frozen=True)
class Mutant:
    name: str
    file: str
    original: str
    replacement: str
    change: str
    tests: tuple
    note: str = field(default="")


ESTIMATOR = "kernels/shared/estimator.h"
LIGHTS = "kernels/shared/lights.h"

# Tests that render the reference against closed forms (tests/reference/). The
# meshes' also render on the wavefront, whose kernels a mutant of kernels/shared
# would make OpenCL rebuild (minutes): the reference's instances only.
ANALYTIC = "ReferenceAnalytic/*.*"
MESH_ANALYTIC = "*/MeshAnalytic.*/Reference*"

MUTANTS = [
    # ---------------------------------------------------------------- checkpoints and resume
    Mutant("identity-mesh-loop-skipped", "src/longrun/render_identity.cpp",
           "for (const Mesh& m : scene.meshes) h.add_all(m.positions).add_all(m.normals).add_all(m.triangles).add(m.material);",
           "for (const Mesh& m : scene.meshes) (void)m;",
           "the render identity hashes no mesh content",
           (GTest("test_longrun", "RenderIdentity.*:FilmFileTest.*"),
            GTest("test_cli", "LongRenderCli.ResumeRefuses*:LongRenderCli.RefusedCheckpoints*"))),
    Mutant("identity-seed-not-hashed", "src/longrun/render_identity.cpp",
           "h.add(r.max_depth).add(r.rr_depth).add(r.seed).add(r.nee)",
           "h.add(r.max_depth).add(r.rr_depth).add(r.nee)",
           "the render identity leaves out the seed",
           (GTest("test_longrun", "RenderIdentity.*:FilmFileTest.*"),)),
    Mutant("resume-start-ignored", "src/cli/render_command.cpp",
           "plan.start = film_to_resume(",
           "(void)film_to_resume(",
           "--resume checks the checkpoint but renders from the first sample",
           (GTest("test_cli", "LongRenderCli.*Resume*:MpiCli.*Resume*"),)),
    Mutant("checkpoint-settings-not-checked", "src/longrun/film_file.cpp",
           "if (file.identity.settings != identity.settings)",
           "if (false && file.identity.settings != identity.settings)",
           "a checkpoint of other settings is resumed",
           (GTest("test_longrun", "FilmFileTest.*"), GTest("test_cli", "LongRenderCli.RefusedCheckpoints*"))),
    Mutant("checkpoint-size-not-checked", "src/longrun/film_file.cpp",
           "if (film.width != width || film.height != height)",
           "if (film.width != width)",
           "a checkpoint of another image height is resumed",
           (GTest("test_longrun", "FilmFileTest.*"), GTest("test_cli", "LongRenderCli.RefusedCheckpoints*")),
           "survived the study's first run at 8e89dc2: FilmFileTest.FilmsOfAnotherRenderAreRefused tried only a "
           "wider render, and the CLI's refused checkpoints differ in their identity, which the camera's size is "
           "part of; the test now tries a taller one too."),
    Mutant("checkpoint-checksum-not-checked", "src/longrun/film_file.cpp",
           "if (stored != fnv1a64(bytes.data(), expected - kChecksumBytes))",
           "if (false && stored != fnv1a64(bytes.data(), expected - kChecksumBytes))",
           "a film file whose checksum does not match is read",
           (GTest("test_longrun", "FilmFileTest.*"),)),
    # ---------------------------------------------------------------- the film's exact sums
    Mutant("film-sum-ties-away", "kernels/shared/film_sum.h",
           "if (remainder > halfway || (remainder == halfway && (quotient & 1) != 0)) quotient += 1;",
           "if (remainder >= halfway) quotient += 1;",
           "values below the film's quantum round ties away from zero instead of to even",
           (GTest("test_core", "FilmSum.*:Film.*"),)),
    Mutant("film-sum-carry-lost", "kernels/shared/film_sum.h",
           "next_carry += a.limb[i] < partial ? 1 : 0;",
           "next_carry += 0;",
           "a film sum loses the carry of adding the incoming carry",
           (GTest("test_core", "FilmSum.*:Film.*"),)),
    Mutant("film-to-double-sticky-bit-lost", "src/core/film.cpp",
           "std::ldexp(static_cast<double>(window | (sticky ? 1 : 0)), 64 * top - lead - WP_FILM_FRACTION_BITS);",
           "std::ldexp(static_cast<double>(window), 64 * top - lead - WP_FILM_FRACTION_BITS);",
           "a film sum's conversion to double rounds twice (the sticky bit lost)",
           (GTest("test_core", "FilmSum.*:Film.*"),)),
    # ---------------------------------------------------------------- non-finite guards
    Mutant("reference-guard-off", "src/reference/path_tracer.h",
           "if (SharedMath<Real>::vec3_is_finite(sum)) {",
           "if (true) {",
           "the reference adds non-finite radiance to the path instead of dropping it",
           (GTest("test_robustness", "*/NonfiniteGuards.*/ReferenceFloat"), GTest("test_reference", "ReferenceRenderer.*"))),
    Mutant("kernel-guard-off", "kernels/device/guards.h",
           "return v3_select(finite, sum, radiance);",
           "return sum;",
           "the kernels add non-finite radiance to the path instead of dropping it",
           (GTest("test_robustness", "*/NonfiniteGuards.*"),)),
    # ---------------------------------------------------------------- the estimator's terms
    Mutant("balance-heuristic", ESTIMATOR,
           "return f > REAL(0.0) ? REAL(1.0) / (REAL(1.0) + ratio * ratio) : REAL(0.0);",
           "return f > REAL(0.0) ? REAL(1.0) / (REAL(1.0) + ratio) : REAL(0.0);",
           "the balance heuristic f / (f + g) instead of the power heuristic",
           (GTest("test_shared", "Estimator/*.*"), GTest("test_reference", "ReferenceMis.*"))),
    Mutant("specular-emission-weighted", ESTIMATOR,
           "return after_specular || !nee ? REAL(1.0) : shared_weight;",
           "return !nee ? REAL(1.0) : shared_weight;",
           "emission seen after a specular vertex gets the MIS weight, as if a light sample could have found it",
           (GTest("test_shared", "Estimator/*.*"), GTest("test_reference", ANALYTIC))),
    Mutant("emission-side-ignored", ESTIMATOR,
           "lane_int seen = emits(emission) && (two_sided || front) && weight > REAL(0.0);",
           "lane_int seen = emits(emission) && (two_sided || !front) && weight > REAL(0.0);",
           "a one-sided emitter is seen from its back, not its front",
           (GTest("test_shared", "Estimator/*.*"), GTest("test_reference", ANALYTIC))),
    Mutant("nee-cosine-dropped", ESTIMATOR,
           "return v3_scale(v3_div(v3_scale(v3_mul(throughput_f, emission), cos_surface), light_pdf), weight);",
           "return v3_scale(v3_div(v3_mul(throughput_f, emission), light_pdf), weight);",
           "the light sample's contribution loses the cosine at the surface",
           (GTest("test_shared", "Estimator/*.*"), GTest("test_reference", ANALYTIC))),
    Mutant("roulette-survival-10-percent-low", ESTIMATOR,
           "outcome.survives = !plays || u < survival;",
           "outcome.survives = !plays || u < REAL(0.9) * survival;",
           "Russian roulette lets 10% fewer paths survive than the probability it divides by",
           (GTest("test_shared", "Estimator/*.Roulette*"),
            GTest("test_reference", "ReferenceAnalytic/*.*Roulette*:ReferenceAnalytic/*.*GlassSphere*"))),
    Mutant("roulette-eta-scale-inverted", ESTIMATOR,
           "return wp_clamp(max_component(throughput) * eta_scale, REAL(0.05), REAL(1.0));",
           "return wp_clamp(max_component(throughput) / eta_scale, REAL(0.05), REAL(1.0));",
           "roulette's survival divides by the refractions' eta^2 instead of factoring it out (unbiased, noisier)",
           (GTest("test_shared", "Estimator/*.Roulette*"),
            GTest("test_reference", "ReferenceAnalytic/*.*GlassSphere*"))),
    Mutant("shadow-ray-end-beyond-light", ESTIMATOR,
           "offset_ray_origin(light_point, v3_select(faces_vertex, light_normal, v3_neg(light_normal)),",
           "offset_ray_origin(light_point, v3_select(faces_vertex, v3_neg(light_normal), light_normal),",
           "the shadow ray's far end is moved through the light instead of short of it",
           (GTest("test_shared", "Estimator/*.*"), GTest("test_reference", ANALYTIC))),
    # ---------------------------------------------------------------- light sampling densities
    Mutant("light-pdf-5-percent-high", LIGHTS,
           "WP_FN real light_sample_pdf(real selection_pmf, real point_pdf) { return selection_pmf * point_pdf; }",
           "WP_FN real light_sample_pdf(real selection_pmf, real point_pdf) {\n"
           "    return REAL(1.05) * selection_pmf * point_pdf;\n}",
           "a light sample's density times 1.05 (in next-event estimation and in MIS)",
           (GTest("test_shared", "Estimator/*.*:LightPdfs/*.*"), GTest("test_reference", "ReferenceMis.*:" + ANALYTIC))),
    Mutant("sphere-cone-pdf-5-percent-high", LIGHTS,
           "return REAL(1.0) / (REAL(2.0) * WP_PI * cone.one_minus_cos_theta_max);",
           "return REAL(1.05) / (REAL(2.0) * WP_PI * cone.one_minus_cos_theta_max);",
           "a sphere light's cone density times 1.05",
           (GTest("test_shared", "Sampling/*.Sphere*:LightPdfs/*.*"), GTest("test_reference", ANALYTIC))),
    Mutant("area-pdf-cosine-dropped", LIGHTS,
           "return cos_light > REAL(0.0) ? pdf_area * distance_squared / cos_light : REAL(0.0);",
           "return cos_light > REAL(0.0) ? pdf_area * distance_squared : REAL(0.0);",
           "the area-to-solid-angle density forgets the cosine at the light",
           (GTest("test_shared", "Sampling/*.*:LightPdfs/*.*"),)),
    Mutant("light-pmf-is-the-cdf", LIGHTS,
           "return index == 0u ? gather(cdf, index) : gather(cdf, index) - below;",
           "return gather(cdf, index);",
           "a light's selection probability is its cumulative probability",
           (GTest("test_shared", "Sampling/*.LightSelection*"), GTest("test_reference", "ReferenceMis.*"))),
    Mutant("sphere-area-sampling-one-hemisphere", LIGHTS,
           "real z = REAL(1.0) - REAL(2.0) * u1;",
           "real z = REAL(1.0) - u1;",
           "area sampling of a sphere light covers only one hemisphere",
           (GTest("test_shared", "Sampling/*.Sphere*:LightPdfs/*.*"),
            GTest("test_reference", "ReferenceAnalytic/*.InsideEmissiveSphere*"))),
    # ---------------------------------------------------------------- ray offsets and hit-point error bounds
    Mutant("offset-sign", "kernels/shared/offset.h",
           "return v3_add_scaled(p, REAL(2.0) * error, n);",
           "return v3_add_scaled(p, REAL(-2.0) * error, n);",
           "spawned rays start below the surface instead of above it",
           (GTest("test_shared", "Offset/*.*"), GTest("test_reference", ANALYTIC))),
    Mutant("offset-quartered", "kernels/shared/offset.h",
           "return v3_add_scaled(p, REAL(2.0) * error, n);",
           "return v3_add_scaled(p, REAL(0.5) * error, n);",
           "spawned rays move by half the error bound instead of twice it",
           (GTest("test_shared", "Offset/*.*"), GTest("test_reference", ANALYTIC))),
    Mutant("plane-bound-t-term-dropped", "kernels/shared/hit_point.h",
           "rounding_gamma(REAL(5.0)) * t * abs_dot(direction, normal) +",
           "rounding_gamma(REAL(0.0)) * t * abs_dot(direction, normal) +",
           "a plane hit's error bound loses the term of the ray's distance",
           (GTest("test_shared", "HitPoint/*.*:Offset/*.*"),)),
    Mutant("sphere-bound-radius-term-smaller", "kernels/shared/hit_point.h",
           "h.error = rounding_gamma(REAL(5.0)) * radius + rounding_gamma(REAL(1.0)) * abs_dot(h.point, h.normal);",
           "h.error = rounding_gamma(REAL(1.0)) * radius + rounding_gamma(REAL(1.0)) * abs_dot(h.point, h.normal);",
           "a sphere hit's error bound takes the radius term at gamma(1) instead of gamma(5)",
           (GTest("test_shared", "HitPoint/*.*:Offset/*.*"),)),
    # ---------------------------------------------------------------- materials
    Mutant("fresnel-term-dropped", "kernels/shared/fresnel.h",
           "real reflectance = (r_parallel * r_parallel + r_perpendicular * r_perpendicular) / REAL(2.0);",
           "real reflectance = (r_parallel * r_parallel) / REAL(2.0);",
           "the Fresnel reflectance loses its perpendicular term",
           (GTest("test_shared", "Fresnel/*.*:Materials/*.Glass*"),
            GTest("test_reference", "ReferenceAnalytic/*.*Glass*"))),
    Mutant("glass-eta-not-inverted-leaving", "kernels/shared/materials/glass.h",
           "real eta = entering ? ior : REAL(1.0) / ior;",
           "real eta = ior;",
           "a path leaving glass refracts as if entering it",
           (GTest("test_shared", "Materials/*.Glass*"), GTest("test_reference", "ReferenceAnalytic/*.*Glass*"))),
    Mutant("glass-radiance-compression-dropped", "kernels/shared/materials/glass.h",
           "refracts && transport == WP_TRANSPORT_RADIANCE ? eta * eta : REAL(1.0));",
           "refracts && transport == WP_TRANSPORT_RADIANCE ? REAL(1.0) : REAL(1.0));",
           "refraction no longer scales radiance by 1/eta^2",
           (GTest("test_shared", "Materials/*.Glass*"), GTest("test_reference", "ReferenceAnalytic/*.*Glass*"))),
    Mutant("uniform-hemisphere-weight-halved", "kernels/shared/materials/diffuse.h",
           "s.weight = uniform_hemisphere ? v3_scale(albedo, REAL(2.0) * in_frame.z) : albedo;",
           "s.weight = uniform_hemisphere ? v3_scale(albedo, in_frame.z) : albedo;",
           "uniform hemisphere sampling's weight loses its factor 2",
           (GTest("test_shared", "Materials/*.Diffuse*"),
            GTest("test_reference", "ReferenceAnalytic/*.*SamplingVariants*:ReferenceAnalytic/*.*WithoutNee*"))),
    Mutant("mirror-about-geometric-normal", "kernels/shared/materials/mirror.h",
           "s.direction = reflect_direction(v3_neg(wo), ns);",
           "s.direction = reflect_direction(v3_neg(wo), nf);",
           "the mirror reflects about the geometric normal instead of the shading normal",
           (GTest("test_shared", "Materials/*.Mirror*"),)),
    Mutant("facing-side-flipped", "kernels/shared/materials/bsdf.h",
           "f.front = v3_dot(direction, normal) < REAL(0.0);",
           "f.front = v3_dot(direction, normal) > REAL(0.0);",
           "the side a path arrives on is taken as the other one",
           (GTest("test_shared", "Materials/*.*"), GTest("test_reference", ANALYTIC))),
    Mutant("shading-normal-leak-allowed", "kernels/shared/materials/bsdf.h",
           "return !shading_normals || v3_dot(direction, normal) > REAL(0.0);",
           "return !shading_normals || v3_dot(direction, normal) > REAL(-2.0);",
           "a direction that leaves through the geometric surface is let through with shading normals",
           (GTest("test_shared", "Materials/*.*"), GTest("test_reference", MESH_ANALYTIC))),
    # ---------------------------------------------------------------- shapes
    Mutant("quad-normal-flipped", "kernels/shared/geometry.h",
           "WP_FN vec3 quad_normal(vec3 edge1, vec3 edge2) { return v3_normalize(v3_cross(edge1, edge2)); }",
           "WP_FN vec3 quad_normal(vec3 edge1, vec3 edge2) { return v3_normalize(v3_cross(edge2, edge1)); }",
           "a quad's normal is edge2 x edge1, the back",
           (GTest("test_shared", "Geometry/*.*:HitPoint/*.*"), GTest("test_reference", ANALYTIC))),
    Mutant("triangle-normal-flipped", "kernels/shared/triangle.h",
           "return v3_normalize(v3_cross(v3_sub(p1, p0), v3_sub(p2, p0)));",
           "return v3_normalize(v3_cross(v3_sub(p2, p0), v3_sub(p1, p0)));",
           "a triangle's normal is (p2 - p0) x (p1 - p0), the back",
           (GTest("test_shared", "TriangleShading/*.*:HitPoint/*.*"), GTest("test_reference", MESH_ANALYTIC))),
    Mutant("triangle-zero-edge-misses", "kernels/shared/triangle.h",
           "lane_int mixed_signs = (e.e0 < REAL(0.0) || e.e1 < REAL(0.0) || e.e2 < REAL(0.0)) &&",
           "lane_int mixed_signs = (e.e0 <= REAL(0.0) || e.e1 < REAL(0.0) || e.e2 < REAL(0.0)) &&",
           "a ray exactly through a triangle's edge p1-p2 misses it (the watertight rule broken)",
           (GTest("test_accel", "Watertight.*:Bvh.*"),)),
    # ---------------------------------------------------------------- the BVH
    Mutant("box-widening-removed", "kernels/shared/bvh.h",
           "WP_FN real box_leave_scale(void) { return REAL(1.0) + REAL(2.0) * rounding_gamma(REAL(3.0)); }",
           "WP_FN real box_leave_scale(void) { return REAL(1.0); }",
           "the box test no longer widens the leaving distance by 1 + 2 gamma(3)",
           (GTest("test_accel", "Bvh.*:Watertight.*"),)),
    Mutant("leaf-last-triangle-skipped", "kernels/shared/bvh.h",
           "uint count = (child & (WP_BVH_MAX_LEAF_SIZE - 1u)) + 1u;",
           "uint count = (child & (WP_BVH_MAX_LEAF_SIZE - 1u));",
           "the traversal skips the last triangle of every leaf",
           (GTest("test_accel", "Bvh.*:Watertight.*"),)),
    # ---------------------------------------------------------------- the kernels' own MIS bookkeeping
    Mutant("kernel-mis-light-of-shape-first", "kernels/device/path_vertex.h",
           "light = is_this ? (lane_uint)i : light;",
           "light = is_this ? (lane_uint)0u : light;",
           "the kernels weigh an emitter hit with the first light's density, whichever light it is",
           (GTest("test_wavefront", "ImageAgreement.*:MeshRender.TwoMeshLights*:ShadeDirectStage.*"),)),
    Mutant("kernel-path-ends-a-bounce-late", "kernels/device/path_vertex.h",
           "return bounce >= max_depth || v.material.type == WP_MATERIAL_EMITTER;",
           "return bounce > max_depth || v.material.type == WP_MATERIAL_EMITTER;",
           "the kernels' paths take one bounce more than max_depth",
           (GTest("test_wavefront", "ImageAgreement.*:WavefrontImage.RegionMeansAgreeWithReference"),)),
    Mutant("kernel-film-skips-a-pass-entry", "kernels/accumulate.cl",
           "for (uint item = first; item < pass_size; item += round_pixel_count) {",
           "for (uint item = first + round_pixel_count; item < pass_size; item += round_pixel_count) {",
           "the device film skips each pixel's first sample of every pass",
           (GTest("test_opencl", "DeviceFilm.*"), GTest("test_wavefront", "ImageAgreement.*"))),
]
