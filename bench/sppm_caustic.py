#!/usr/bin/env python3
"""SPPM against path tracing in caustics (issue 22; docs/architecture.md, "Photon mapping").

Usage: python3 bench/sppm_caustic.py [--out bench/results] [--binary build/wavepath] [--cache DIR] [--repeats 5]

Three scenes at 64x64 on the wavefront backend, each with a caustic REGION:
- bench/scenes/caustic_patch.json, the analytic patch of
  tests/support/caustic_patch.h (a diffuse patch under a wide glass slab lit by
  a small quad light), seen at 45 degrees so that it fills the image: the
  region is the whole image;
- bench/scenes/sppm_caustic.json, a glass sphere on a diffuse floor under a
  small quad light: the region is the floor under the sphere, lit only through
  the glass;
- scenes/room.json: the region is the glass sphere's caustic on the floor;
  SPPM runs there with its defaults, with the former default of one photon
  per pixel and with a smaller first radius, which tells the photons' noise
  from the bias of the gathering radius.
SPPM's defaults (issue 39): each pixel's first radius two footprints at its
first visible point, 65,536 photons per iteration; each scene also runs at
4,096 photons per iteration (one per pixel, the former default) over about
the same photons in all, which measures the choice of the photon count.
Per scene, renders path tracing at each of its path_spp and SPPM with each of
its sppm flag sets at each of that set's iterations, interleaved, each --repeats times (seed
= repetition), and measures relMSE against Mitsuba's converged path-traced image
(bench/mitsuba_peer.py at the scene's truth_spp, cached in --cache) in the
region and over the whole image, and the image's mean over the truth's. The
truth's own noise adds its variance to every expected squared error; the
tables give each relMSE less that floor (the truth's per-value variance over
the passes it was rendered in, weighted as relMSE weighs errors), and the gain
at equal time is taken from those. Writes sppm_caustic.json and sppm_caustic.md
into --out, headed by the commit, date, machine, OpenCL platform and load, and
replaces the block between `<!-- sppm_caustic:begin -->` and
`<!-- sppm_caustic:end -->` in --out's analysis.md (bench/results') by the targets' rows.
"""
import os
import re

import numpy as np

from run import ROOT, loglog_at, rel_mse, rel_noise, scene_max_depth
from study import TIME_AND_RELMSE, cell, generated_by, interleaved, load_range, run_study, summary, table

SIZE = 64
# region: fractions of the image (columns, rows from the top).
SCENES = [
    {"name": "caustic_patch", "scene": "bench/scenes/caustic_patch.json", "truth_spp": 65536,
     "region": {"x": (0.0, 1.0), "y": (0.0, 1.0)}, "region_is": "the patch, the whole image",
     # The defaults (issue 39: each pixel's first radius from its footprint, 65,536 photons per iteration),
     # beside the former default photon count, one per pixel (4,096 at 64x64), at about the same photons in all.
     "path_spp": [64, 256, 1024, 4096], "sppm": [([], [4, 16, 64]), (["--photons", "4096"], [64, 256, 1024])]},
    {"name": "sppm_caustic", "scene": "bench/scenes/sppm_caustic.json", "truth_spp": 131072,
     "region": {"x": (0.25, 0.75), "y": (0.58, 0.82)}, "region_is": "the floor under the sphere",
     "path_spp": [16, 64, 256, 1024, 4096], "sppm": [([], [4, 16, 64]), (["--photons", "4096"], [16, 64, 256])]},
    {"name": "room", "scene": "scenes/room.json", "truth_spp": 16384,
     "region": {"x": (0.64, 0.88), "y": (0.83, 0.91)}, "region_is": "the glass sphere's caustic on the floor",
     # Beside the defaults, the former default photon count (one per pixel) and whether the region's error is
     # the gathering radius's bias (a smaller first radius, 0.03 against two footprints, 0.22 on the mean).
     "path_spp": [16, 64, 256, 1024, 4096],
     "sppm": [([], [4, 16, 64]), (["--photons", "4096"], [16, 64, 256]), (["--initial-radius", "0.03"], [4, 16, 64])]},
]
GAIN_TARGET, MEAN_TARGET = 10.0, 0.01


