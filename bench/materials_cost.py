#!/usr/bin/env python3
"""What each element of the material-test scene costs per sample, in wavepath and in Mitsuba 3 (issue 36).

Usage: python3 bench/materials_cost.py [--binary build/wavepath] [--out bench/results] [--repeats 5]

bench/scenes/materials.json (a textured floor, a rough gold, a rough plastic and a rough glass sphere under an
environment map; bench/efficiency.py --scenes materials.json measures its efficiency) and variants of it, each with
one element made plain: a sphere's material made diffuse, the floor's texture a constant albedo, the environment
map a constant background; and every one of them at once. Each is rendered by the default command (`wavepath
render SCENE` with the size, spp and seed) and by Mitsuba llvm_ad_rgb with its independent sampler, at 256x256 and
SPP samples per pixel, the variants and renderers interleaved over the repetitions (the load average before each
render). Per variant: each renderer's time per sample (median; the render alone, as efficiency.py times it),
wavepath's rays per sample (extension and shadow, from its stats; Mitsuba's paths are the same by construction:
the converter gives it our depth and roulette), each renderer's time per ray, and what the element costs each
per sample: the scene's time per sample less the variant's. Two variants make the spheres diffuse, one with the
rough materials still defined (on no shape): wavepath compiles the kinds of the scene's materials into its kernels
and evaluates every kind compiled in at every vertex, keeping each lane's own (kernels/device/path_vertex.h,
scatter_vertex and vertex_bsdf_value), so the two differ in what kinds no vertex has cost; Mitsuba's images and
work are the same in both (the converter gives it only the materials of shapes).
Beside them, the scene as is under the default command
with --lanes 1, 4 and 8 (its default without meshes on AVX-512 is 16: opencl/lanes.cpp), interleaved with the
rest: what the vector code gains on this scene's mix of materials.
Writes materials_cost.json and materials_cost.md into --out.
"""
import copy
import json
import os
import statistics
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from run import ROOT, spread  # noqa: E402
from study import generated_by, interleaved, load_range, run_study, table  # noqa: E402

SCENE = os.path.join(ROOT, "bench", "scenes", "materials.json")
SIZE = 256
SPP = 64  # as bench/efficiency.py renders the scene, so that the times per sample compare
PLAIN = {"type": "diffuse", "albedo": [0.5, 0.5, 0.5]}
SKY = [0.8, 0.7, 0.7]  # about the environment map's mean radiance (scenes/test/envmaps/sky.exr)


def plain_material(name):
    def change(scene):
        scene["materials"][name] = dict(PLAIN)
    return change


ROUGH = ["gold_ggx", "blue_plastic_ggx", "frosted_glass_ggx"]


def plain_spheres(keep_rough_materials):
    def change(scene):
        scene["materials"]["plain_sphere"] = dict(PLAIN)
        for shape in scene["shapes"]:
            if shape["type"] == "sphere":
                shape["material"] = "plain_sphere"
        if not keep_rough_materials:
            for name in ROUGH:
                del scene["materials"][name]
    return change


def plain_floor(scene):
    scene["materials"]["floor"] = dict(PLAIN)


def constant_sky(scene):
    scene["lights"] = []
    scene["background"] = SKY


# (label, what it makes plain, the changes); the first is the scene as it is.
VARIANTS = [
    ("as is", "nothing", []),
    ("gold diffuse", "the roughconductor", [plain_material("gold_ggx")]),
    ("plastic diffuse", "the roughplastic", [plain_material("blue_plastic_ggx")]),
    ("glass diffuse", "the roughdielectric", [plain_material("frosted_glass_ggx")]),
    ("floor untextured", "the bitmap texture", [plain_floor]),
    ("constant sky", "the environment map", [constant_sky]),
    ("spheres diffuse", "the three spheres' materials", [plain_spheres(False)]),
    ("spheres diffuse, rough kinds on no shape", "the three spheres' materials, still defined",
     [plain_spheres(True)]),
    ("all plain", "all of these", [plain_spheres(False), plain_floor, constant_sky]),
]
SPHERES_DIFFUSE, ROUGH_KINDS_UNUSED = 6, 7  # the two variants whose difference is the unused kinds' cost
LANES = [1, 4, 8]


def write_variant(scene, changes, path):
    """The scene with `changes` applied, its files' paths made absolute (the variant lives elsewhere)."""
    variant = copy.deepcopy(scene)
    folder = os.path.dirname(SCENE)
    for light in variant.get("lights", []):
        light["filename"] = os.path.abspath(os.path.join(folder, light["filename"]))
    for texture in variant.get("textures", {}).values():
        texture["file"] = os.path.abspath(os.path.join(folder, texture["file"]))
    for change in changes:
        change(variant)
    with open(path, "w") as f:
        json.dump(variant, f, indent=1)
    return path


