#!/usr/bin/env python3
"""Public scenes for development (issue 37): which of them wavepath renders, whether its images agree with
Mitsuba 3's, and the default command's efficiency against Mitsuba's on each.

The scenes are others' assets, so they are never committed and CI does not run this. Fetch them yourself:

    git clone https://github.com/takkasila/practical_path_guiding_lab    # --ppg: its scenes/
    git clone https://github.com/mitsuba-renderer/mitsuba-data             # --mitsuba-data: scenes/, docs/scenes/

Usage: python3 bench/public_scenes.py --ppg DIR --mitsuba-data DIR [--binary build/wavepath] [--out bench/results]
                                      [--width 128] [--spp 32] [--repeats 8] [--converged-spp 2048]

For each scene of SCENES found under the two folders:
1. Load: `wavepath render` at 1 spp; a scene it cannot render is listed with its one error line (what it lacks).
2. Both renderers render the scene as its file has it, but for the image: about WIDTH wide at the film's aspect
   (film_size), and the path integrator where the file names another (the path-guiding lab's scenes name their
   own; -D integrator=path). wavepath takes --width/--height; Mitsuba renders with a sensor of that size built
   from the file's (its world transform, x field of view and pixel filter).
3. Agreement: the REPEATS renders of each (seeds 0..REPEATS-1, SPP each) give each pixel's mean and variance;
   8x8 block means (and the whole image) are compared per channel by z = difference / combined standard error, as
   tests/oracle/mitsuba_oracle.py does, against the Bonferroni threshold of the whole run at a false-failure rate
   of 1e-3. With a tent or gaussian filter (most of these files name one) Mitsuba splats each sample into
   neighbouring pixels, which then correlate, so the sum of pixel variances understates a block's: each renderer's
   sum is scaled by its design effect, the ratio pooled over all blocks of the spread of block means over the
   renders to that sum (block_variances).
4. Efficiency: 1 / mean(relMSE x time) over the repetitions, relMSE against Mitsuba's converged image
   (CONVERGED_SPP, in passes) less that image's own noise; time is each renderer's render alone (loading and
   kernel builds left out: each configuration renders once before it is timed). wavepath runs its default command
   (`wavepath render SCENE`), Mitsuba llvm_ad_rgb its independent sampler; the repetitions interleave the two, and
   the ratio is given per repetition (min and median) beside the ratio of the means.
Writes public_scenes.json and public_scenes.md into --out.
"""
import argparse
import json
import math
import os
import statistics
import subprocess
import sys
import tempfile
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
sys.path.insert(0, os.path.join(HERE, "..", "tests", "oracle"))
sys.path.insert(0, os.path.join(HERE, "..", "scripts"))
import mitsuba_oracle  # noqa: E402
import mitsuba_scene  # noqa: E402
from run import ROOT, Runner, rel_mse, rel_noise, run_meta, spread  # noqa: E402
from study import generated_by, table  # noqa: E402

# (name, folder flag, path under it, -D defines both renderers take). The path-guiding lab's four scenes the issue
# names, its teapot, Mitsuba's material preview and the per-plugin scenes of its docs for the plugins wavepath has.
SCENES = [
    ("cornell-box", "ppg", "scenes/cornell-box/scene.xml", {"integrator": "path"}),
    ("veach-mis", "ppg", "scenes/veach-mis/scene.xml", {"integrator": "path"}),
    ("veach-bidir", "ppg", "scenes/veach-bidir/scene.xml", {"integrator": "path"}),
    ("veach-ajar", "ppg", "scenes/veach-ajar/scene.xml", {"integrator": "path"}),
    ("torus", "ppg", "scenes/torus/scene.xml", {"integrator": "path"}),
    ("teapot", "ppg", "scenes/teapot/scene_v3.xml", {"integrator": "path"}),
    ("matpreview", "mitsuba_data", "scenes/matpreview/matpreview.xml", {}),
    *((name, "mitsuba_data", f"docs/scenes/{name}.xml", {}) for name in [
        "bsdf_diffuse_plain", "bsdf_diffuse_textured", "bsdf_conductor_aluminium", "bsdf_conductor_gold",
        "bsdf_roughconductor_copper", "bsdf_roughconductor_anisotropic_aluminium", "bsdf_dielectric_glass",
        "bsdf_dielectric_diamond", "bsdf_roughdielectric_glass", "bsdf_roughdielectric_rough",
        "bsdf_thindielectric_glass", "bsdf_plastic_default", "bsdf_plastic_shiny", "bsdf_roughplastic_ggx",
        "bsdf_roughplastic_beckmann", "bsdf_twosided_cbox", "bsdf_twosided_cbox_onesided", "bsdf_mask_before",
        "bsdf_mask_after", "bsdf_bumpmap_with", "bsdf_normalmap_with", "bsdf_roughconductor_textured_carbon",
        "texture_checkerboard", "emitter_constant", "emitter_directional", "emitter_envmap"]),
]
BLOCK = 8
ALPHA = 1e-3