def region_mask(region):
    rows = np.arange(SIZE)[::-1]  # PFM rows run bottom-up; regions count from the top
    cols = np.arange(SIZE)
    in_rows = (rows >= region["y"][0] * SIZE) & (rows < region["y"][1] * SIZE)
    in_cols = (cols >= region["x"][0] * SIZE) & (cols < region["x"][1] * SIZE)
    return np.repeat(np.outer(in_rows, in_cols).reshape(-1), 3)  # every channel of a pixel


def configurations():
    for s in SCENES:
        for spp in s["path_spp"]:
            yield {"scene": s["name"], "integrator": "path", "flags": [], "spp": spp}
        for flags, iterations in s["sppm"]:
            for n in iterations:
                yield {"scene": s["name"], "integrator": "sppm", "flags": flags, "spp": n}


def truths(peer, cache):
    """Per scene: the converged image, its region mask, the relMSE floors its noise adds (region, image) and
    the relative standard error of its mean (pixels independent, a pixel's channels not)."""
    out = {}
    for s in SCENES:
        path = os.path.join(ROOT, s["scene"])
        converged = peer.converged(path, SIZE, s["truth_spp"], scene_max_depth(path), cache)
        image, mask = np.asarray(converged.image, dtype=np.float64), region_mask(s["region"])
        out[s["name"]] = {"path": path, "image": image, "mask": mask,
                          "floor_region": rel_noise(converged.variance[mask], image[mask]),
                          "floor_image": rel_noise(converged.variance, image),
                          "mean_se": float(np.sqrt(np.sum(converged.pixel_variance)) / converged.pixel_variance.size
                                           / image.mean())}
    return out


def measure(runner, peer, args):
    truth = truths(peer, args.cache)

    def measure_one(c, seed):
        t = truth[c["scene"]]
        s = runner.render(t["path"], "wavefront", SIZE, SIZE, c["spp"], ["--integrator", c["integrator"], *c["flags"]],
                          image=True, seed=seed)
        image, mask = np.asarray(s["image"], dtype=np.float64), t["mask"]
        return {"time_s": s["time_s"], "relmse_region": rel_mse(image[mask], t["image"][mask]),
                "relmse_image": rel_mse(image, t["image"]), "mean_ratio": float(image.mean() / t["image"].mean())}

    configs = list(configurations())
    runs = interleaved(configs, args.repeats, measure_one)
    rows = []
    for c, r in zip(configs, runs):
        row = summary(c, r, ["relmse_region", "relmse_image", "mean_ratio"])
        row["relmse_region_less_truth"] = row["relmse_region"] - truth[c["scene"]]["floor_region"]
        row["relmse_image_less_truth"] = row["relmse_image"] - truth[c["scene"]]["floor_image"]
        rows.append(row)
    for s in SCENES:
        path_line = sorted((r["time_s"]["median"], r["relmse_region_less_truth"]) for r in rows
                           if r["scene"] == s["name"] and r["integrator"] == "path")
        for r in rows:
            if r["scene"] == s["name"] and r["integrator"] == "sppm":
                equal_time = loglog_at(path_line, r["time_s"]["median"])
                r["gain_equal_time"] = (equal_time / r["relmse_region_less_truth"]
                                        if equal_time and r["relmse_region_less_truth"] > 0 else None)
    scenes = {s["name"]: {"scene": s["scene"], "truth_spp": s["truth_spp"], "region": s["region"],
                          **{k: v for k, v in truth[s["name"]].items() if k in ("floor_region", "floor_image",
                                                                                 "mean_se")}} for s in SCENES}
    return {"size": SIZE, "scenes": scenes, "load": load_range(runs), "rows": rows}


def flag_words(flags):
    return f"`{' '.join(flags)}`" if flags else "defaults"