def measure(runner, peer, args):
    with open(SCENE) as f:
        scene = json.load(f)
    paths = [write_variant(scene, changes, os.path.join(runner.scratch, f"variant_{i}.json"))
             for i, (_, _, changes) in enumerate(VARIANTS)]
    configurations = ([(path, renderer, []) for path in paths for renderer in ("wavepath", "mitsuba")] +
                      [(paths[0], "wavepath", ["--lanes", str(n)]) for n in LANES])

    def measure_one(configuration, seed):
        path, renderer, flags = configuration
        if renderer == "mitsuba":
            r = peer.render(path, SIZE, SPP, seed=seed)
            return {"time_s": r["time_s"], "samples": r["samples"]}
        r = runner.render(path, None, SIZE, SIZE, SPP, extra=flags, seed=seed)
        return {"time_s": r["time_s"], "samples": r["samples"], "backend": r["backend"],
                "rays": r["extension_rays"] + r["shadow_rays"]}

    runs = interleaved(configurations, args.repeats, measure_one)
    as_is = runs[0]
    lanes = [{"lanes": n, "backend": r[0]["backend"],
              "us_per_sample": spread([1e6 * x["time_s"] / x["samples"] for x in r]),
              "over_default_time": spread([x["time_s"] / d["time_s"] for x, d in zip(r, as_is)])}
             for n, r in zip(LANES, runs[2 * len(VARIANTS):])]
    rows = []
    for i, (label, plain, _) in enumerate(VARIANTS):
        ours, theirs = runs[2 * i], runs[2 * i + 1]
        rays_per_sample = statistics.median(r["rays"] / r["samples"] for r in ours)
        rows.append({"variant": label, "plain": plain, "backend": ours[0]["backend"],
                     "wavepath_us_per_sample": spread([1e6 * r["time_s"] / r["samples"] for r in ours]),
                     "mitsuba_us_per_sample": spread([1e6 * r["time_s"] / r["samples"] for r in theirs]),
                     "rays_per_sample": rays_per_sample,
                     "wavepath_over_mitsuba_time": spread([a["time_s"] / b["time_s"] for a, b in zip(ours, theirs)])})
    without, unused = runs[2 * SPHERES_DIFFUSE], runs[2 * ROUGH_KINDS_UNUSED]
    unused_kinds = {renderer: spread([b["time_s"] / a["time_s"] for a, b in zip(runs[2 * SPHERES_DIFFUSE + k],
                                                                                runs[2 * ROUGH_KINDS_UNUSED + k])])
                    for k, renderer in enumerate(["wavepath", "mitsuba"])}
    unused_kinds["wavepath_us_per_sample"] = (statistics.median(1e6 * r["time_s"] / r["samples"] for r in unused) -
                                              statistics.median(1e6 * r["time_s"] / r["samples"] for r in without))
    return {"size": SIZE, "spp": SPP, "rows": rows, "lanes": lanes, "unused_kinds": unused_kinds, "load": load_range(runs), "runs": runs}


def markdown(result):
    rows, first = result["rows"], result["rows"][0]
    lines = ["# What each element of the material-test scene costs per sample (issue 36)", "",
             generated_by("materials_cost.py", result["meta"], result["load"]) +
             f" {result['repeats']} interleaved repetitions, {result['size']}x{result['size']}, {result['spp']} spp; "
             "do not edit by hand.", "",
             "Time per sample: median over the repetitions of the render's time over its samples (us; the default "
             "command's, which ran the backend named, and Mitsuba llvm_ad_rgb's with its independent sampler). "
             "Rays: wavepath's extension and shadow rays per sample (Mitsuba's paths are the same). Cost: the "
             "scene's time per sample less the variant's, what the element made plain costs. wavepath / Mitsuba: "
             "the time per sample's ratio, per repetition min / median / max.", ""]
    body = []
    for r in rows:
        w, m = r["wavepath_us_per_sample"]["median"], r["mitsuba_us_per_sample"]["median"]
        ratio = r["wavepath_over_mitsuba_time"]
        cost = ("" if r is first else
                f"{first['wavepath_us_per_sample']['median'] - w:.3f} / {first['mitsuba_us_per_sample']['median'] - m:.3f}")
        body.append([r["variant"], r["plain"], r["backend"], f"{w:.3f}", f"{m:.3f}",
                     f"{ratio['min']:.2f} / {ratio['median']:.2f} / {ratio['max']:.2f}", f"{r['rays_per_sample']:.2f}",
                     f"{1e3 * w / r['rays_per_sample']:.0f} / {1e3 * m / r['rays_per_sample']:.0f}", cost])
    lines += table(["variant", "made plain", "wavepath ran", "wavepath us/sample", "Mitsuba us/sample",
                    "wavepath / Mitsuba time", "rays/sample", "ns per ray (wavepath / Mitsuba)",
                    "cost us/sample (wavepath / Mitsuba)"], body)
    u = result["unused_kinds"]
    lines += ["", f"The rough kinds compiled in but on no shape (\"{VARIANTS[ROUGH_KINDS_UNUSED][0]}\" against "
              f"\"{VARIANTS[SPHERES_DIFFUSE][0]}\", the same image): wavepath's time "
              f"{u['wavepath']['median']:.2f}x (per repetition {u['wavepath']['min']:.2f}-{u['wavepath']['max']:.2f}), "
              f"{u['wavepath_us_per_sample']:.3f} us per sample more; Mitsuba's {u['mitsuba']['median']:.2f}x "
              f"({u['mitsuba']['min']:.2f}-{u['mitsuba']['max']:.2f})."]
    lines += ["", "The scene as is under the default command with --lanes N, against the default command's lanes (the "
              "first row above): time per sample (median), and its time over the default's, per repetition min / "
              "median / max.", ""]
    lines += table(["--lanes", "ran", "wavepath us/sample", "time over the default's"],
                   [[str(r["lanes"]), r["backend"], f"{r['us_per_sample']['median']:.3f}",
                     f"{r['over_default_time']['min']:.2f} / {r['over_default_time']['median']:.2f} / "
                     f"{r['over_default_time']['max']:.2f}"] for r in result["lanes"]])
    return "\n".join(lines) + "\n"


if __name__ == "__main__":
    run_study(__doc__, "materials_cost", measure, markdown)
