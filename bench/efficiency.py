#!/usr/bin/env python3
"""Efficiency of the default command against Mitsuba 3 (issue 21's first target).

Usage: python3 bench/efficiency.py [--binary build/wavepath] [--out bench/results] [--repeats 5]
                                   [--quiet-load 2.5] [--wait-s 1200] [--scenes room.json,cornell.json,bunny.json]
                                   [--name efficiency]
       python3 bench/efficiency.py --scenes materials.json --name efficiency_materials   (issue 36)

Efficiency is 1 / (relMSE x time): relMSE against Mitsuba's converged image of the scene (bench/mitsuba_peer.py,
cached in bench/out/converged-cache as bench/run.py caches them), less that image's own noise, and the render's
time. Measured per scene at 256x256 for:
- the default command, `wavepath render scene.json` with nothing but the size, spp and the outputs (and a seed per
  run: one image's relMSE is itself noisy, so each run renders other samples);
- the default command with --sampler independent (what its Sobol' points give, like for like);
- each explicit backend (--backend wavefront, megakernel, reference);
- Mitsuba llvm_ad_rgb with its independent sampler (the peer of the targets) and with each of its other samplers,
  to name its best for the scene.
Each repetition renders every configuration once, in turn (interleaved), with the load average taken before each
render. A configuration's efficiency is 1 / mean over runs of (relMSE x time), with the standard error of that
mean; its ratio to Mitsuba's is stated with the two errors combined, and also per repetition (min and median).
A scene is one of SCENE_SPP's, found in scenes/ or else in bench/scenes/ (the bench's own, such as issue 36's
material-test scene). Each scene's run ends with one profiled render of the default command (--profile-json): its
stages' device time per sample, what the time per sample is spent on.
Writes NAME.json and NAME.md (--name, default efficiency) into --out, headed by the commit, date, machine, OpenCL
platform and the command that reproduces them, and the targets met or not into the generated block of --out's
analysis.md that names NAME.json.
--quiet-load waits (up to --wait-s) for the 1-minute load average to fall below it before starting, and the
results say whether it did.
"""
import argparse
import json
import math
import os
import shlex
import statistics
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from mitsuba_peer import MitsubaPeer  # noqa: E402
from run import ROOT, Runner, rel_mse, rel_noise, run_meta, scene_max_depth, spread  # noqa: E402

SIZE = 256
# spp per run: a second or two each on a quiet 2-core machine (the whole run about half an hour on 2 shared
# cores); powers of four, which every Mitsuba sampler but `orthogonal` (a prime's square) takes as they are:
# `stratified` and `ldsampler` round other counts up to a power of four (32 to 36 and to 64), and a scrambled
# net's error per sample falls with the sample count, so samplers compared at different counts are not like
# for like. Each scene's table says what every configuration took.
SCENE_SPP = {"room.json": 64, "cornell.json": 64, "bunny.json": 16, "materials.json": 64}
DEFAULT_SCENES = "room.json,cornell.json,bunny.json"
# The issue whose targets a scene's run reads: issue 36's material-test scene (bench/scenes/materials.json: a
# textured floor, rough metal, plastic and glass under an environment map); the others issue 21's.
SCENE_ISSUE = {"materials.json": 36}
BACKEND_AUTO_SOURCE = "efficiency"  # the --name whose .json src/cli/backend_choice.cpp restates
CONVERGED_SPP = 4096
BACKENDS = ["wavefront", "megakernel", "reference"]  # the explicit ones, beside the default command; --backend auto ranks them
# Who --backend auto ranks first where two backends tie (neither has a clear lead, clear_lead): the wavefront, which
# takes every flag, then the megakernel; the reference, the independent renderer the others are checked against,
# last.
TIE_ORDER = ["wavefront", "megakernel", "reference"]
MITSUBA_SAMPLERS = ["independent", "stratified", "multijitter", "orthogonal", "ldsampler"]
PEER = "mitsuba-independent"  # what the targets are stated against
INDEPENDENT = "default-independent"  # the default command with --sampler independent: what the Sobol' points give


def load_average():
    return os.getloadavg()[0]