def targets(result):
    """Per scene, each SPPM row against the issue's targets: the gain at equal time in the region, and the
    whole image's mean over the truth's."""
    lines = table(["scene", "SPPM flags", "iterations", "time median (s)", "gain at equal time (target >= 10x)",
                   "mean ratio (target within 1%)", "truth mean's standard error"],
                  [[r["scene"], flag_words(r["flags"]), str(r["spp"]), f"{r['time_s']['median']:.2f}",
                    "outside path tracing's times" if r["gain_equal_time"] is None else
                    f"{r['gain_equal_time']:.1f}x ({'met' if r['gain_equal_time'] >= GAIN_TARGET else 'not met'})",
                    f"{r['mean_ratio']:.4f} ({'met' if abs(r['mean_ratio'] - 1) <= MEAN_TARGET else 'not met'})",
                    f"{100 * result['scenes'][r['scene']]['mean_se']:.2f}%"]
                   for r in result["rows"] if r["integrator"] == "sppm"])
    return "\n".join(lines)


def markdown(result):
    meta, scenes = result["meta"], result["scenes"]
    described = "; ".join(
        f"`{s['scene']}` ({spec['name']}: region columns {s['region']['x'][0]:.2f}-{s['region']['x'][1]:.2f}, "
        f"rows {s['region']['y'][0]:.2f}-{s['region']['y'][1]:.2f} from the top, {spec['region_is']}; truth at "
        f"{s['truth_spp']} spp, whose noise adds {s['floor_region']:.3g} to relMSE in the region and "
        f"{s['floor_image']:.3g} over the image)"
        for spec in SCENES for s in [scenes[spec["name"]]])
    lines = ["# SPPM against path tracing in caustics", "",
             f"{generated_by('sppm_caustic.py', meta, result['load'])} {result['size']}x{result['size']}, wavefront "
             f"backend, {result['repeats']} interleaved repetitions (seed = repetition); truth: Mitsuba "
             f"({meta['mitsuba']}) path tracing at each scene's max depth. Scenes: {described}.", "",
             f"{TIME_AND_RELMSE} in the region and over the whole image; 'less truth' "
             "subtracts what the truth's own noise adds to it (its per-value variance over the passes it was "
             "rendered in, weighted alike), an estimate of the error against the exact image. Gain at equal time: "
             "path tracing's relMSE in the region less truth at the SPPM row's median time (log-log line through "
             "the path-tracing rows; blank outside them) over SPPM's (target: at least 10x). Mean ratio: the "
             "image's mean over the truth's, averaged over the repetitions (target for SPPM: within 1%).", "",
             "## Targets", "", targets(result), "", "## All rows", "",
             *table(["scene", "integrator", "flags", "spp / iterations", "time min (s)", "time median (s)",
                     "relMSE region", "relMSE region less truth", "relMSE image", "relMSE image less truth",
                     "gain at equal time", "mean ratio"],
                    [[r["scene"], r["integrator"], flag_words(r["flags"]), str(r["spp"]), f"{r['time_s']['min']:.3f}",
                      f"{r['time_s']['median']:.3f}", f"{r['relmse_region']:.4g}",
                      f"{r['relmse_region_less_truth']:.4g}", f"{r['relmse_image']:.4g}",
                      f"{r['relmse_image_less_truth']:.4g}", cell(r.get("gain_equal_time"), "{:.2f}x"),
                      f"{r['mean_ratio']:.4f}"] for r in result["rows"]])]
    return "\n".join(lines) + "\n"


def update_analysis(result, out):
    """analysis.md's generated block in --out (bench/results'), when there is one: the targets' table and
    where it comes from."""
    analysis = os.path.join(out, "analysis.md")
    if not os.path.exists(analysis):
        return
    with open(analysis) as f:
        text = f.read()
    pattern = re.compile(r"(<!-- sppm_caustic:begin -->\n).*?(<!-- sppm_caustic:end -->)", re.S)
    if not pattern.search(text):
        raise SystemExit(f"sppm_caustic: {analysis} has no <!-- sppm_caustic:begin --> block")
    meta = result["meta"]
    words = (f"From `python3 bench/sppm_caustic.py` at commit {meta['commit']}, {meta['date']} "
             f"(bench/results/sppm_caustic.md, {result['repeats']} interleaved repetitions, load average "
             f"{result['load']['min']:.1f}-{result['load']['max']:.1f}):\n\n{targets(result)}\n")
    with open(analysis, "w") as f:
        f.write(pattern.sub(lambda m: m.group(1) + words + m.group(2), text))


def main():
    result, args = run_study(__doc__, "sppm_caustic", measure, markdown)
    update_analysis(result, args.out)


if __name__ == "__main__":
    main()