def add_one_scene_arguments(parser):
    """The arguments of a script that looks at one scene of SCENES: the clones and the scene's name."""
    parser.add_argument("--ppg", help="a clone of takkasila/practical_path_guiding_lab")
    parser.add_argument("--mitsuba-data", help="a clone of mitsuba-renderer/mitsuba-data")
    parser.add_argument("--scene", required=True, help="a name of public_scenes.py's table")


def one_scene(args, tool):
    """(name, path, defines) of the scene add_one_scene_arguments' arguments name, or the tool's exit."""
    roots = {"ppg": args.ppg, "mitsuba_data": args.mitsuba_data}
    entry = next((e for e in SCENES if e[0] == args.scene), None)
    if entry is None:
        sys.exit(f"{tool}: no scene {args.scene!r} in public_scenes.py's table")
    name, source, relative, defines = entry
    if not roots.get(source):
        sys.exit(f"{tool}: {name} needs --{'ppg' if source == 'ppg' else 'mitsuba-data'}")
    return name, os.path.join(roots[source], relative), defines


def scene_options(defines):
    return [word for key, value in defines.items() for word in ("-D", f"{key}={value}")]


def load_error(binary, path, defines, scratch):
    """wavepath's error line for the scene, or None where it renders."""
    run = subprocess.run([binary, "render", path, "-q", "--spp", "1", "--width", "16", "--height", "16", "-o",
                          os.path.join(scratch, "load.pfm"), *scene_options(defines)], capture_output=True, text=True)
    if run.returncode == 0:
        return None
    return (run.stderr.strip().splitlines() or [f"exit status {run.returncode}"])[0]