def wait_for_quiet(threshold, wait_s):
    """Polls the 1-minute load average each minute until it falls below `threshold` or `wait_s` passes."""
    start, seen = time.time(), []
    while True:
        seen.append(round(load_average(), 2))
        if seen[-1] < threshold or time.time() - start >= wait_s:
            return {"threshold": threshold, "waited_s": round(time.time() - start), "loads_seen": seen,
                    "quiet": seen[-1] < threshold}
        time.sleep(60)


def scene_path(scene):
    """A scene of SCENE_SPP: the shipped one (scenes/) or else the bench's own (bench/scenes/)."""
    for folder in (os.path.join(ROOT, "scenes"), os.path.join(ROOT, "bench", "scenes")):
        if os.path.exists(os.path.join(folder, scene)):
            return os.path.join(folder, scene)
    sys.exit(f"efficiency: {scene}: in neither scenes/ nor bench/scenes/")


def issue(scene):
    return SCENE_ISSUE.get(scene, 21)


def scene_has_meshes(path):
    with open(path) as f:
        return any(shape.get("type") == "mesh" for shape in json.load(f).get("shapes", []))


def intersector(estimator):
    """What traced the rays, as --intersector names it, from the film's estimator (opencl, opencl-embree,
    reference-embree, reference-float...)."""
    return "embree" if estimator.endswith("-embree") else "bvh"


def configurations():
    """(label, how): how is ("wavepath", backend or None for the default command, flags) or ("mitsuba", sampler,
    flags)."""
    return ([("default", ("wavepath", None, [])), (INDEPENDENT, ("wavepath", None, ["--sampler", "independent"]))] +
            [(b, ("wavepath", b, [])) for b in BACKENDS] +
            [(f"mitsuba-{s}", ("mitsuba", s, [])) for s in MITSUBA_SAMPLERS])


def measure_scene(runner, peer, scene, spp, repeats, cache):
    """Every configuration's runs on one scene, interleaved: relMSE (less the truth's noise), time, samples/s
    and the load average before the run."""
    path = scene_path(scene)
    truth = peer.converged(path, SIZE, CONVERGED_SPP, scene_max_depth(path), cache)
    noise = rel_noise(truth.variance, truth.image)
    runs = {label: [] for label, _ in configurations()}
    for repetition in range(repeats):
        for label, (renderer, what, flags) in configurations():
            load = load_average()
            if renderer == "mitsuba":
                r = peer.render(path, SIZE, spp, seed=repetition, sampler=what)
                backend, traced_by = "mitsuba " + what, None
            else:
                r = runner.render(path, what, SIZE, SIZE, spp, extra=flags, image=True, seed=repetition)
                backend, traced_by = r["backend"], intersector(r["estimator"])
            relmse = rel_mse(r["image"], truth.image) - noise
            runs[label].append({"repetition": repetition, "backend": backend, "intersector": traced_by,
                                "relmse": relmse,
                                "time_s": r["time_s"], "samples": r["samples"],
                                "samples_per_s": r["samples_per_s"], "load_average": round(load, 2),
                                "backend_choice": r.get("backend_choice")})
    profiled = runner.render(path, None, SIZE, SIZE, spp, profile=True, seed=repeats)
    return {"scene": scene, "spp": spp, "meshes": scene_has_meshes(path), "truth_spp": CONVERGED_SPP,
            "truth_noise_relmse": noise, "truth_file": os.path.basename(truth.file), "runs": runs,
            "profile": {"backend": profiled["backend"], "samples": profiled["samples"],
                        "time_s": profiled["time_s"], "profile": profiled["profile"]}}


