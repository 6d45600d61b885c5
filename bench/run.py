#!/usr/bin/env python3
"""wavepath benchmark: throughput, scaling and speed versus accuracy, beside Mitsuba 3.

Usage: python3 bench/run.py [--quick] [--check] [--out bench/out] [--binary build/wavepath]
                            [--mesh-bench build/bench/mesh_bench] [--series throughput,scaling,accuracy,meshes,estimators,embree,lanes]

Runs the wavepath executable (build it first: bash scripts/setup.sh, which also
installs Mitsuba 3) and writes into --out: results.json, one CSV per study, PNG
plots (when matplotlib is installed; pip install -r bench/requirements.txt) and
summary.md, each headed by the commit, date, machine, OpenCL platform and build.
Mitsuba (llvm_ad_rgb, bench/mitsuba_peer.py) is a row of the throughput and
accuracy studies, and renders the converged images that relMSE and bias are
measured against (cached in --out/converged-cache under a key of the scene's
content, the settings and the renderer's version). --quick shrinks every study
to a few minutes (CI runs it, with --check: exit 1 when relMSE does not fall
as about 1/spp, an image's mean strays from the truth's, a ratio is not
finite, or mesh_bench's tracers of our own tests find different hits). The
meshes series runs bench/mesh_bench (cmake --build build --target
mesh_bench) and writes meshes.json, meshes.csv and meshes.md besides; the
estimators series (not run by default) compares MIS, NEE and roulette settings
per scene at equal spp and writes estimators.csv and estimators.md; the lanes
series (not run by default) measures samples/s per --lanes count for both
OpenCL backends and writes lanes.json and lanes.md (--lanes-short: at 128x128
and a sixth of the spp; --lanes-megakernel and --lanes-wavefront: 8 against 16
lanes at 256x256 for that backend's default, into lanes_<backend>.*).
"""
import argparse
import array
import csv
import json
import math
import os
import platform
import statistics
import struct
import subprocess
import sys
import tempfile
import time

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from mitsuba_peer import MitsubaPeer  # noqa: E402


class Runner:
    def __init__(self, binary, scratch):
        self.binary = binary
        self.scratch = scratch
        self.warm = set()

    def render(self, scene, backend, width, height, spp, extra=(), profile=False, image=False, seed=None,
               warm_spp=None):
        """One render with `backend` (None: no --backend flag, wavepath's default); returns the stats JSON
        (plus 'profile' and 'image' when asked).

        The first render of each OpenCL configuration is run twice and the
        first discarded: PoCL compiles each kernel for its launch geometry
        when it is first enqueued, which is not the renderer's speed (`seed`
        does not change the geometry, so it is not part of the configuration).
        `warm_spp`: fewer spp for that first render, where they launch the same geometry."""
        key = (scene, backend, width, height, spp, tuple(extra), profile)
        if backend != "reference" and key not in self.warm:
            self.warm.add(key)
            self.render(scene, backend, width, height, warm_spp or spp, extra, profile, seed=seed)
        out = os.path.join(self.scratch, "image.pfm")
        stats_path = os.path.join(self.scratch, "stats.json")
        profile_path = os.path.join(self.scratch, "profile.json")
        args = [self.binary, "render", scene, "-o", out, "-q", "--width", str(width), "--height", str(height),
                "--spp", str(spp), "--stats-json", stats_path, *extra]
        if backend is not None:  # None: the default command, the backend left to wavepath's choice
            args += ["--backend", backend]
        if seed is not None:
            args += ["--seed", str(seed)]
        if backend == "reference":
            args += ["--threads", str(os.cpu_count())]
        if profile:
            args += ["--profile-json", profile_path]
        subprocess.run(args, check=True, cwd=ROOT)
        with open(stats_path) as f:
            stats = json.load(f)
        if profile:
            with open(profile_path) as f:
                stats["profile"] = json.load(f)
        if image:
            stats["image"] = read_pfm(out)
        return stats


def read_pfm(path):
    """Linear RGB floats of a colour PFM, as written by wavepath."""
    with open(path, "rb") as f:
        assert f.readline().strip() == b"PF"
        width, height = map(int, f.readline().split())
        scale = float(f.readline())
        data = array.array("f")
        data.frombytes(f.read(width * height * 12))
        if (scale < 0) != (sys.byteorder == "little"):
            data.byteswap()
        return data


def rel_mse(image, reference):
    """Mean over pixels and channels of (x - r)^2 / (r^2 + 1e-2)."""
    x, r = np.asarray(image, dtype=np.float64), np.asarray(reference, dtype=np.float64)
    return float(np.mean((x - r) ** 2 / (r * r + 1e-2)))


def rel_noise(variance, reference):
    """The relMSE that noise of this per-value variance adds against `reference` (same weights as rel_mse)."""
    r = np.asarray(reference, dtype=np.float64)
    return float(np.mean(np.asarray(variance) / (r * r + 1e-2)))


def machine(binary):
    cpu = platform.processor()
    try:
        with open("/proc/cpuinfo") as f:
            cpu = next(line.split(":", 1)[1].strip() for line in f if line.startswith("model name"))
    except (OSError, StopIteration):
        pass
    # The OpenCL platform and device the wavefront runs on, as the binary itself lists them.
    devices = subprocess.run([binary, "devices"], capture_output=True, text=True).stdout.splitlines()
    device = next((line.split("] ", 1)[1].strip() for line in devices if line.startswith("[0]")), "")
    platform_line = next((line.split(":", 1)[1].strip() for line in devices if "platform:" in line), "")
    widths = next((line.split(":", 1)[1].strip() for line in devices if "float vector width:" in line), "")
    return {"cpu": cpu, "cores": os.cpu_count(), "opencl_platform": platform_line, "opencl_device": device,
            "opencl_float_vector_width": widths, "python": platform.python_version()}


def run_meta(binary, peer):
    """What the figures were measured with: commit, date, machine, OpenCL platform, build, Mitsuba."""
    def output(args):
        try:
            return subprocess.run(args, capture_output=True, text=True, cwd=ROOT).stdout.strip()
        except OSError:
            return ""
    build_type = ""
    cache = os.path.join(os.path.dirname(binary), "CMakeCache.txt")
    if os.path.exists(cache):
        with open(cache) as f:
            build_type = next((line.split("=", 1)[1].strip() for line in f if line.startswith("CMAKE_BUILD_TYPE:")), "")
    return {"commit": output(["git", "describe", "--always", "--dirty", "--abbrev=12"]),
            "date": time.strftime("%Y-%m-%d %H:%M:%S UTC", time.gmtime()),
            "wavepath": output([binary, "version"]), "build_type": build_type, "binary": binary,
            "mitsuba": peer.describe(), **machine(binary)}


def spread(values):
    return {"min": min(values), "median": statistics.median(values), "max": max(values)}


def throughput(runner, peer, cfg):
    """Samples/s per scene and backend, interleaved, min and median over runs; per scene one profiled
    wavefront run, with its tracing stages' rays/s as fractions of the intersect bound (the roofline)."""
    rows = []
    for scene in cfg["scenes"]:
        path = os.path.join(ROOT, "scenes", scene)
        # (label, backend, flags); the wavefront also with one path per work item, to show what its lanes give
        # the megakernel too: its default lanes are the single-kernel design at its best on a CPU (like for like), 1 the
        # scalar one
        configurations = [("wavefront", "wavefront", []), ("wavefront-1-lane", "wavefront", ["--lanes", "1"]),
                          ("megakernel", "megakernel", []), ("megakernel-1-lane", "megakernel", ["--lanes", "1"]),
                          ("reference", "reference", []), ("mitsuba", None, [])]
        runs = {label: [] for label, _, _ in configurations}
        for _ in range(cfg["repeats"]):  # interleaved: each repetition runs every configuration once
            for label, backend, flags in configurations:
                if backend is None:
                    runs[label].append(peer.render(path, cfg["size"], cfg["spp"]))
                else:
                    runs[label].append(runner.render(path, backend, cfg["size"], cfg["size"], cfg["spp"], extra=flags))
        profile = runner.render(path, "wavefront", cfg["size"], cfg["size"], cfg["spp"], profile=True)["profile"]
        for backend, stats in runs.items():
            sps = [s["samples_per_s"] for s in stats]
            row = {"scene": scene, "backend": backend, "size": cfg["size"], "spp": cfg["spp"], "runs": len(sps),
                   "msamples_s_min": min(sps) / 1e6, "msamples_s_median": statistics.median(sps) / 1e6,
                   "msamples_s_max": max(sps) / 1e6}
            if "extension_rays" in stats[0]:
                rays = [(s["extension_rays"] + s["shadow_rays"]) / s["time_s"] for s in stats]
                row["mrays_s_median"] = statistics.median(rays) / 1e6
            rows.append(row)
        # The wavefront against each other configuration, repetition by repetition (same machine state).
        for other in ("megakernel", "megakernel-1-lane", "reference", "mitsuba"):
            ratios = [w["samples_per_s"] / o["samples_per_s"] for w, o in zip(runs["wavefront"], runs[other])]
            rows.append({"scene": scene, "backend": f"wavefront/{other}", "runs": len(ratios),
                         **{f"ratio_{k}": v for k, v in spread(ratios).items()}})
        of_bound = profile["of_intersect_bound"]
        # the stage that traces the extension rays: intersect, or intersect_and_shade (which shades too)
        closest_hit_stage = "intersect" if "intersect" in of_bound else "intersect_and_shade"
        rows.append({"scene": scene, "backend": "wavefront-profile", "profile": profile,
                     "intersect_bound_mrays_s": profile["intersect_bound_rays_per_s"] / 1e6,
                     "closest_hit_stage": closest_hit_stage,
                     "intersect_of_bound": of_bound[closest_hit_stage],
                     # absent where shade traces the shadow rays (no intersect_shadow stage)
                     "intersect_shadow_of_bound": of_bound.get("intersect_shadow")})
    return rows