def film_size(width, original):
    """About WIDTH wide at the original film's aspect: the smallest multiple of the reduced aspect that is at least
    WIDTH wide where that is at most twice WIDTH (the aspect exact), else WIDTH by the nearest height (683 x 512
    becomes 128 x 96: an aspect 0.06% off the file's, the same in both renderers)."""
    w, h = original
    g = math.gcd(w, h)
    a, b = w // g, h // g
    k = max(1, -(-width // a))
    if a * k <= min(w, 2 * width):
        return a * k, b * k
    return min(w, width), max(1, round(min(w, width) * h / w))


class MitsubaXml:
    """Mitsuba's renders of an XML file with a sensor of another size: the file's camera and pixel filter."""

    def __init__(self, mi, path, defines, width):
        self.mi = mi
        self.scene = mi.load_file(path, **defines)
        original = self.scene.sensors()[0]
        size = original.film().size()
        self.size = film_size(width, (int(size[0]), int(size[1])))
        params = mi.traverse(original)
        self.sensor_dict = {"type": "perspective", "fov_axis": "x", "fov": float(params["x_fov"][0]),
                            "near_clip": float(params["near_clip"]), "far_clip": float(params["far_clip"]),
                            "to_world": mi.ScalarTransform4f(np.array(original.world_transform().matrix).reshape(4, 4)),
                            "film": {"type": "hdrfilm", "width": self.size[0], "height": self.size[1],
                                     "pixel_format": "rgb", "rfilter": original.film().rfilter()}}
        self.sensors = {}

    def sensor(self, spp):
        if spp not in self.sensors:
            self.sensors[spp] = self.mi.load_dict(
                {**self.sensor_dict, "sampler": {"type": "independent", "sample_count": spp}})
        return self.sensors[spp]

    def render(self, spp, seed):
        """time_s and the image as flat linear RGB in the bottom-up row order of wavepath's PFM files. The first
        render at each spp is run twice: Dr.Jit compiles its kernels then, which is not the renderer's speed."""
        fresh = spp not in self.sensors
        sensor = self.sensor(spp)
        if fresh:
            np.array(self.mi.render(self.scene, sensor=sensor, seed=seed + 1_000_003))
        start = time.perf_counter()
        image = np.array(self.mi.render(self.scene, sensor=sensor, seed=seed), dtype=np.float64)
        return {"time_s": time.perf_counter() - start, "image": image[::-1].reshape(-1)}

    def converged(self, spp, passes):
        images = np.stack([self.render(spp // passes, 20_000 + k)["image"] for k in range(passes)])
        return images.mean(axis=0), images.var(axis=0, ddof=1) / passes


class MitsubaVersion:
    """What run_meta asks of a peer."""

    def __init__(self, mi):
        self.version = mi.__version__

    def describe(self):
        return f"Mitsuba {self.version} llvm_ad_rgb"


def block_variances(images):
    """Per block (whole image last) and channel: the mean over the renders and the variance of that mean. The
    sum of the pixels' variances (mitsuba_oracle.block_statistics) is scaled by the design effect: the ratio, over
    all blocks, of the spread of whole blocks' means over the renders to that sum. A tent or gaussian filter that
    splats (Mitsuba's) correlates neighbouring pixels, which the sum alone leaves out; pooled over every block
    the ratio is well estimated where each block's own spread over a few renders is not."""
    means, variances = mitsuba_oracle.block_statistics(images, BLOCK)
    per_render = np.stack([mitsuba_oracle.block_means(image, BLOCK)[0] for image in images])
    spread = per_render.var(axis=0, ddof=1) / len(images)
    effect = max(1.0, float(spread[:-1].sum() / variances[:-1].sum()))
    return means, variances * effect, effect


def block_z(ours, theirs):
    """|z| per block (whole image last) and channel, and both renderers' block means (block_variances)."""
    mean_ours, variance_ours, _ = block_variances(ours)
    mean_theirs, variance_theirs, _ = block_variances(theirs)
    se = np.sqrt(variance_ours + variance_theirs)
    difference = mean_ours - mean_theirs
    z = np.where(se > 0, np.abs(difference) / np.where(se > 0, se, 1), np.where(difference == 0, 0.0, np.inf))
    return z, mean_ours, mean_theirs


def as_images(flat, size):
    return np.stack([np.asarray(f, dtype=np.float64).reshape(size[1], size[0], 3) for f in flat])


def measure(args, mi, runner, name, path, defines, scratch):
    peer = MitsubaXml(mi, path, defines, args.width)
    width, height = peer.size
    truth, truth_variance = peer.converged(args.converged_spp, max(2, args.converged_spp // 256))
    noise = rel_noise(truth_variance, truth)
    runs = {"wavepath": [], "mitsuba": []}
    for seed in range(args.repeats):
        r = runner.render(path, None, width, height, args.spp, extra=scene_options(defines), image=True, seed=seed)
        runs["wavepath"].append({"time_s": r["time_s"], "image": np.asarray(r["image"], dtype=np.float64),
                                 "backend": r["backend"], "load": os.getloadavg()[0]})
        m = peer.render(args.spp, seed)
        runs["mitsuba"].append({**m, "load": os.getloadavg()[0]})
    for who in runs:
        for r in runs[who]:
            r["relmse"] = rel_mse(r["image"], truth) - noise
    ours = as_images([r["image"] for r in runs["wavepath"]], peer.size)
    theirs = as_images([r["image"] for r in runs["mitsuba"]], peer.size)
    z, mean_ours, mean_theirs = block_z(ours, theirs)
    products = {who: [r["relmse"] * r["time_s"] for r in runs[who]] for who in runs}
    per_repetition = [m / w for w, m in zip(products["wavepath"], products["mitsuba"])]
    return {"scene": name, "file": path, "defines": defines, "size": [width, height], "spp": args.spp,
            "backend": sorted({r["backend"] for r in runs["wavepath"]}),
            "ratio_whole": (mean_ours[-1] / mean_theirs[-1]).tolist(), "z_whole": z[-1].tolist(),
            "z_max": float(z.max()), "tests": int(z.size),
            "z_worst_block": int(np.argmax(z[:-1].max(axis=1))),
            "relmse": {who: statistics.mean(r["relmse"] for r in runs[who]) for who in runs},
            "time_s": {who: spread([r["time_s"] for r in runs[who]]) for who in runs},
            "efficiency_ratio": statistics.mean(products["mitsuba"]) / statistics.mean(products["wavepath"]),
            "efficiency_ratio_per_repetition": spread(per_repetition),
            "truth_noise_relmse": noise, "load": spread([r["load"] for who in runs for r in runs[who]])}


def markdown(results):
    meta = results["meta"]
    rendered = [r for r in results["scenes"] if "z_max" in r]
    z_crit = results["z_crit"]
    lines = ["# Public scenes against Mitsuba 3", "",
             generated_by("public_scenes.py " + " ".join(results["argv"]), meta,
                          {"min": min((r["load"]["min"] for r in rendered), default=0),
                           "max": max((r["load"]["max"] for r in rendered), default=0)}) +
             f" {meta['mitsuba']}.", "",
             f"{len(rendered)} of {len(results['scenes'])} scenes found render. Agreement: whole-image ratio "
             f"wavepath/Mitsuba (RGB) and the largest |z| over {BLOCK}x{BLOCK} blocks and channels, against "
             f"{z_crit:.2f} (Bonferroni over the run's {results['tests']} tests, false-failure rate {ALPHA:g}); "
             f"{results['repeats']} renders of {results['spp']} spp each. Efficiency: 1 / mean(relMSE x time) of "
             f"the default command over Mitsuba's (independent sampler), the ratio of the means and per "
             f"repetition (min / median); relMSE against Mitsuba's {results['converged_spp']}-spp image.", ""]
    rows = []
    for r in rendered:
        agree = "yes" if r["z_max"] <= z_crit else "**no**"
        rows.append([r["scene"], f"{r['size'][0]}x{r['size'][1]}", ", ".join(r["backend"]),
                     " / ".join(f"{v:.4f}" for v in r["ratio_whole"]), f"{r['z_max']:.2f}", agree,
                     f"{r['efficiency_ratio']:.2f}",
                     f"{r['efficiency_ratio_per_repetition']['min']:.2f} / "
                     f"{r['efficiency_ratio_per_repetition']['median']:.2f}",
                     f"{r['time_s']['wavepath']['median']:.2f} / {r['time_s']['mitsuba']['median']:.2f}"])
    lines += table(["scene", "size", "default backend", "ratio", "max abs z", "agrees", "efficiency vs Mitsuba",
                    "per repetition", "time s (ours / theirs, median)"], rows)
    missing = [r for r in results["scenes"] if "error" in r]
    if missing:
        lines += ["", "Scenes wavepath does not render yet, with its error line:", ""]
        lines += [f"- {r['scene']}: `{r['error']}`" for r in missing]
    absent = results["absent"]
    if absent:
        lines += ["", f"Not found (folder not given or file absent): {', '.join(absent)}."]
    return "\n".join(lines) + "\n"


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--ppg", help="a clone of takkasila/practical_path_guiding_lab")
    parser.add_argument("--mitsuba-data", help="a clone of mitsuba-renderer/mitsuba-data")
    parser.add_argument("--binary", default=os.path.join(ROOT, "build", "wavepath"))
    parser.add_argument("--out", default=os.path.join(ROOT, "bench", "results"))
    parser.add_argument("--width", type=int, default=128)
    parser.add_argument("--spp", type=int, default=32)
    parser.add_argument("--repeats", type=int, default=8)
    parser.add_argument("--converged-spp", type=int, default=2048)
    parser.add_argument("--only", help="comma-separated scene names")
    args = parser.parse_args()
    folders = {"ppg": args.ppg, "mitsuba_data": args.mitsuba_data}
    wanted = set(args.only.split(",")) if args.only else None
    mi = mitsuba_scene.open_mitsuba("llvm_ad_rgb")
    results = {"argv": sys.argv[1:], "spp": args.spp, "repeats": args.repeats, "converged_spp": args.converged_spp,
               "scenes": [], "absent": []}
    with tempfile.TemporaryDirectory(prefix="wavepath-public-scenes-") as scratch:
        runner = Runner(args.binary, scratch)
        results["meta"] = run_meta(args.binary, MitsubaVersion(mi))
        for name, folder, relative, defines in SCENES:
            if wanted and name not in wanted:
                continue
            path = os.path.join(folders[folder], relative) if folders[folder] else None
            if not path or not os.path.exists(path):
                results["absent"].append(name)
                continue
            error = load_error(args.binary, path, defines, scratch)
            if error:
                results["scenes"].append({"scene": name, "file": path, "error": error})
                print(f"{name}: {error}", flush=True)
                continue
            r = measure(args, mi, runner, name, path, defines, scratch)
            results["scenes"].append(r)
            print(f"{name}: {r['size'][0]}x{r['size'][1]} ratio {r['ratio_whole']} max |z| {r['z_max']:.2f}, "
                  f"efficiency {r['efficiency_ratio']:.2f}x Mitsuba", flush=True)
    results["tests"] = sum(r.get("tests", 0) for r in results["scenes"])
    results["z_crit"] = mitsuba_oracle.critical_z_for_tests(max(1, results["tests"]), ALPHA)
    os.makedirs(args.out, exist_ok=True)
    with open(os.path.join(args.out, "public_scenes.json"), "w") as f:
        json.dump(results, f, indent=1)
    with open(os.path.join(args.out, "public_scenes.md"), "w") as f:
        f.write(markdown(results))
    failed = [r["scene"] for r in results["scenes"] if r.get("z_max", 0) > results["z_crit"]]
    print(f"wrote {args.out}/public_scenes.md; disagreeing: {', '.join(failed) or 'none'}")


if __name__ == "__main__":
    main()