def efficiency(runs):
    """1 / mean(relMSE x time) over the runs, its standard error, and per-run figures."""
    products = [r["relmse"] * r["time_s"] for r in runs]
    mean = statistics.mean(products)
    se = statistics.stdev(products) / math.sqrt(len(products))
    return {"efficiency": 1.0 / mean, "efficiency_rel_se": se / mean,
            "relmse_mean": statistics.mean(r["relmse"] for r in runs),
            "relmse_x_spp": statistics.mean(r["relmse"] * r["samples"] for r in runs) / SIZE ** 2,
            "spp_taken": sorted({round(r["samples"] / SIZE ** 2) for r in runs}),
            "time_s": spread([r["time_s"] for r in runs]),
            "msamples_s": spread([r["samples_per_s"] / 1e6 for r in runs]),
            "load_average": spread([r["load_average"] for r in runs]),
            "backends_run": sorted({r["backend"] + (f" with {r['intersector']}" if r["intersector"] else "")
                                    for r in runs})}


def ratio(a_runs, b_runs, a, b):
    """a's efficiency over b's: of the estimates, and per repetition (the two renders side by side, so the load's
    drift over the run cancels), with the standard error of the per-repetition ratios' mean."""
    per_repetition = [(rb["relmse"] * rb["time_s"]) / (ra["relmse"] * ra["time_s"]) for ra, rb in zip(a_runs, b_runs)]
    logs = [math.log(r) for r in per_repetition]
    return {"ratio": a["efficiency"] / b["efficiency"],
            "ratio_se": statistics.stdev(per_repetition) / math.sqrt(len(per_repetition)),
            "per_repetition": spread(per_repetition),
            "repetitions": len(logs), "log_mean": statistics.mean(logs),
            "log_se": statistics.stdev(logs) / math.sqrt(len(logs))}


def summarise(scene_runs):
    """Per scene: each configuration's efficiency and its ratio to Mitsuba's independent sampler; Mitsuba's best
    sampler; the wavefront's samples/s over the megakernel's; the explicit backends ranked by efficiency, each
    with its ratio over the next (the ranking --backend auto's table restates, src/cli/backend_choice.cpp)."""
    runs = scene_runs["runs"]
    configs = {label: efficiency(r) for label, r in runs.items()}
    for label, c in configs.items():
        c["vs_mitsuba"] = ratio(runs[label], runs[PEER], c, configs[PEER])
    samplers = [f"mitsuba-{s}" for s in MITSUBA_SAMPLERS]
    best_sampler = max(samplers, key=lambda label: configs[label]["efficiency"])
    wavefront_over_megakernel = [w["samples_per_s"] / m["samples_per_s"]
                                 for w, m in zip(runs["wavefront"], runs["megakernel"])]
    ranked = sorted(BACKENDS, key=lambda b: configs[b]["efficiency"], reverse=True)
    ranking = [{"backend": b, "intersector": runs[b][0]["intersector"],
                **({"over_next": ratio(runs[b], runs[n], configs[b], configs[n])} if n else {})}
               for b, n in zip(ranked, ranked[1:] + [None])]
    pairs = {f"{b}/{n}": ratio(runs[b], runs[n], configs[b], configs[n]) for b in BACKENDS for n in BACKENDS
             if b != n}
    sobol = {"efficiency": ratio(runs["default"], runs[INDEPENDENT], configs["default"], configs[INDEPENDENT]),
             "accuracy_per_sample": configs[INDEPENDENT]["relmse_x_spp"] / configs["default"]["relmse_x_spp"],
             "samples_s": spread([d["samples_per_s"] / i["samples_per_s"]
                                  for d, i in zip(runs["default"], runs[INDEPENDENT])])}
    return {"scene": scene_runs["scene"], "spp": scene_runs["spp"], "meshes": scene_runs["meshes"],
            "truth_spp": scene_runs["truth_spp"], "truth_noise_relmse": scene_runs["truth_noise_relmse"],
            "truth_file": scene_runs["truth_file"], "configurations": configs,
            "mitsuba_best_sampler": best_sampler.removeprefix("mitsuba-"),
            "wavefront_over_megakernel_samples_s": spread(wavefront_over_megakernel), "ranking": ranking,
            "sobol_over_independent": sobol,
            "backend_pairs": pairs, **({"profile": scene_runs["profile"]} if "profile" in scene_runs else {})}


# Student's t at 97.5% (one-sided) by degrees of freedom, for a lead's lower bound; beyond the table, the normal's.
T_975 = {1: 12.71, 2: 4.303, 3: 3.182, 4: 2.776, 5: 2.571, 6: 2.447, 7: 2.365, 8: 2.306, 9: 2.262}


