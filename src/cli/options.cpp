#include "cli/options.h"

#include <limits>

#include "cli/errors.h"
#include "cli/flag_checks.h"
#include "scene/limits.h"  // the loader's limits, so flags and files agree

namespace wp::cli {

namespace {

template <class Int>
void add_integer(CLI::App& app, const std::string& flag, std::optional<Int>& value, const std::string& help,
                 std::int64_t min, std::int64_t max) {
    app.add_option(flag, value, help)->check(integer_in(min, max));
}

// The limits each mesh file's import process runs under (docs/scene-format.md, "Mesh import limits").
void add_mesh_import_options(CLI::App& render, MeshImportLimits& limits) {
    render
        .add_option("--mesh-import-memory", limits.memory_mib,
                    "Memory in MiB each mesh file's import may use (its process's address space beyond its start); "
                    "raise it for very large meshes")
        ->check(integer_in(1, std::int64_t(kMaxImportMemoryMib)))
        ->capture_default_str();
    render.add_option("--mesh-import-cpu", limits.cpu_s, "CPU seconds each mesh file's import may use")
        ->check(integer_in(1, kMaxImportCpuS))
        ->capture_default_str();
    render
        .add_option("--mesh-import-time", limits.wall_s,
                    "Seconds each mesh file's import may take before it is stopped (wall clock)")
        ->check(number_in(1e-3, kMaxImportWallS))
        ->capture_default_str();
}

// The sppm flags, which need the sppm integrator (the scene's or --integrator's).
void apply_sppm_overrides(const RenderOverrides& overrides, Scene& scene) {
    const std::pair<const char*, bool> flags[] = {{"--photons", overrides.photons.has_value()},
                                                  {"--initial-radius", overrides.initial_radius.has_value()},
                                                  {"--alpha", overrides.alpha.has_value()}};
    for (const auto& [flag, given] : flags)
        if (given && scene.render.integrator != Integrator::Sppm)
            throw UsageError(std::string(flag) +
                             ": applies to the sppm integrator only (the scene's render.integrator is path; add "
                             "--integrator sppm)");
    if (overrides.photons) scene.render.sppm.photons = static_cast<std::uint32_t>(*overrides.photons);
    if (overrides.initial_radius) scene.render.sppm.radius = *overrides.initial_radius;
    if (overrides.alpha) scene.render.sppm.alpha = *overrides.alpha;
    if (const std::string problem = sppm_problem(scene); !problem.empty())
        throw UsageError("--integrator sppm: " + problem);
}

}  // namespace

void add_render_options(CLI::App& render, RenderCommand& command) {
    render
        .add_option("scene", command.scene_path,
                    "Scene file: wavepath JSON, or Mitsuba 3 XML (.xml); see docs/scene-format.md")
        ->required();
    render
        .add_option("-D,--define", command.defines,
                    "name=value: the value of $name in a Mitsuba XML scene (overrides its <default>); repeatable")
        ->allow_extra_args(false);
    render.add_option("-o,--output", command.output_path, "Output image: .exr .pfm .hdr (linear) or .png .jpg (sRGB)")
        ->required();

    RenderOverrides& o = command.overrides;
    add_integer(render, "--spp", o.spp, "Samples per pixel (overrides render.spp)", 1, kMaxSpp);
    add_integer(render, "--width", o.width, "Image width in pixels (overrides camera.width)", 1, kMaxResolution);
    add_integer(render, "--height", o.height, "Image height in pixels (overrides camera.height)", 1, kMaxResolution);
    add_integer(render, "--max-depth", o.max_depth, "Most scattering events per path (overrides render.max_depth)", 0,
                kMaxDepthLimit);
    add_integer(render, "--rr-depth", o.rr_depth, "Russian roulette from this depth on (overrides render.rr_depth)", 0,
                std::numeric_limits<int>::max());
    add_integer(render, "--seed", o.seed, "Random seed (overrides render.seed)", 0,
                std::numeric_limits<std::uint32_t>::max());
    render
        .add_option("--nee", o.nee, "Next-event estimation: on, or off for pure BSDF sampling (overrides render.nee)")
        ->check(CLI::IsMember({"on", "off"}));
    render
        .add_option("--mis", o.mis,
                    "Multiple importance sampling of light samples and BSDF-sampled emitter hits (power "
                    "heuristic): on, or off to count emission after diffuse bounces by the light sample alone "
                    "(overrides render.mis)")
        ->check(CLI::IsMember({"on", "off"}));
    render
        .add_option("--hemisphere", o.hemisphere,
                    "Diffuse sampling: cosine or uniform hemisphere (overrides render.hemisphere)")
        ->check(CLI::IsMember({"cosine", "uniform"}));
    render
        .add_option("--sampler", o.sampler,
                    "A camera sample's numbers: sobol (Owen-scrambled Sobol' points for each vertex's pixel, light "
                    "and BSDF samples: less noise per sample) or independent (overrides render.sampler)")
        ->check(CLI::IsMember({"sobol", "independent"}));

    render
        .add_option("--integrator", o.integrator,
                    "What estimates each pixel: path (path tracing) or sppm (stochastic progressive photon mapping, "
                    "whose iterations --spp counts; overrides render.integrator)")
        ->check(CLI::IsMember({"path", "sppm"}));
    add_integer(render, "--photons", o.photons,
                "sppm: photons per iteration (overrides render.photons; default one per pixel)", 1, kMaxPhotons);
    render
        .add_option("--initial-radius", o.initial_radius,
                    "sppm: every pixel's first gathering radius, in scene units (overrides render.initial_radius; "
                    "default from the scene's extent and a pixel's footprint, docs/scene-format.md)")
        ->check(CLI::Range(1e-30, 1e12));
    render
        .add_option("--alpha", o.alpha,
                    "sppm: the fraction of each iteration's photons a pixel keeps as its radius shrinks, in (0, 1] "
                    "(overrides render.alpha; default 2/3)")
        ->check(CLI::Range(1e-9, 1.0));

    add_backend_options(render, command.backend);
    add_mesh_import_options(render, command.mesh_import);

    LongRunFlags& l = command.long_run;
    render.add_option("--checkpoint", l.checkpoint,
                      "Write a checkpoint (a film file, .wpfilm) to this file every --checkpoint-every seconds "
                      "and at the end");
    render.add_option("--checkpoint-every", l.checkpoint_every_s, "Seconds between checkpoints (0: after every pass)")
        ->check(number_in(0.0, 1e9))
        ->capture_default_str();
    render.add_option("--resume", l.resume,
                      "Continue the render whose checkpoint this is (same scene and settings; "
                      "the image is bit-identical to an uninterrupted render's)");
    render.add_option("--time", l.time_s, "Time budget in seconds: stop before a pass that would end past it")
        ->check(number_in(1e-3, 1e9));
    render
        .add_option("--target-error", l.target_error,
                    "Stop once the image's estimated relative standard error is at most this (checked at 4, 5, 6, "
                    "8, 10, ... samples per pixel; docs/long-renders.md)")
        ->check(number_in(1e-9, 1.0));
    render
        .add_option("--adaptive", l.adaptive,
                    "Adaptive sampling: after max(8, spp/16) samples, a pixel stops once its estimated error "
                    "(standard error over the square root of its value) and its neighbours' is at most this, "
                    "e.g. 0.01 (docs/long-renders.md)")
        ->check(number_in(1e-9, 1e9));
    render.add_option("--samples", l.samples,
                      "A:B renders samples A to B-1 of every pixel into a partial film (-o FILE.wpfilm), "
                      "for `wavepath merge`");

    render.add_flag("-q,--quiet", command.quiet, "No progress and no summary on stderr (errors still appear)");
    render.add_option("--stats-json", command.stats_json_path, "Also write the run's figures to this JSON file");
}

void apply_overrides(const RenderOverrides& overrides, Scene& scene) {
    if (overrides.spp) scene.render.spp = *overrides.spp;
    if (overrides.max_depth) scene.render.max_depth = *overrides.max_depth;
    if (overrides.rr_depth) scene.render.rr_depth = *overrides.rr_depth;
    if (overrides.seed) scene.render.seed = static_cast<std::uint32_t>(*overrides.seed);
    if (overrides.nee) scene.render.nee = *overrides.nee == "on";
    if (overrides.mis) scene.render.mis = *overrides.mis == "on";
    if (overrides.hemisphere)
        scene.render.hemisphere = *overrides.hemisphere == "uniform" ? Hemisphere::Uniform : Hemisphere::Cosine;
    if (overrides.sampler)
        scene.render.sampler = *overrides.sampler == "independent" ? Sampler::Independent : Sampler::Sobol;
    if (overrides.width) scene.camera.width = *overrides.width;
    if (overrides.height) scene.camera.height = *overrides.height;
    if (overrides.integrator)
        scene.render.integrator = *overrides.integrator == "sppm" ? Integrator::Sppm : Integrator::Path;
    apply_sppm_overrides(overrides, scene);

    const std::int64_t pixels = std::int64_t{scene.camera.width} * scene.camera.height;
    if (pixels > kMaxPixels)
        throw UsageError("--width/--height: width * height must be <= " + std::to_string(kMaxPixels) + ", got " +
                         std::to_string(scene.camera.width) + " * " + std::to_string(scene.camera.height) + " = " +
                         std::to_string(pixels));
}

}  // namespace wp::cli