def scaling(runner, cfg):
    """Wavefront size and resolution sweeps on the room."""
    path = os.path.join(ROOT, "scenes", "room.json")
    rows = []
    for log2 in cfg["wavefront_log2"]:
        # At least twice the wavefront's worth of samples, so that it runs full.
        spp = max(cfg["spp"], -(-2 * 2 ** log2 // cfg["size"] ** 2))
        s = runner.render(path, "wavefront", cfg["size"], cfg["size"], spp, extra=["--wavefront", str(2 ** log2)],
                          profile=True)
        rows.append({"study": "wavefront_size", "paths": 2 ** log2, "spp": spp, "msamples_s": s["samples_per_s"] / 1e6,
                     "kernel_s": s["profile"]["kernel_s"], "gaps_s": s["profile"]["gaps_s"], "time_s": s["time_s"]})
    for size in cfg["resolutions"]:
        for backend in ("wavefront", "megakernel", "reference"):
            s = runner.render(path, backend, size, size, 1)
            rows.append({"study": "resolution", "backend": backend, "size": size,
                         "msamples_s": s["samples_per_s"] / 1e6, "time_s": s["time_s"]})
    return rows


def scene_render_settings(path):
    with open(path) as f:
        return json.load(f).get("render", {})


def scene_max_depth(path):
    return scene_render_settings(path).get("max_depth", 8)


def accuracy(runner, peer, cfg, out):
    """relMSE against converged images from Mitsuba, versus time: per scene the spp series of every renderer;
    on the room also the wavefront's max_depth, rr_depth, nee and hemisphere series.

    The truth of a series has the series' max_depth (the scene's), so that its bias^2 is the estimator's;
    the max_depth series is measured against a truth at depth 64, so that truncation shows as bias."""
    size = cfg["accuracy_size"]
    cache = os.path.join(out, "converged-cache")
    rows, truths = [], []

    def truth(path, spp, depth):
        converged = peer.converged(path, size, spp, depth, cache)
        noise = rel_noise(converged.variance, converged.image)
        truths.append({"scene": os.path.basename(path), "renderer": peer.describe(), "size": size, "spp": spp,
                       "max_depth": depth, "cache_file": os.path.basename(converged.file), "noise_relmse": noise})
        return converged, noise

    for scene in cfg["accuracy_scenes"]:
        path = os.path.join(ROOT, "scenes", scene)
        depth = scene_max_depth(path)

        def measure(study, backend, spp, extra=(), against=None, **setting):
            """relMSE over the seeds for one setting, split into bias and variance:
            E[relMSE of one image] = bias^2 + var + c, E[relMSE of the mean of n] = bias^2 + var/n + c,
            with c the truth's own noise (from its passes). bias^2 is reported as measured, signed:
            noise can make a zero bias negative."""
            converged, noise = against
            reference = converged.image
            errors, times, images = [], [], []
            for seed in range(cfg["seeds"]):
                if backend == "mitsuba":
                    s = peer.render(path, size, spp, seed=seed, max_depth=setting.get("max_depth"))
                else:
                    s = runner.render(path, backend, size, size, spp, extra=["--seed", str(seed), *extra], image=True)
                errors.append(rel_mse(s["image"], reference))
                times.append(s["time_s"])
                images.append(np.asarray(s["image"], dtype=np.float64))
            n, stack = len(images), np.stack(images)
            mean_image = stack.mean(axis=0)
            e, t, e_mean = statistics.mean(errors), statistics.mean(times), rel_mse(mean_image, reference)
            # The image's mean against the truth's, in standard errors. The image mean is the mean over pixels of
            # each pixel's mean over its channels; pixels are independent, a pixel's channels are not (the same
            # paths), so the variance is summed per pixel, of its channel mean, over the seeds and the truth's.
            pixel_variance = stack.reshape(n, -1, 3).mean(axis=-1).var(axis=0, ddof=1) / n + converged.pixel_variance
            se = math.sqrt(pixel_variance.sum()) / pixel_variance.size
            rows.append({"scene": scene, "study": study, "backend": backend, "spp": spp, **setting, "relmse": e,
                         "relmse_sd": statistics.stdev(errors), "bias2": (n * e_mean - e) / (n - 1) - noise,
                         "variance": (e - e_mean) * n / (n - 1), "truth_noise": noise, "time_s": t,
                         "efficiency": 1.0 / (e * t) if e > 0 and t > 0 else 0.0,
                         "mean_ratio": float(mean_image.mean() / reference.mean()),
                         "mean_z": float((mean_image.mean() - reference.mean()) / se) if se > 0 else 0.0})

        same_depth = truth(path, cfg["converged_spp"], depth)
        for spp in cfg["spp_series"]:
            for backend in cfg["spp_backends"]:
                measure("spp", backend, spp, against=same_depth)
            if "reference" in cfg["spp_backends"]:
                measure("spp", "reference", spp, ["--precision", "double"], against=same_depth, precision="double")
        if scene != "room.json":
            continue
        deep = truth(path, cfg["deep_converged_spp"], 64)
        for d in cfg["depth_series"]:
            measure("max_depth", "wavefront", cfg["depth_spp"], ["--max-depth", str(d)], against=deep, max_depth=d)
        for rr in cfg["rr_series"]:  # Russian roulette start depth; beyond max_depth it is off
            measure("rr_depth", "wavefront", cfg["depth_spp"], ["--rr-depth", str(rr)], against=same_depth, rr_depth=rr)
        for nee in cfg["nee_series"]:  # off: pure BSDF sampling, the same image with more variance
            measure("nee", "wavefront", cfg["depth_spp"], ["--nee", nee], against=same_depth, nee=nee)
        for hemisphere in cfg["hemisphere_series"]:  # diffuse sampling: cosine (the default) or uniform
            measure("hemisphere", "wavefront", cfg["depth_spp"], ["--hemisphere", hemisphere], against=same_depth,
                    hemisphere=hemisphere)
    return {"rows": rows, "truths": truths, "peer": peer_comparison(rows)}


# What the estimators series compares besides the roulette curve, at the scene's own max_depth: (label, flags).
ESTIMATOR_VARIANTS = [("mis off", ["--mis", "off"]), ("nee off", ["--nee", "off"])]
ROULETTE_OFF = 1_000_000  # an rr_depth no path reaches


def estimator_settings(cfg, depth, scene_depth, scene_rr):
    """(label, flags) at one max_depth: the roulette curve (start depths, the scene's among them, then off),
    and at the scene's max_depth also the variants. Every flag list names the max_depth."""
    curve = [(f"rr_depth {rr}", ["--rr-depth", str(rr)]) for rr in sorted({*cfg["estimator_rr"], scene_rr})]
    curve.append(("roulette off", ["--rr-depth", str(ROULETTE_OFF)]))
    variants = ESTIMATOR_VARIANTS if depth == scene_depth else []
    return [(label, ["--max-depth", str(depth), *flags]) for label, flags in curve + variants]


def estimators(runner, peer, cfg, out):
    """Per scene and max_depth, the wavefront's estimator choices at equal spp against the Mitsuba truth of
    that depth: relMSE over seeds (each seed renders every setting in turn, so times are interleaved), time
    min and median, efficiency 1 / (relMSE x median time), and per seed the ratio of the efficiency to the
    scene's own settings' (its rr_depth, MIS and NEE on), min and median."""
    size, spp = cfg["estimator_size"], cfg["estimator_spp"]
    cache = os.path.join(out, "converged-cache")
    rows = []
    for scene in cfg["estimator_scenes"]:
        path = os.path.join(ROOT, "scenes", scene)
        scene_depth, scene_rr = scene_max_depth(path), scene_render_settings(path).get("rr_depth", 3)
        for depth in cfg["estimator_depths"]:
            truth = peer.converged(path, size, cfg["converged_spp"], depth, cache).image
            settings = estimator_settings(cfg, depth, scene_depth, scene_rr)
            default = f"rr_depth {scene_rr}"
            errors = {label: [] for label, _ in settings}
            times = {label: [] for label, _ in settings}
            rays = {label: [] for label, _ in settings}
            for seed in range(cfg["estimator_seeds"]):
                for label, flags in settings:
                    s = runner.render(path, "wavefront", size, size, spp, extra=flags, image=True, seed=seed)
                    errors[label].append(rel_mse(s["image"], truth))
                    times[label].append(s["time_s"])
                    rays[label].append((s["extension_rays"] + s["shadow_rays"]) / s["samples"])
            for label, _ in settings:
                e, t, r = statistics.mean(errors[label]), statistics.median(times[label]), statistics.mean(rays[label])
                per_seed = [(ed * td) / (ex * tx) for ed, td, ex, tx in
                            zip(errors[default], times[default], errors[label], times[label])]
                rows.append({"scene": scene, "max_depth": depth, "setting": label,
                             "scene_default": label == default, "size": size, "spp": spp,
                             "seeds": len(errors[label]), "relmse": e, "relmse_sd": statistics.stdev(errors[label]),
                             "time_s_min": min(times[label]), "time_s_median": t, "efficiency": 1.0 / (e * t),
                             "relmse_of_default": e / statistics.mean(errors[default]),
                             "efficiency_of_default_min": min(per_seed),
                             "efficiency_of_default_median": statistics.median(per_seed),
                             "rays_per_sample": r,
                             "efficiency_per_ray_of_default":
                                 statistics.mean(errors[default]) * statistics.mean(rays[default]) / (e * r)})
    return rows


def estimators_markdown(rows, meta, truth_spp):
    lines = ["# Estimator choices: speed against accuracy per scene", "",
             "Generated by `python3 bench/run.py --series estimators`; do not edit by hand.", "",
             f"- commit `{meta['commit']}`, {meta['date']}, build {meta['build_type']}",
             f"- machine: {meta['cpu']}, {meta['cores']} cores (shared: read the ratios, measured side by side)",
             f"- OpenCL: {meta['opencl_platform']}; device {meta['opencl_device']}",
             f"- truth: {meta['mitsuba']} at {truth_spp} spp and the row's max_depth", "",
             "The wavefront, each setting at the same spp and seeds 0..n-1; every seed renders every setting of "
             "its max_depth in turn. relMSE: mean over the seeds of the image's relative MSE against the truth "
             "(its own noise included); time: the render's, kernel build left out; efficiency 1 / (relMSE x "
             "median time); of scene's: efficiency relative to the scene's own settings at the same max_depth "
             "(its rr_depth, marked *), per seed (min / median). Rays: extension and shadow rays per sample, "
             "the work a setting asks for, which no load on the machine changes; per ray, of scene's: "
             "1 / (relMSE x rays per sample) relative to the scene's own settings'. MIS and NEE are on unless "
             "the setting says.", "",
             "| scene | max_depth | setting | size, spp | relMSE (sd) | relMSE of scene's | time s (min / median) | "
             "efficiency | of scene's (min / median) | rays | per ray, of scene's |",
             "|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        mark = " *" if r["scene_default"] else ""
        lines.append(f"| {r['scene']} | {r['max_depth']} | {r['setting']}{mark} | {r['size']}², {r['spp']} | "
                     f"{r['relmse']:.4g} ({r['relmse_sd']:.2g}) | {r['relmse_of_default']:.3f} | "
                     f"{r['time_s_min']:.3f} / {r['time_s_median']:.3f} | {r['efficiency']:.3g} | "
                     f"{r['efficiency_of_default_min']:.2f} / {r['efficiency_of_default_median']:.2f} | "
                     f"{r['rays_per_sample']:.2f} | {r['efficiency_per_ray_of_default']:.2f} |")
    return "\n".join(lines) + "\n"


LANE_COUNTS = [1, 4, 8, 16]


def lanes(runner, cfg):
    """Samples/s per lane count (--lanes) for both OpenCL backends, per scene: each repetition renders every
    backend and lane count in turn (interleaved), the 1-minute load average read before each render; then one
    profiled wavefront render per lane count, for its stages' device times. Ratios against one lane and against
    8 (the default on CPUs, measured before 4 and 16 were compiled) are taken repetition by repetition."""
    rows = []
    for scene, spp in cfg["lanes_scenes"].items():
        path = os.path.join(ROOT, "scenes", scene)
        size = cfg["lanes_size"]
        counts = cfg.get("lanes_counts", LANE_COUNTS)
        backends = cfg.get("lanes_backends", ["wavefront", "megakernel"])
        configurations = [(backend, n) for backend in backends for n in counts]
        runs = {c: [] for c in configurations}
        for _ in range(cfg["lanes_repeats"]):
            for backend, n in configurations:
                load = os.getloadavg()[0]
                s = runner.render(path, backend, size, size, spp, extra=["--lanes", str(n)],
                                  warm_spp=min(4, spp))
                runs[(backend, n)].append({"samples_per_s": s["samples_per_s"], "time_s": s["time_s"],
                                           "load_1min": load})
        stages = {}
        for n in counts if "wavefront" in backends else []:
            profile = runner.render(path, "wavefront", size, size, spp, extra=["--lanes", str(n)], profile=True,
                                    warm_spp=min(4, spp))["profile"]
            stages[n] = {k["name"]: k["device_s"] for k in profile["kernels"]}
        for backend, n in configurations:
            r = runs[(backend, n)]
            sps = [x["samples_per_s"] / 1e6 for x in r]
            row = {"scene": scene, "backend": backend, "lanes": n, "size": size, "spp": spp, "runs": len(r),
                   "msamples_s_min": min(sps), "msamples_s_median": statistics.median(sps),
                   "msamples_s_max": max(sps), "time_s_median": statistics.median(x["time_s"] for x in r),
                   **{f"load_{k}": v for k, v in spread([x["load_1min"] for x in r]).items()},
                   "runs_detail": r}
            for base in (b for b in (1, 8) if b in counts):
                ratios = [a["samples_per_s"] / b["samples_per_s"] for a, b in zip(r, runs[(backend, base)])]
                row.update({f"of_{base}_lanes_{k}": v for k, v in spread(ratios).items()})
            if backend == "wavefront":
                row["stage_device_s"] = stages[n]
            rows.append(row)
    return rows


def eight_against_sixteen(cfg, backend, scenes):
    """The lanes series narrowed to the question a backend's default asks: 8 or 16 lanes, at 256x256."""
    cfg.update({"lanes_scenes": scenes, "lanes_size": 256, "lanes_backends": [backend], "lanes_counts": [8, 16],
                "lanes_flag": f" --lanes-{backend}", "lanes_file": f"lanes_{backend}"})


def lanes_markdown(rows, meta, cfg):
    lines = ["# Lanes: samples/s per lane count", "",
             f"Generated by `python3 bench/run.py --series lanes{cfg.get('lanes_flag', '')}` "
             f"(its {cfg['lanes_file']}.md and {cfg['lanes_file']}.json); do not edit by hand.",
             "",
             f"- commit `{meta['commit']}`, {meta['date']}, build {meta['build_type']}",
             f"- machine: {meta['cpu']}, {meta['cores']} cores, shared with other work: the 1-minute load average "
             "read before each render is given per row (min / median / max); read the ratios, measured side by side",
             f"- OpenCL: {meta['opencl_platform']}; device {meta['opencl_device']}; float vector width "
             f"{meta.get('opencl_float_vector_width', '?')}", "",
             f"Each scene at {cfg['lanes_size']}x{cfg['lanes_size']}, {cfg['lanes_repeats']} repetitions; every "
             "repetition renders each backend at each `--lanes` in turn, after unrecorded warm-up renders of "
             "each at 4 spp (PoCL compiles each kernel at its first launch; 4 spp launch the same sizes). Samples/s over the render's time (device setup and kernel build "
             "left out, as `--stats-json` counts them). Of 1 and of 8: samples/s over that of 1 or 8 lanes of the "
             "same backend in the same repetition (min / median). Fastest: the highest median of its scene and "
             "backend (*).", "",
             "| scene | spp | backend | lanes | Msamples/s min | median | of 1 lane (min / median) | "
             "of 8 lanes (min / median) | load (min / median / max) |", "|---|---|---|---|---|---|---|---|---|"]
    best = {}
    for r in rows:
        key = (r["scene"], r["backend"])
        if key not in best or r["msamples_s_median"] > best[key]["msamples_s_median"]:
            best[key] = r
    for r in rows:
        mark = " *" if best[(r["scene"], r["backend"])] is r else ""
        of = {base: (f"{r[f'of_{base}_lanes_min']:.2f} / {r[f'of_{base}_lanes_median']:.2f}"
                     if f"of_{base}_lanes_min" in r else "not run") for base in (1, 8)}
        lines.append(f"| {r['scene']} | {r['spp']} | {r['backend']} | {r['lanes']}{mark} | {r['msamples_s_min']:.3f} | "
                     f"{r['msamples_s_median']:.3f} | {of[1]} | {of[8]} | {r['load_min']:.1f} / "
                     f"{r['load_median']:.1f} / {r['load_max']:.1f} |")
    profiled = [r for r in rows if "stage_device_s" in r]
    if not profiled:
        return "\n".join(lines) + "\n"
    kernels = [k for k in profiled[0]["stage_device_s"] if any(r["stage_device_s"].get(k, 0) > 0 for r in profiled)]
    lines += ["", "Wavefront kernels' device time per frame in ms, one profiled render per scene and lane count "
              "(after the timed ones; a single run on a shared machine, so read large differences only):", "",
              "| scene | lanes | " + " | ".join(kernels) + " |", "|---|---|" + "---|" * len(kernels)]
    for r in profiled:
        lines.append(f"| {r['scene']} | {r['lanes']} | "
                     + " | ".join(f"{1e3 * r['stage_device_s'].get(k, 0.0):.0f}" for k in kernels) + " |")
    return "\n".join(lines) + "\n"


def loglog_at(points, x):
    """y at x on the log-log polyline through (x, y) points sorted by x; None outside their range."""
    for (x0, y0), (x1, y1) in zip(points, points[1:]):
        if x0 <= x <= x1 and x0 > 0 and x1 > x0 and y0 > 0 and y1 > 0:
            f = math.log(x / x0) / math.log(x1 / x0)
            return math.exp(math.log(y0) + f * (math.log(y1) - math.log(y0)))
    return None


def peer_comparison(rows):
    """Each renderer's efficiency 1/(relMSE x time) against Mitsuba's, at equal spp and at equal time
    (Mitsuba's relMSE at the renderer's time, on the log-log line through its spp series)."""
    out = []
    spp_rows = [r for r in rows if r["study"] == "spp" and "precision" not in r]
    for scene in sorted({r["scene"] for r in spp_rows}):
        mitsuba = sorted(((r["time_s"], r["relmse"]) for r in spp_rows
                          if r["scene"] == scene and r["backend"] == "mitsuba"))
        by_spp = {r["spp"]: r for r in spp_rows if r["scene"] == scene and r["backend"] == "mitsuba"}
        for r in spp_rows:
            if r["scene"] != scene or r["backend"] == "mitsuba":
                continue
            equal_time = loglog_at(mitsuba, r["time_s"])
            out.append({"scene": scene, "backend": r["backend"], "spp": r["spp"], "time_s": r["time_s"],
                        "relmse": r["relmse"], "efficiency": r["efficiency"],
                        "mitsuba_efficiency_equal_spp": by_spp[r["spp"]]["efficiency"],
                        "vs_mitsuba_equal_spp": r["efficiency"] / by_spp[r["spp"]]["efficiency"],
                        "mitsuba_relmse_equal_time": equal_time,
                        "vs_mitsuba_equal_time": equal_time / r["relmse"] if equal_time else None})
    return out


def run_mesh_bench(mesh_bench, flags, out, name, sections):
    """bench/mesh_bench's given sections with `flags` (--quick, --repeats N): its printout to NAME.txt, its
    figures from NAME.json, with the command's flags as "flags"."""
    raw = os.path.join(out, f"{name}.json")
    args = [mesh_bench, "--json", raw, "--sections", sections] + flags
    printed = subprocess.run(args, check=True, cwd=ROOT, capture_output=True, text=True).stdout
    with open(os.path.join(out, f"{name}.txt"), "w") as f:
        f.write(printed)
    with open(raw) as f:
        m = json.load(f)
    m["flags"] = " ".join(["--sections", sections] + flags)
    with open(raw, "w") as f:
        json.dump(m, f, indent=1)
    return m


def meshes(mesh_bench, flags, out):
    """bench/mesh_bench: BVH build, traversal beside Embree, whole frames against triangle count."""
    return run_mesh_bench(mesh_bench, flags, out, "meshes", "abcde")


def wavefront_embree(mesh_bench, flags, out):
    """bench/mesh_bench sections b, f, g and h: the Embree intersector beside our BVH and Embree, behind the
    wavefront's stages, and what Embree's packets of a pixel's samples would give."""
    return run_mesh_bench(mesh_bench, flags, out, "wavefront_embree", "bfgh")


def embree_targets(m):
    """Issue 21's intersect target, read off the run: (text, met) for the wavefront's stage as
    --intersector embree runs it, and for the intersector alone."""
    rows = {r["tracer"]: r for r in m["traversal"]
            if r["rays"] == "incoherent" and r["query"] == "closest"}
    out = []
    for tracer, what in (("embree_stage", "the wavefront's intersect stage with --intersector embree (the host's "
                                          "trace and the kernel's rest)"),
                         ("ours_verified", "the Embree intersector alone (verified mode)")):
        r = rows[tracer]
        out.append((f"intersect on incoherent bunny rays, {what}: {r['of_embree_median']:.2f}x Embree "
                    f"rtcIntersect1 on 2 threads (medians; target at least 1.0x)", r["of_embree_median"] >= 1.0))
    return out


def mesh_bench_header(m, title, series):
    """A mesh_bench page's title and the run's commit, date, machine, OpenCL platform, Embree and load."""
    meta = m["meta"]
    lines = [f"# {title}", "",
             f"Generated by `python3 bench/run.py --series {series}` from one run of `bench/mesh_bench "
             f"{m['flags']}`; do not edit by hand.", "",
             f"- commit `{meta['commit']}`, {meta['date']}", f"- machine: {meta['cpu']}, {meta['cores']} cores",
             f"- OpenCL: {meta['opencl_platform']}; device {meta['opencl_device']}",
             f"- {meta.get('embree_device', 'Embree ' + meta['embree'])}"]
    if "load_average_start" in meta:
        lines.append(f"- load average (1, 5, 15 min) at the start: {meta['load_average_start']}; at the end: "
                     f"{meta.get('load_average_end', '?')} (other engineers' builds share the cores)")
    return lines + [""]


def markdown_table(columns, rows):
    """A markdown table: a header of `columns`, then a line of cells for each row."""
    return (["| " + " | ".join(columns) + " |", "|" + "---|" * len(columns)] +
            ["| " + " | ".join(str(cell) for cell in row) + " |" for row in rows])


def wavefront_embree_markdown(m):
    lines = mesh_bench_header(m, "Embree behind the wavefront's intersect stages", "embree")
    lines += ["## Target (issue 21)", ""]
    lines += [f"- {'met' if met else 'NOT met'}: {text}" for text, met in embree_targets(m)]
    lines += traversal_markdown(m)
    shipped, ref = m["shipped_scene"], m["reference"]
    lines += ["", "## f. The shipped bunny scene in each mode", "",
              f"`{os.path.relpath(shipped[0]['scene'], ROOT)}` as shipped (spheres, quads, the mesh light, the "
              f"bunny), {shipped[0]['ray_count']:,} rays of each kind made as in b: quads among Embree's shapes "
              "(enlarged triangles in the verified mode, user geometry in the exact one), spheres tested in turn. "
              f"{shipped[0]['repeats']} interleaved repetitions after a warm-up round.", ""]
    lines += markdown_table(["rays", "query", "tracer", "Mrays/s best", "Mrays/s median"],
                            [[r["rays"], r["query"], r["tracer"], f"{r['mrays_s_best']:.2f}",
                              f"{r['mrays_s_median']:.2f}"] for r in shipped])
    lines += ["", "## f. The reference renderer with each intersector", "",
              f"`render_reference` on 2 threads, {ref[0]['width']}x{ref[0]['height']}, {ref[0]['spp']} spp, "
              f"{ref[0]['repeats']} interleaved repetitions; pixels differing: between the two images of the last "
              "repetition.", ""]
    lines += markdown_table(["scene", "intersector", "Msamples/s min", "median", "pixels differing"],
                            [[r["scene"], r["intersector"], f"{r['msamples_s_min']:.4f}",
                              f"{r['msamples_s_median']:.4f}", r["pixels_differing"]] for r in ref])
    wf = m["wavefront"]
    lines += ["", "## g. The wavefront with each intersector", "",
              f"`render_wavefront` at {wf[0]['width']}x{wf[0]['height']}, {wf[0]['spp']} spp, default options but "
              f"the intersector, {wf[0]['repeats']} interleaved repetitions after one warm-up render each: samples/s "
              "of unprofiled renders. The tracing stages' Mrays/s from a profiled render of its own (intersect and "
              "shade apart): rays over the stage's time, with Embree the host's trace (map, Embree, unmap) plus the kernel's rest; host alone: "
              "the host's trace only. \"traced in shade\": no intersect_shadow stage ran, for `shade` traces its shadow rays "
              "itself there (our BVH on a CPU device).", ""]
    lines += markdown_table(["scene", "intersector", "Msamples/s min", "median", "of bvh (medians)",
                             "intersect Mrays/s", "host alone", "intersect_shadow Mrays/s", "host alone"],
                            [[r["scene"], r["intersector"], f"{r['msamples_s_min']:.4f}",
                              f"{r['msamples_s_median']:.4f}", f"{r['of_bvh_median']:.2f}x",
                              f"{r['intersect_mrays_s_median']:.2f}",
                              f"{r['intersect_host_mrays_s_median']:.2f}" if "intersect_host_mrays_s_median" in r
                              else "-",
                              f"{r['intersect_shadow_mrays_s_median']:.2f}"
                              if r.get("intersect_shadow_mrays_s_median") is not None else "traced in shade",
                              f"{r['intersect_shadow_host_mrays_s_median']:.2f}"
                              if "intersect_shadow_host_mrays_s_median" in r else "-"] for r in wf])
    packets = m["pixel_packets"]
    lines += ["", "## h. Packets of a pixel's samples", "",
              "Camera rays with a pixel's samples adjacent (as Mitsuba's wavefront lays them out), "
              f"{packets[0]['count']:,} of them, and their diffuse bounces, traced by Embree on its own triangles "
              "(not robust, 2 threads): one ray at a time in that order, one at a time shuffled (as a queue of "
              "unrelated paths holds them), and in packets of 16 consecutive rays (rtcIntersect16). Hits differing: "
              "rays whose triangle or distance is not what the first row finds for them.", ""]
    lines += markdown_table(["rays", "traced", "count", "Mrays/s best", "median", "of in order (medians)",
                             "hits differing"],
                            [[r["rays"], r["traced"], f"{r['count']:,}", f"{r['mrays_s_best']:.2f}",
                              f"{r['mrays_s_median']:.2f}", f"{r['of_in_order_median']:.2f}x",
                              r.get("hits_differing_from_in_order", "-")] for r in packets])
    return "\n".join(lines) + "\n"


def mesh_rows(m):
    """One flat row per figure, each with the run's commit, date, machine and platform."""
    meta = {f"meta_{k}": v for k, v in m["meta"].items()}
    rows = []
    for section in ("build", "traversal", "agreement", "render", "short_list"):
        rows += [{"section": section, **r, **meta} for r in m.get(section, [])]
    for r in m["lanes"]:
        stages = {f"{k}_device_ms_{q}": v[f"device_ms_{q}"] for k, v in r["stages"].items() for q in ("min", "median")}
        rows.append({"section": "lanes", **{k: v for k, v in r.items() if k != "stages"}, **stages, **meta})
    return rows


def fit_log(render_rows):
    """Least squares of microseconds per sample on log2(scene triangles): (a, b, r^2)."""
    xs = [math.log2(r["scene_triangles"]) for r in render_rows]
    ys = [1.0 / r["msamples_s_median"] for r in render_rows]
    n = len(xs)
    mx, my = sum(xs) / n, sum(ys) / n
    sxx = sum((x - mx) ** 2 for x in xs)
    if n < 3 or sxx == 0:
        return None
    b = sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sxx
    a = my - b * mx
    ss_res = sum((y - a - b * x) ** 2 for x, y in zip(xs, ys))
    ss_tot = sum((y - my) ** 2 for y in ys)
    return a, b, 1.0 - ss_res / ss_tot if ss_tot > 0 else 1.0


def mesh_targets(m):
    """The issue's two targets, read off the run: (text, met) pairs."""
    lines = []
    largest = max(m["build"], key=lambda r: r["triangles"])
    if largest["triangles"] >= 1_000_000:
        s = largest["flatten_scene_s_median"]
        lines.append((f"build plus flattening (flatten_scene) of {largest['triangles']:,} triangles: {s:.3f} s "
                      f"median (target under 2 s)", s < 2.0))
    for r in m["traversal"]:
        if r["rays"] == "incoherent" and r["query"] == "closest" and r["tracer"] == "opencl_stage":
            lines.append((f"intersect stage on incoherent rays: {r['of_embree_median']:.2f}x Embree's rays/s "
                          f"(medians; target at least 0.5x)", r["of_embree_median"] >= 0.5))
    return lines


def traversal_markdown(m):
    """Section b of mesh_bench: rays/s of every tracer and their agreement."""
    tr = m["traversal"]
    lines = ["", "## b. Traversal on the bunny scene, beside Embree", "",
              f"`scenes/bunny.json` with its two spheres left out and each wall quad as two triangles "
              f"({tr[0]['ray_count']:,} primary rays, one per pixel; incoherent: one cosine-distributed bounce "
              "from each primary hit, origin offset as the renderer offsets it, whatever the material). Closest hit: "
              "t_max infinite. Any hit: the same rays as segments ending at 0.99 of their closest hit, so nearly "
              "all are unoccluded and must be traversed to the end (a shadow ray that reaches its light). "
              "opencl_stage: the wavefront's intersect / intersect_shadow kernel run alone through the Pipeline, "
              "timed by its OpenCL events (kernel time only); embree_stage: the same stage as --intersector "
              "embree runs it (the host maps the queue and the path state, traces with the Embree intersector on 2 "
              "threads, unmaps; the kernel does the rest), timed as the profile's host row plus the kernel; "
              "scalar_cpp: the BVH traversal compiled as C++ (kernels/shared/bvh.h through the reference) on 2 "
              "threads; embree: `rtcIntersect1` / `rtcOccluded1` on 2 threads, scene of the same float triangles, "
              "RTC_BUILD_QUALITY_MEDIUM, not robust (embree_robust: RTC_SCENE_FLAG_ROBUST); ours_*: the Embree "
              "intersector (src/accel/embree_intersector.h) on a queue of every ray, read from SoA arrays by slot "
              "as the wavefront keeps its path state, on 2 threads, by the wall clock: verified = Embree's robust "
              "triangles, enlarged, find the nearest with one rtcIntersect1 and our test recomputes its distance "
              "(rays our test rejects traced again exactly: counted under the row), exact = our test as Embree user "
              "geometry on every triangle whose box the ray enters. Repetitions interleaved "
              "(every tracer, ray set and query in turn), after one unrecorded warm-up round.", "",
              "| rays | query | tracer | Mrays/s best | Mrays/s median | of Embree (medians) | hits / occluded |",
              "|---|---|---|---|---|---|---|"]
    for r in tr:
        lines.append(f"| {r['rays']} | {r['query']} | {r['tracer']} | {r['mrays_s_best']:.2f} | "
                     f"{r['mrays_s_median']:.2f} | {r['of_embree_median']:.2f}x | {r['hits']:,} |")
    lines += ["", f"Best of {tr[0]['repeats']} repetitions (from the shortest time) and their median.", "",
              "Agreement (last repetition). Closest hit: a ray differs when one side hits and the other does not, "
              "or the distances differ by more than 1e-4 relative; hits of another triangle at the same distance "
              "(shared edges) are counted apart; bit-identical: same triangle and the same float t. Any hit: the "
              "verdicts differ.", "",
              "| rays | query | pair | hits a | hits b | differ | other triangle, same t | bit-identical |",
              "|---|---|---|---|---|---|---|---|"]
    for r in m["agreement"]:
        extra = (f"{r['other_triangle_same_t']} | {100 * r['bit_identical_fraction']:.2f}%"
                 if r["query"] == "closest" else "- | -")
        lines.append(f"| {r['rays']} | {r['query']} | {r['pair']} | {r['hits_a']:,} | {r['hits_b']:,} | "
                     f"{100 * r['differ_fraction']:.4f}% | {extra} |")
    return lines


def meshes_markdown(m):
    lines = mesh_bench_header(m, "Triangle meshes: BVH build, traversal beside Embree, whole frames", "meshes")
    lines += ["## Targets (issue 11)", ""]
    for text, met in mesh_targets(m):
        lines.append(f"- {'met' if met else 'NOT met'}: {text}")
    lines += ["", "## a. BVH build and memory", "",
              "Meshes from the bunny (69,666 triangles): below it by vertex clustering, above it by 1->4 midpoint "
              "subdivision. `build_bvh`: Embree's binned SAH (`rtcBuildBVH`, all cores) into our nodes plus our "
              "depth-first flattening with boxes recomputed in double; `flatten_scene`: everything the renderer pays "
              "for the meshes (gathering the triangles, build_bvh, leaf order, device structs). Bytes as uploaded: "
              "64-byte nodes and 44-byte triangles.", "",
              "| triangles | nodes | depth | build_bvh s (min / median) | flatten_scene s (min / median) | "
              "bytes per triangle |", "|---|---|---|---|---|---|"]
    for r in m["build"]:
        lines.append(f"| {r['triangles']:,} | {r['nodes']:,} | {r['depth']} | {r['build_bvh_s_min']:.3f} / "
                     f"{r['build_bvh_s_median']:.3f} | {r['flatten_scene_s_min']:.3f} / "
                     f"{r['flatten_scene_s_median']:.3f} | {r['bytes_per_triangle']:.1f} |")
    lines += traversal_markdown(m)
    rr = m["render"]
    lines += ["", "## c. Whole frames against triangle count", "",
              f"The traced scene of b with the bunny at each size, wavefront (`render_wavefront`, default options), "
              f"{rr[0]['width']}x{rr[0]['height']}, {rr[0]['spp']} spp, {rr[0]['repeats']} interleaved repetitions "
              "after one warm-up render; samples/s over the render's time (device setup, kernel build and BVH "
              "build left out, as `wavepath render --stats-json` counts them).", "",
              "| bunny triangles | scene triangles | Msamples/s min | median | us per sample (median) | "
              "Mrays/s median |", "|---|---|---|---|---|---|"]
    for r in rr:
        lines.append(f"| {r['triangles']:,} | {r['scene_triangles']:,} | {r['msamples_s_min']:.4f} | "
                     f"{r['msamples_s_median']:.4f} | {1 / r['msamples_s_median']:.2f} | {r['mrays_s_median']:.3f} |")
    fit = fit_log(rr)
    if fit:
        a, b, r2 = fit
        lines += ["", f"Least-squares fit of the median time per sample on log2(scene triangles): "
                  f"{a:.2f} + {b:.3f} x log2(n) us, r^2 = {r2:.3f}."]
    ll = m["lanes"]
    stages = list(ll[0]["stages"])
    lines += ["", "## d. Lanes with meshes", "",
              f"`{os.path.relpath(ll[0]['scene'], ROOT)}` as shipped (quads, spheres, the mesh light, the bunny), "
              f"{ll[0]['width']}x{ll[0]['height']}, {ll[0]['spp']} spp, {ll[0]['repeats']} interleaved repetitions "
              "after one warm-up render each: one lane in every stage against 8 (the default on CPUs), where "
              "intersect and intersect_shadow traverse the BVH in each lane (kernels/device/bvh_lanes.h). "
              "Samples/s from unprofiled renders; each kernel's device time (median, ms per frame) from a "
              "profiled render of its own.", "",
              "| lanes | Msamples/s min | median | " + " | ".join(stages) + " |",
              "|---|---|---|" + "---|" * len(stages)]
    for r in ll:
        lines.append(f"| {r['lanes']} | {r['msamples_s_min']:.4f} | {r['msamples_s_median']:.4f} | "
                     + " | ".join(f"{r['stages'][k]['device_ms_median']:.1f}" for k in stages) + " |")
    same = all(r["image_identical_to_one_lane"] for r in ll)
    lines += ["", f"Images of the two identical to the bit: {'yes' if same else 'NO'}."]
    sl = m.get("short_list")
    if not sl:
        return "\n".join(lines) + "\n"
    lines += ["", "## e. Short list or BVH", "",
              f"The shipped room, cornell and bunny scenes at {sl[0]['width']}x{sl[0]['height']}, {sl[0]['spp']} spp, "
              f"{sl[0]['repeats']} interleaved repetitions after one warm-up render each, default options (8 "
              "lanes): as shipped (spheres and quads tested one by one by every ray), with every quad as two "
              "triangles in the BVH, and with the spheres left out (what moving them into the BVH could save at "
              "most). Samples/s from unprofiled renders; the intersect stages' device time per ray from a profiled "
              "render of its own.", "",
              "| scene | shapes | Msamples/s min | median | intersect ns/ray | intersect_shadow ns/ray |",
              "|---|---|---|---|---|---|"]
    for r in sl:
        lines.append(f"| {r['scene']} | {r['shapes']} | {r['msamples_s_min']:.4f} | "
                     f"{r['msamples_s_median']:.4f} | {r['intersect_ns_per_ray_median']:.1f} | "
                     f"{r['intersect_shadow_ns_per_ray_median']:.1f} |")
    return "\n".join(lines) + "\n"


def write_csv(path, rows):
    keys = []
    for r in rows:
        keys += [k for k in r if k not in keys and not isinstance(r[k], (dict, list))]
    with open(path, "w", newline="") as f:
        writer = csv.writer(f, lineterminator="\n")  # quotes only fields with commas or quotes
        writer.writerow(keys)
        for r in rows:
            writer.writerow([str(r.get(k, "")) for k in keys])


def plot(out, results):
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        return ["(matplotlib not installed: no plots; pip install -r bench/requirements.txt)"]
    made = []
    rows = [r for r in results["throughput"] if "msamples_s_median" in r]
    scenes = sorted({r["scene"] for r in rows})
    fig, ax = plt.subplots(figsize=(6, 3.5))
    for i, backend in enumerate(("wavefront", "megakernel", "reference", "mitsuba")):
        vals = [next(r["msamples_s_median"] for r in rows if r["scene"] == s and r["backend"] == backend)
                for s in scenes]
        ax.bar([j + 0.2 * i for j in range(len(scenes))], vals, width=0.2, label=backend)
    ax.set_xticks([j + 0.3 for j in range(len(scenes))], scenes)
    ax.set_ylabel("Msamples/s (median)")
    ax.legend()
    fig.tight_layout()
    fig.savefig(os.path.join(out, "throughput.png"), dpi=80)
    made.append("throughput.png")
    ws = [r for r in results["scaling"] if r["study"] == "wavefront_size"]
    fig, ax = plt.subplots(figsize=(6, 3.5))
    ax.semilogx([r["paths"] for r in ws], [r["msamples_s"] for r in ws], "o-", base=2)
    ax.set_xlabel("paths in flight")
    ax.set_ylabel("Msamples/s")
    fig.tight_layout()
    fig.savefig(os.path.join(out, "scaling_wavefront.png"), dpi=80)
    made.append("scaling_wavefront.png")
    fig, ax = plt.subplots(figsize=(6, 3.5))
    series = [("spp", "wavefront", None, "o-"), ("spp", "reference", None, "o-"),
              ("spp", "reference", "double", "o:"), ("spp", "mitsuba", None, "x-"), ("max_depth", "wavefront", None, "s--"),
              ("rr_depth", "wavefront", None, "^--"), ("nee", "wavefront", None, "v"),
              ("hemisphere", "wavefront", None, "D")]
    for study, backend, precision, style in series:
        pts = [r for r in results["accuracy"]["rows"] if r["scene"] == "room.json" and r["study"] == study
               and r["backend"] == backend and r.get("precision") == precision]
        label = f"{backend}{' ' + precision if precision else ''}, {study} series"
        ax.loglog([r["time_s"] for r in pts], [r["relmse"] for r in pts], style, label=label)
    ax.set_xlabel("time (s)")
    ax.set_ylabel("relMSE (room)")
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "relmse_vs_time.png"), dpi=80)
    made.append("relmse_vs_time.png")
    return made


def precision_sentence(rows):
    """What the data say of float against double and of the wavefront against the float reference."""
    out = []
    for scene in sorted({r["scene"] for r in rows}):
        def relmse(backend, spp, precision=None):
            return next((r["relmse"] for r in rows if r["scene"] == scene and r["study"] == "spp" and
                         r["backend"] == backend and r["spp"] == spp and r.get("precision") == precision), None)
        spps = sorted({r["spp"] for r in rows if r["scene"] == scene and r.get("precision") == "double"})
        if not spps:
            continue
        ratios = [relmse("reference", s, "double") / relmse("reference", s) for s in spps]
        same = all(relmse("wavefront", s) == relmse("reference", s) for s in spps)
        out.append(f"{scene}: relMSE of the reference in double over float {min(ratios):.4f}-{max(ratios):.4f} "
                   f"across the spp series; the wavefront's relMSE {'equals' if same else 'differs from'} the float "
                   f"reference's at {'every' if same else 'some'} spp.")
    return " ".join(out)


def accuracy_markdown(acc):
    rows, lines = acc["rows"], ["", "## Speed versus accuracy (relMSE against Mitsuba's converged images)", ""]
    lines += ["The truth of each series is a converged image from Mitsuba, a renderer that shares no code with "
              "wavepath, rendered in passes whose spread gives its own noise c (the relMSE it adds to every "
              "measurement), cached under a key of the converted scene, the settings and the renderer's version:", "",
              "| scene | truth | spp | max_depth | noise c (relMSE) | cache file |", "|---|---|---|---|---|---|"]
    for t in acc["truths"]:
        lines.append(f"| {t['scene']} | {t['renderer']} | {t['spp']} | {t['max_depth']} | {t['noise_relmse']:.3g} | "
                     f"{t['cache_file']} |")
    lines += ["", "relMSE per image, mean over seeds (+- standard deviation), with (x - r)^2 / (r^2 + 0.01) per pixel "
              "and channel. bias^2 = (n relMSE(mean of the n images) - mean relMSE) / (n - 1) - c, signed (noise can "
              "make a zero bias negative); variance = n (mean relMSE - relMSE(mean image)) / (n - 1). mean ratio: "
              "the image's mean over the truth's, with z in standard errors from each pixel's variance of its "
              "channels' mean (a pixel's channels share their paths; pixels are independent). The "
              "max_depth series is measured against a truth at depth 64, the others against one at the scene's "
              "max_depth. " + precision_sentence(rows), "",
              "| scene | study | backend | setting | relMSE | bias^2 | variance | time s | 1/(relMSE x time) | "
              "mean ratio (z) |", "|---|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        setting = ", ".join(f"{k} {r[k]}" for k in ("spp", "precision", "max_depth", "rr_depth", "nee", "hemisphere")
                            if k in r)
        lines.append(f"| {r['scene']} | {r['study']} | {r['backend']} | {setting} | {r['relmse']:.4g} +- "
                     f"{r['relmse_sd']:.2g} | {r['bias2']:.3g} | {r['variance']:.3g} | {r['time_s']:.3f} | "
                     f"{r['efficiency']:.4g} | {r['mean_ratio']:.4f} ({r['mean_z']:+.1f}) |")
    lines += ["", "### Against Mitsuba (llvm_ad_rgb): efficiency 1/(relMSE x time)", "",
              "Equal spp: both at the same spp. Equal time: Mitsuba's relMSE at the renderer's time, on the "
              "log-log line through Mitsuba's spp series (blank outside it); the ratio is then Mitsuba's relMSE "
              "over the renderer's, which is the efficiency ratio at that time.", "",
              "| scene | backend | spp | time s | relMSE | efficiency | x Mitsuba at equal spp | "
              "x Mitsuba at equal time |", "|---|---|---|---|---|---|---|---|"]
    for r in acc["peer"]:
        equal_time = f"{r['vs_mitsuba_equal_time']:.2f}" if r["vs_mitsuba_equal_time"] else ""
        lines.append(f"| {r['scene']} | {r['backend']} | {r['spp']} | {r['time_s']:.3f} | {r['relmse']:.4g} | "
                     f"{r['efficiency']:.4g} | {r['vs_mitsuba_equal_spp']:.2f} | {equal_time} |")
    return lines


# mesh_bench's agreement pairs whose tracers both report our own tests' hits (our BVH in OpenCL and in C++, and
# the Embree intersector in either mode, which recomputes every distance with our tests): no ray may differ.
EXACT_PAIRS = {"opencl_stage vs scalar_cpp", "scalar_cpp vs embree_stage", "scalar_cpp vs ours_verified",
               "scalar_cpp vs ours_exact"}


def check(results):
    """What a broken renderer would fail (bench_quick --check): relMSE falling with spp at about 1/spp,
    every image's mean agreeing with the independent truth, finite ratios, and mesh_bench's tracers of our own
    tests finding the same hits (EXACT_PAIRS). Returns the failures."""
    failures = []
    rows = results.get("accuracy", {}).get("rows", [])
    for scene in sorted({r["scene"] for r in rows}):
        for backend in sorted({r["backend"] for r in rows if r["study"] == "spp"}):
            pts = [(r["spp"], r["relmse"]) for r in rows if r["scene"] == scene and r["study"] == "spp"
                   and r["backend"] == backend and "precision" not in r]
            xs, ys = [math.log(p[0]) for p in pts], [math.log(p[1]) for p in pts]
            mx, my = statistics.mean(xs), statistics.mean(ys)
            slope = sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sum((x - mx) ** 2 for x in xs)
            if not -1.3 <= slope <= -0.7:
                failures.append(f"{scene} {backend}: relMSE falls as spp^{slope:.2f}, not about spp^-1")
    for r in rows:  # |z| <= 5: each image's mean within five standard errors of the truth's (truncation apart)
        if r["study"] != "max_depth" and abs(r["mean_z"]) > 5:
            failures.append(f"{r['scene']} {r['study']} {r['backend']} spp {r['spp']}: image mean {r['mean_ratio']:.4f}"
                            f" of the truth's, z = {r['mean_z']:.1f}")
    for name in ("meshes", "embree"):  # mesh_bench's tracers that compute our tests' hits: the same rays, the same hits
        for r in results.get(name, {}).get("agreement", []):
            if r["pair"] in EXACT_PAIRS and r["differ_fraction"] > 0:
                failures.append(f"mesh_bench {r['rays']} {r['query']} hits: {r['pair']} differ on "
                                f"{100 * r['differ_fraction']:.4f}% of the rays")
    values = [r[k] for r in results.get("throughput", []) for k in r if k.startswith("ratio_")]
    values += [r["efficiency"] for r in rows] + [r["vs_mitsuba_equal_spp"] for r in results.get("accuracy", {}).get("peer", [])]
    failures += [f"ratio or efficiency {v} is not finite and positive" for v in values
                 if not (isinstance(v, float) and math.isfinite(v) and v > 0)]
    return failures


def summary(results, plots):
    m = results["meta"]
    results = {"throughput": [], "scaling": [], **results}
    lines = ["# wavepath benchmark", "",
             f"Commit `{m['commit']}`, {m['date']}; {m['wavepath']} ({m['build_type']} build, `{m['binary']}`); "
             f"{m['mitsuba']}.", "",
             f"Machine: {m['cpu']}, {m['cores']} cores; OpenCL: {m['opencl_platform']}. Mode: {results['mode']}; "
             f"{results['elapsed_s']:.0f} s.", "", "## Throughput (interleaved runs)", "",
             "Each repetition runs every configuration once, in turn. Mitsuba renders in this process "
             "(`mi.render` and reading the image back, scene loading left out); wavepath's time is the render's "
             "from `--stats-json` (device setup and kernel build left out).", "",
             "| scene | backend | size | spp | runs | Msamples/s min | median | max | Mrays/s median |",
             "|---|---|---|---|---|---|---|---|---|"]
    for r in results["throughput"]:
        if "msamples_s_median" in r:
            rays = f"{r['mrays_s_median']:.2f}" if "mrays_s_median" in r else "-"
            lines.append(f"| {r['scene']} | {r['backend']} | {r['size']}^2 | {r['spp']} | {r['runs']} | "
                         f"{r['msamples_s_min']:.3f} | {r['msamples_s_median']:.3f} | {r['msamples_s_max']:.3f} | "
                         f"{rays} |")
    lines += ["", "The wavefront's samples/s over each other configuration's, per repetition:", "",
              "| scene | ratio | runs | min | median | max |", "|---|---|---|---|---|---|"]
    for r in results["throughput"]:
        if "ratio_median" in r:
            lines.append(f"| {r['scene']} | {r['backend']} | {r['runs']} | {r['ratio_min']:.3f} | "
                         f"{r['ratio_median']:.3f} | {r['ratio_max']:.3f} |")
    for r in results["throughput"]:
        if "profile" in r:
            p = r["profile"]
            lines += ["", f"Wavefront stages, {r['scene']} (one profiled run, render {p['render_s']:.3f} s, "
                      f"between kernels {p['gaps_s']:.3f} s):", "",
                      "| kernel | launches | items | device s | Mitems/s | share |", "|---|---|---|---|---|---|"]
            for k in p["kernels"]:
                lines.append(f"| {k['name']} | {k['launches']} | {k['items']} | {k['device_s']:.3f} | "
                             f"{k['items_per_s'] / 1e6:.2f} | {100 * k['share']:.1f}% |")
    lines += ["", "## Roofline (wavefront tracing stages against the intersect bound)", "",
              "The bound: camera rays traced with closest hit and nothing else (kernels/intersect_bound.cl: no "
              "queues, no path state), best of three launches of 2^20 rays after the profiled render. "
              "intersect_shadow runs any hit, cheaper per test, and is measured against the same bound. Where "
              "intersect_and_shade traces the extension rays (CPU devices), its rays/s include the shading.", "",
              "| scene | bound Mrays/s | closest-hit stage | Mrays/s | of bound | intersect_shadow Mrays/s | of bound |",
              "|---|---|---|---|---|---|---|"]
    for r in results["throughput"]:
        if "intersect_bound_mrays_s" in r:
            bound, shadow = r["intersect_bound_mrays_s"], r.get("intersect_shadow_of_bound")
            shadow_cells = (f"{shadow * bound:.2f} | {100 * shadow:.0f}%" if shadow is not None
                            else "- (traced in shade) | -")
            lines.append(f"| {r['scene']} | {bound:.2f} | {r.get('closest_hit_stage', 'intersect')} | "
                         f"{r['intersect_of_bound'] * bound:.2f} | "
                         f"{100 * r['intersect_of_bound']:.0f}% | {shadow_cells} |")
    lines += ["", "## Scaling (room)", "", "| study | paths / size | backend | Msamples/s |", "|---|---|---|---|"]
    for r in results["scaling"]:
        lines.append(f"| {r['study']} | {r.get('paths', r.get('size'))} | {r.get('backend', 'wavefront')} | "
                     f"{r['msamples_s']:.3f} |")
    if "accuracy" in results:
        lines += accuracy_markdown(results["accuracy"])
    if "meshes" in results:
        mm = results["meshes"]
        lines += ["", "## Meshes (bench/mesh_bench; every table in meshes.md)", ""]
        lines += [f"- {'met' if met else 'NOT met'}: {text}" for text, met in mesh_targets(mm)]
        lines.append(f"- commit {mm['meta']['commit']}, {mm['meta']['date']}; " + "; ".join(
            f"{r['triangles']:,} triangles {r['msamples_s_median']:.3f} Msamples/s" for r in mm["render"]))
    lines += [""] + [f"![{p}]({p})" if p.endswith(".png") else p for p in plots]
    return "\n".join(lines) + "\n"


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--quick", action="store_true", help="small sizes, for CI (under two minutes)")
    parser.add_argument("--out", default=os.path.join(ROOT, "bench", "out"))
    parser.add_argument("--binary", default=os.path.join(ROOT, "build", "wavepath"))
    parser.add_argument("--mesh-bench", default=os.path.join(ROOT, "build", "bench", "mesh_bench"))
    parser.add_argument("--series", default="throughput,scaling,accuracy,meshes",
                        help="comma-separated: throughput, scaling, accuracy, meshes, estimators, embree, lanes")
    parser.add_argument("--mesh-repeats", type=int, default=0,
                        help="bench/mesh_bench's interleaved repetitions (its default: 7, 5 with --quick)")
    parser.add_argument("--check", action="store_true",
                        help="exit 1 when the results show what a broken renderer would (bench_quick)")
    parser.add_argument("--lanes-short", action="store_true",
                        help="the lanes series at 128x128 and a sixth of its spp (about 15 minutes on 2 cores)")
    parser.add_argument("--lanes-megakernel", action="store_true",
                        help="the lanes series for the megakernel's default without meshes only: 8 and 16 lanes on "
                             "room and cornell at 256x256, 32 spp (lanes_megakernel.md; about 5 minutes on 2 cores)")
    parser.add_argument("--lanes-wavefront", action="store_true",
                        help="the lanes series for the wavefront's default only: 8 and 16 lanes on room and cornell "
                             "at 256x256, 32 spp, and the bunny at 8 spp (lanes_wavefront.md; about 5 minutes on 2 "
                             "cores)")
    args = parser.parse_args()
    series = args.series.split(",")
    unknown = set(series) - {"throughput", "scaling", "accuracy", "meshes", "estimators", "embree", "lanes"}
    if unknown:
        parser.error(f"unknown series: {', '.join(sorted(unknown))}")
    if args.quick:
        cfg = {"scenes": ["cornell.json"], "size": 128, "spp": 2, "repeats": 5,
               "wavefront_log2": [12, 14, 16], "resolutions": [64, 128], "accuracy_size": 32,
               "accuracy_scenes": ["room.json", "cornell.json"], "converged_spp": 1024, "deep_converged_spp": 512,
               "spp_series": [1, 4, 16], "spp_backends": ["wavefront", "mitsuba"], "seeds": 3,
               "depth_series": [1, 8], "depth_spp": 8, "rr_series": [1000], "nee_series": ["off"],
               "hemisphere_series": ["uniform"], "estimator_scenes": ["cornell.json"], "estimator_size": 32,
               "estimator_spp": 4, "estimator_seeds": 3, "estimator_depths": [8], "estimator_rr": [],
               "lanes_scenes": {"cornell.json": 2, "bunny.json": 1}, "lanes_size": 64, "lanes_repeats": 5}
    else:
        cfg = {"scenes": ["room.json", "cornell.json"], "size": 512, "spp": 4, "repeats": 5,
               "wavefront_log2": [12, 14, 16, 18, 20, 22], "resolutions": [128, 256, 512, 1024, 2048],
               "accuracy_size": 128, "accuracy_scenes": ["room.json", "cornell.json"], "converged_spp": 4096,
               "deep_converged_spp": 1024, "spp_series": [1, 4, 16, 64, 256],
               "spp_backends": ["wavefront", "megakernel", "reference", "mitsuba"], "seeds": 3,
               "depth_series": [1, 2, 4, 8, 16, 32], "depth_spp": 16, "rr_series": [1, 2, 3, 5, 8, 1000],
               "nee_series": ["on", "off"], "hemisphere_series": ["cosine", "uniform"],
               "estimator_scenes": ["room.json", "cornell.json"], "estimator_size": 128, "estimator_spp": 16,
               "estimator_seeds": 5, "estimator_depths": [8, 32], "estimator_rr": [1, 2, 3, 5, 8],
               "lanes_scenes": {"room.json": 192, "cornell.json": 192, "bunny.json": 48}, "lanes_size": 256,
               "lanes_repeats": 5}
    cfg["lanes_file"] = "lanes"
    mesh_flags = ((["--quick"] if args.quick else []) +
                  (["--repeats", str(args.mesh_repeats)] if args.mesh_repeats else []))
    if args.lanes_short:
        cfg.update({"lanes_scenes": {"room.json": 32, "cornell.json": 32, "bunny.json": 8}, "lanes_size": 128,
                    "lanes_flag": " --lanes-short"})
    if args.lanes_megakernel:
        eight_against_sixteen(cfg, "megakernel", {"room.json": 32, "cornell.json": 32})
    if args.lanes_wavefront:
        eight_against_sixteen(cfg, "wavefront", {"room.json": 32, "cornell.json": 32, "bunny.json": 8})
    os.makedirs(args.out, exist_ok=True)
    start = time.time()
    with tempfile.TemporaryDirectory(prefix="wavepath-bench-") as scratch:
        os.environ.setdefault("WAVEPATH_CACHE_DIR", os.path.join(args.out, "program-cache"))
        runner = Runner(os.path.abspath(args.binary), scratch)
        peer = MitsubaPeer()
        results = {"mode": "quick" if args.quick else "full", "config": cfg,
                   "meta": run_meta(os.path.abspath(args.binary), peer)}
        for study, run in (("throughput", lambda: throughput(runner, peer, cfg)),
                           ("scaling", lambda: scaling(runner, cfg)),
                           ("accuracy", lambda: accuracy(runner, peer, cfg, args.out)),
                           ("meshes", lambda: meshes(os.path.abspath(args.mesh_bench), mesh_flags, args.out)),
                           ("estimators", lambda: estimators(runner, peer, cfg, args.out)),
                           ("embree", lambda: wavefront_embree(os.path.abspath(args.mesh_bench), mesh_flags,
                                                               args.out)),
                           ("lanes", lambda: lanes(runner, cfg))):
            if study in series:
                results[study] = run()
    results["elapsed_s"] = time.time() - start
    with open(os.path.join(args.out, "results.json"), "w") as f:
        json.dump(results, f, indent=1)
    for study in ("throughput", "scaling"):
        if study in results:
            write_csv(os.path.join(args.out, f"{study}.csv"), results[study])
    if "accuracy" in results:
        write_csv(os.path.join(args.out, "accuracy.csv"), results["accuracy"]["rows"])
        write_csv(os.path.join(args.out, "accuracy_vs_mitsuba.csv"), results["accuracy"]["peer"])
    if "meshes" in results:
        write_csv(os.path.join(args.out, "meshes.csv"), mesh_rows(results["meshes"]))
        with open(os.path.join(args.out, "meshes.md"), "w") as f:
            f.write(meshes_markdown(results["meshes"]))
    if "embree" in results:
        with open(os.path.join(args.out, "wavefront_embree.md"), "w") as f:
            f.write(wavefront_embree_markdown(results["embree"]))
    if "estimators" in results:
        write_csv(os.path.join(args.out, "estimators.csv"), results["estimators"])
        with open(os.path.join(args.out, "estimators.md"), "w") as f:
            f.write(estimators_markdown(results["estimators"], results["meta"], cfg["converged_spp"]))
    if "lanes" in results:
        with open(os.path.join(args.out, f"{cfg['lanes_file']}.json"), "w") as f:
            json.dump({"meta": results["meta"], "config": {k: v for k, v in cfg.items() if k.startswith("lanes")},
                       "rows": results["lanes"]}, f, indent=1)
        with open(os.path.join(args.out, f"{cfg['lanes_file']}.md"), "w") as f:
            f.write(lanes_markdown(results["lanes"], results["meta"], cfg))
    plots = plot(args.out, results) if all(k in results for k in ("throughput", "scaling", "accuracy")) else []
    with open(os.path.join(args.out, "summary.md"), "w") as f:
        f.write(summary(results, plots))
    print(f"bench: wrote {args.out}/summary.md in {results['elapsed_s']:.0f} s")
    if args.check:
        failures = check(results)
        for failure in failures:
            print(f"bench: check failed: {failure}")
        sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