def clear_lead(b, n, scenes):
    """b's efficiency over n's, at 97.5% confidence in each scene, above 1 in some scene of the situation and below
    1 in none: per scene, a one-sided t interval on the mean over repetitions of the log of the ratio, side by side.
    So a backend clearly faster in one scene and not clearly slower in the others leads: the faster path for the
    situation, though another scene ties. Where the two tie in every scene, each scene passes with chance 2.5%
    (with two scenes, a false lead about 5% of runs); a repetition disturbed by the machine's load widens an
    interval rather than decides."""
    def interval(pair):
        t = T_975.get(pair["repetitions"] - 1, 1.96)
        return pair["log_mean"] - t * pair["log_se"], pair["log_mean"] + t * pair["log_se"]

    bounds = [interval(s["backend_pairs"][f"{b}/{n}"]) for s in scenes]
    return any(low > 0.0 for low, _ in bounds) and not any(high < 0.0 for _, high in bounds)


def tie_ordered(ranked, scenes):
    """`ranked` with each tie settled by TIE_ORDER: a backend stays ahead of the one after it, where TIE_ORDER puts
    that one first, only with a clear lead over it (clear_lead)."""
    ranked = list(ranked)
    swapped = True
    while swapped:  # each swap puts a pair in TIE_ORDER's order, so this ends
        swapped = False
        for i, (b, n) in enumerate(zip(ranked, ranked[1:])):
            if TIE_ORDER.index(n) < TIE_ORDER.index(b) and not clear_lead(b, n, scenes):
                ranked[i], ranked[i + 1] = n, b
                swapped = True
    return ranked


def situations(scenes):
    """The ranking `--backend auto` restates, per situation (scenes with meshes or without): the explicit
    backends by the geometric mean over the situation's scenes of their efficiency over Mitsuba's (so that
    no one scene's scale weighs more), each with the range over those scenes of its per-repetition median
    efficiency over the next's. Where scenes disagree (a range across 1) the order is the mean's, but for ties:
    a backend ranks ahead of one that TIE_ORDER puts first only with a clear lead over it (clear_lead)."""
    result = []
    for meshes in sorted({s["meshes"] for s in scenes}):
        members = [s for s in scenes if s["meshes"] == meshes]

        def mean_over_mitsuba(backend):
            return math.exp(statistics.mean(math.log(s["configurations"][backend]["vs_mitsuba"]["ratio"])
                                            for s in members))

        ranked = tie_ordered(sorted(BACKENDS, key=mean_over_mitsuba, reverse=True), members)
        ranking = []
        for b, n in zip(ranked, ranked[1:] + [None]):
            entry = {"backend": b, "intersector": next(r["intersector"] for r in members[0]["ranking"]
                                                        if r["backend"] == b),
                     "over_mitsuba_geometric_mean": mean_over_mitsuba(b)}
            if n:
                medians = [s["backend_pairs"][f"{b}/{n}"]["per_repetition"]["median"] for s in members]
                entry["over_next_per_scene_median"] = {"low": min(medians), "high": max(medians)}
                entry["clear_lead_over_next"] = clear_lead(b, n, members)
            ranking.append(entry)
        result.append({"meshes": meshes, "scenes": [s["scene"] for s in members], "ranking": ranking})
    return result


def type_of(type_line):
    """'CPU' of `wavepath devices`' line 'type: CPU, compute units: 2, ...'."""
    return type_line.split(":", 1)[1].split(",", 1)[0].strip()


def device_type(binary):
    """The type (CPU, GPU...) `wavepath devices` gives device 0, the one run_meta names."""
    lines = subprocess.run([binary, "devices"], capture_output=True, text=True).stdout.splitlines()
    for i, line in enumerate(lines):
        if line.startswith("[0]"):
            return next((type_of(l) for l in lines[i + 1:] if l.strip().startswith("type:")), "")
    return ""


def issues(results):
    """The issues whose targets the run's scenes read, as the heading names them: "21", "21 and 36"."""
    return " and ".join(str(i) for i in sorted({issue(s["scene"]) for s in results["raw"]}))


def targets(results):
    """The targets of the scenes' issues read off the run: (text, met) pairs. Issue 21's and 36's: the default
    command at 1.5x Mitsuba's efficiency; issue 21's: the wavefront at 0.9x the megakernel's samples/s where no
    meshes."""
    lines = []
    for s in results["scenes"]:
        c = s["configurations"]
        d, m = c["default"], c[PEER]
        speed = d["msamples_s"]["median"] / m["msamples_s"]["median"]
        accuracy = m["relmse_x_spp"] / d["relmse_x_spp"]
        v, best = d["vs_mitsuba"], c["mitsuba-" + s["mitsuba_best_sampler"]]
        short = "" if v["per_repetition"]["median"] >= 1.5 else f", {1.5 / v['per_repetition']['median']:.2f}x short"
        lines.append((f"{s['scene']}: the default command ({', '.join(d['backends_run'])}) at {v['ratio']:.2f}x "
                      f"Mitsuba's efficiency (per repetition {v['per_repetition']['min']:.2f}-"
                      f"{v['per_repetition']['max']:.2f}, median {v['per_repetition']['median']:.2f}; target 1.5x"
                      f"{short}): "
                      f"{speed:.2f}x its samples/s (medians) times {accuracy:.2f}x its accuracy per sample "
                      f"(Mitsuba's relMSE x spp over ours); against Mitsuba's best sampler here, "
                      f"{s['mitsuba_best_sampler']}, {d['efficiency'] / best['efficiency']:.2f}x",
                      v["per_repetition"]["median"] >= 1.5))
    for s in results["scenes"]:
        if not s["meshes"] and issue(s["scene"]) == 21:
            w = s["wavefront_over_megakernel_samples_s"]
            short = "" if w["median"] >= 0.9 else f", {0.9 / w['median']:.2f}x short"
            lines.append((f"{s['scene']}: the wavefront at {w['median']:.2f}x the megakernel's samples/s (median per "
                          f"repetition, {w['min']:.2f}-{w['max']:.2f}; target 0.9x{short})", w["median"] >= 0.9))
    return lines


def markdown(results):
    m, command = results["meta"], results["command"]
    quiet = results["quiet"]
    loads = [r["load_average"] for s in results["raw"] for runs in s["runs"].values() for r in runs]
    lines = [f"# Efficiency against Mitsuba 3 (issue {issues(results)})", "",
             f"Generated by `{command}`; do not edit by hand.", "",
             f"- commit `{m['commit']}`, {m['date']}, {m['wavepath']} ({m['build_type']} build)",
             f"- machine: {m['cpu']}, {m['cores']} cores",
             f"- OpenCL: {m['opencl_platform']}; device {m['opencl_device']} ({results['device_type']})",
             f"- peer: {m['mitsuba']}; truth: Mitsuba's converged image at {CONVERGED_SPP} spp per scene",
             f"- load average (1 min) before each render: {min(loads):.2f}-{max(loads):.2f}, median "
             f"{statistics.median(loads):.2f}; waited {quiet['waited_s']} s for it to fall below "
             f"{quiet['threshold']} (seen: {', '.join(map(str, quiet['loads_seen']))}): "
             + ("it did." if quiet["quiet"] else "it did not; measured anyway, interleaved."),
             f"- {results['repeats']} repetitions; each renders every configuration once, in turn; "
             f"{results['elapsed_s']} s in all", "", f"## Issue {issues(results)}'s targets in this run", ""]
    lines += [f"- {'met' if met else 'NOT met'}: {text}." for text, met in targets(results)]
    lines += ["", "## Method", "",
             "Efficiency = 1 / (relMSE x time), estimated as 1 / mean over the runs of relMSE x time (each run its "
             "own seed), +- the standard error of that mean, relative. relMSE: mean over pixels and channels of "
             "(x - r)^2 / (r^2 + 0.01) against the truth r, less the truth's own noise. Time: the render's "
             "(wavepath's from --stats-json, device setup and kernel build left out; Mitsuba's `mi.render` and "
             "reading the image back, scene loading left out; each configuration's first render discarded). "
             "x Mitsuba: efficiency over Mitsuba's with its independent sampler (the target's peer): the ratio of "
             "the estimates, and per repetition (the two renders side by side) min / median / max with the "
             "standard error of their mean. relMSE x spp: the variance per "
             "sample, which speed does not change. `default` is `wavepath render scene.json` with only the "
             "size, spp, seed and outputs; its backend column is what it ran.", ""]
    for s in results["scenes"]:
        lines += [f"## {s['scene']} ({SIZE}x{SIZE}, {s['spp']} spp{', meshes' if s['meshes'] else ''})", "",
                  "| configuration | ran | efficiency (+- rel. se) | x Mitsuba | x Mitsuba per repetition "
                  "(min / median / max, +- se) | relMSE | relMSE x spp | time s (min / median) | "
                  "Msamples/s (min / median) | load |",
                  "|---|---|---|---|---|---|---|---|---|---|"]
        for label, c in s["configurations"].items():
            v, p, load = c["vs_mitsuba"], c["vs_mitsuba"]["per_repetition"], c["load_average"]
            lines.append(
                f"| {label} | {', '.join(c['backends_run'])} | {c['efficiency']:.4g} (+-{100 * c['efficiency_rel_se']:.0f}%) | "
                f"{v['ratio']:.2f} | {p['min']:.2f} / {p['median']:.2f} / {p['max']:.2f} (+-{v['ratio_se']:.2f}) | "
                f"{c['relmse_mean']:.4g} | {c['relmse_x_spp']:.4g} | {c['time_s']['min']:.3f} / "
                f"{c['time_s']['median']:.3f} | {c['msamples_s']['min']:.3f} / {c['msamples_s']['median']:.3f} | "
                f"{load['min']:.1f}-{load['max']:.1f} |")
        w = s["wavefront_over_megakernel_samples_s"]
        ranking = ", then ".join(
            r["backend"] + (f" ({r['over_next']['per_repetition']['median']:.2f}x the next's efficiency, per repetition "
                            f"{r['over_next']['per_repetition']['min']:.2f}-{r['over_next']['per_repetition']['max']:.2f}"
                            f", +-{r['over_next']['ratio_se']:.2f})" if "over_next" in r else "")
            for r in s["ranking"])
        best = s["configurations"]["mitsuba-" + s["mitsuba_best_sampler"]]
        g = s["sobol_over_independent"]
        asked = [label for label, c in s["configurations"].items() if c["spp_taken"] == [s["spp"]]]
        others = [f"{label} {', '.join(map(str, c['spp_taken']))}" for label, c in s["configurations"].items()
                  if c["spp_taken"] != [s["spp"]]]
        lines += ["", f"- Samples per pixel taken: {s['spp']} by {len(asked)} of the {len(s['configurations'])} "
                      f"configurations" + (f"; {', '.join(others)}." if others else ", every one.")]
        lines += [f"- The default command's Sobol' sampler over its independent numbers (`--sampler independent`): "
                      f"{g['efficiency']['ratio']:.2f}x the efficiency (per repetition "
                      f"{g['efficiency']['per_repetition']['min']:.2f} / {g['efficiency']['per_repetition']['median']:.2f}"
                      f" / {g['efficiency']['per_repetition']['max']:.2f}): {g['accuracy_per_sample']:.2f}x the "
                      f"accuracy per sample (relMSE x spp, independent's over Sobol's) at "
                      f"{g['samples_s']['median']:.2f}x the samples/s (per repetition {g['samples_s']['min']:.2f}-"
                      f"{g['samples_s']['max']:.2f}).",
                  f"- Mitsuba's most efficient sampler here: {s['mitsuba_best_sampler']} "
                      f"({best['vs_mitsuba']['ratio']:.2f}x its independent sampler's efficiency).",
                  f"- The wavefront's samples/s over the megakernel's, per repetition: {w['min']:.2f} (min), "
                  f"{w['median']:.2f} (median), {w['max']:.2f} (max).",
                  f"- The explicit backends by efficiency in this scene: {ranking}.", ""]
        if s.get("profile"):
            lines += profile_lines(s)
    restated = results["name"] == BACKEND_AUTO_SOURCE
    lines += ["## The ranking `--backend auto` restates" if restated else
              f"## The explicit backends ranked as `--backend auto` ranks them (it restates {BACKEND_AUTO_SOURCE}.md's, "
              "not this)", "",
              "Per situation, the explicit backends by the geometric mean over its scenes of their efficiency over "
              "Mitsuba's, each with the range over those scenes of its per-repetition median efficiency over the "
              "next's (" + ("src/cli/backend_choice.cpp restates it; " if restated else "") +
              "a range across 1 is a tie between the scenes). A "
              "backend's lead over the next is clear where, at 97.5% confidence per scene from the spread over "
              "repetitions, it is ahead in some scene and behind in none; otherwise the two tie and the order is "
              f"{', '.join(TIE_ORDER)}'s.",
              ""]
    for sit in results["situations"]:
        order = ", then ".join(
            f"{r['backend']} with {r['intersector']} ({r['over_mitsuba_geometric_mean']:.2f}x Mitsuba"
            + (f"; {r['over_next_per_scene_median']['low']:.2f}-{r['over_next_per_scene_median']['high']:.2f}x the "
               "next's" + ("" if r["clear_lead_over_next"] else ", a tie")
               if "over_next_per_scene_median" in r else "") + ")"
            for r in sit["ranking"])
        lines.append(f"- {'with' if sit['meshes'] else 'without'} meshes ({', '.join(sit['scenes'])}): {order}.")
    return "\n".join(lines) + "\n"


def profile_lines(s):
    """The profiled render's stages per sample, beside Mitsuba's whole time per sample."""
    p, prof = s["profile"], s["profile"]["profile"]
    samples = p["samples"]
    mitsuba_us = 1.0 / s["configurations"][PEER]["msamples_s"]["median"]
    default_us = 1.0 / s["configurations"]["default"]["msamples_s"]["median"]
    lines = [f"Where the default command's time goes: one render under `--profile-json` ({p['backend']}, "
             f"{samples / SIZE ** 2:.0f} spp, {prof['render_s']:.3f} s: {1e6 * prof['render_s'] / samples:.3f} us per "
             f"sample; unprofiled, median of the runs above: {default_us:.3f} us; Mitsuba's independent sampler: "
             f"{mitsuba_us:.3f} us). Device time per stage; items per sample: the rays or paths it took per camera "
             "sample.", "",
             "| stage | launches | items per sample | us per item | us per sample | share of the render |",
             "|---|---|---|---|---|---|"]
    for k in prof["kernels"]:
        lines.append(f"| {k['name']} | {k['launches']} | {k['items'] / samples:.3f} | "
                     f"{1e6 * k['device_s'] / max(k['items'], 1):.3f} | {1e6 * k['device_s'] / samples:.4f} | "
                     f"{100 * k['device_s'] / prof['render_s']:.1f}% |")
    for label, key in (("(between kernels)", "gaps_s"), ("(host, other)", "host_other_s")):
        lines.append(f"| {label} | | | | {1e6 * prof[key] / samples:.4f} | {100 * prof[key] / prof['render_s']:.1f}% |")
    return lines + [""]


ANALYSIS_END = "<!-- generated by bench/efficiency.py: end -->"


def analysis_begin(name):
    """The marker that opens the block of analysis.md written from NAME.json (each run's name has its own)."""
    return f"<!-- generated by bench/efficiency.py from {name}.json: begin -->"


def analysis_block(results):
    """The run's targets as analysis.md states them, with the run they come from."""
    m, name = results["meta"], results["name"]
    return "\n".join([f"From [{name}.md]({name}.md): commit `{m['commit']}`, {m['date']}, {m['cpu']}, "
                      f"{results['repeats']} interleaved repetitions.", ""] +
                     [f"- **{'met' if met else 'NOT met'}**: {text}." for text, met in targets(results)])


def write_analysis(results, path):
    """Replaces the generated block of analysis.md (between its markers) with this run's targets; an --out
    without an analysis.md (a scratch run) has none to replace."""
    if not os.path.exists(path):
        print(f"efficiency: no {path}: the targets are in {results['name']}.md alone", file=sys.stderr)
        return
    with open(path) as f:
        text = f.read()
    marker = analysis_begin(results["name"])
    begin = text.find(marker)
    end = text.find(ANALYSIS_END, begin)
    if begin < 0 or end < begin:
        sys.exit(f"efficiency: {path}: no block between '{marker}' and '{ANALYSIS_END}' to write")
    with open(path, "w") as f:
        f.write(text[:begin + len(marker)] + "\n" + analysis_block(results) + "\n" + text[end:])


def write_results(results, out):
    """The runs' summary into `results`, then NAME.json and NAME.md into `out`, and the targets into its
    analysis.md's generated block."""
    results["scenes"] = [summarise(s) for s in results["raw"]]
    results["situations"] = situations(results["scenes"])
    os.makedirs(out, exist_ok=True)
    with open(os.path.join(out, results["name"] + ".json"), "w") as f:
        json.dump(results, f, indent=1)
    with open(os.path.join(out, results["name"] + ".md"), "w") as f:
        f.write(markdown(results))
    write_analysis(results, os.path.join(out, "analysis.md"))


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--binary", default=os.path.join(ROOT, "build", "wavepath"))
    parser.add_argument("--out", default=os.path.join(ROOT, "bench", "results"))
    parser.add_argument("--cache", default=os.path.join(ROOT, "bench", "out", "converged-cache"),
                        help="converged Mitsuba images (shared with bench/run.py)")
    parser.add_argument("--repeats", type=int, default=5)
    parser.add_argument("--quiet-load", type=float, default=2.5)
    parser.add_argument("--wait-s", type=float, default=1200)
    parser.add_argument("--scenes", default=DEFAULT_SCENES, help=f"of {', '.join(SCENE_SPP)}")
    parser.add_argument("--name", default=BACKEND_AUTO_SOURCE,
                        help="the results' file name (NAME.json, NAME.md) and analysis.md's block")
    parser.add_argument("--summarise-again", action="store_true",
                        help="measure nothing: summarise --out's NAME.json's runs again into it and "
                             "NAME.md (after a change to this script's summary)")
    args = parser.parse_args()
    if args.summarise_again:
        with open(os.path.join(args.out, args.name + ".json")) as f:
            results = {"name": args.name, **json.load(f)}
        write_results(results, args.out)
        return
    unknown = [scene for scene in args.scenes.split(",") if scene not in SCENE_SPP]
    if unknown:
        sys.exit(f"efficiency: --scenes: {', '.join(unknown)}: not in SCENE_SPP ({', '.join(SCENE_SPP)})")
    command = "python3 bench/efficiency.py" + "".join(
        f" {flag} {shlex.quote(str(value))}" for flag, value, default in
        (("--repeats", args.repeats, 5), ("--scenes", args.scenes, DEFAULT_SCENES),
         ("--name", args.name, BACKEND_AUTO_SOURCE))
        if value != default)
    quiet = wait_for_quiet(args.quiet_load, args.wait_s)
    binary = os.path.abspath(args.binary)
    start = time.time()
    with tempfile.TemporaryDirectory(prefix="wavepath-efficiency-") as scratch:
        os.environ.setdefault("WAVEPATH_CACHE_DIR", os.path.join(ROOT, "bench", "out", "program-cache"))
        runner, peer = Runner(binary, scratch), MitsubaPeer()
        meta = run_meta(binary, peer)
        raw = [measure_scene(runner, peer, scene, SCENE_SPP[scene], args.repeats, args.cache)
               for scene in args.scenes.split(",")]
    results = {"name": args.name, "command": command, "meta": meta, "device_type": device_type(binary),
               "quiet": quiet, "repeats": args.repeats, "size": SIZE, "elapsed_s": round(time.time() - start),
               "raw": raw}
    write_results(results, args.out)
    print(f"efficiency: wrote {args.out}/{args.name}.md in {results['elapsed_s']} s")


if __name__ == "__main__":
    main()
