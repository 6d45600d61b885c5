#!/usr/bin/env python3
"""Adaptive sampling's efficiency (wavepath render --adaptive, docs/long-renders.md).

Usage: python3 bench/adaptive.py [--out bench/results] [--binary build/wavepath] [--cache DIR] [--repeats 5]

On room and cornell at 128x128 (the wavefront backend), renders without
adaptive sampling at 16, 64 and 256 spp and with --adaptive 0.2, 0.1 and 0.05
at up to 256 spp, interleaved, each --repeats times (seed = repetition), and
measures relMSE against Mitsuba's converged image (bench/run.py's truth, cached
in --cache). Writes adaptive.json and adaptive.md into --out, headed by the
commit, date, machine and OpenCL platform: per configuration the time (min,
median), the mean relMSE, the efficiency 1/(relMSE x median time), the image
mean over the truth's (adaptive sampling's stopping bias shows there), and
adaptive sampling's gain: its efficiency over the non-adaptive one at 256 spp
(equal spp cap), the non-adaptive relMSE at the same time (on the log-log
line through the non-adaptive renders) over its own (equal time), and the
non-adaptive relMSE at its mean spp over its own (equal samples: what the
placement of the samples gains, before the cost of rounds and checks).
"""
import os
import statistics

import numpy as np

from run import ROOT, loglog_at, rel_mse, scene_max_depth
from study import TIME_AND_RELMSE, cell, generated_by, interleaved, load_range, run_study, summary, table

SCENES = ["room.json", "cornell.json"]
SIZE, TRUTH_SPP = 128, 4096
PLAIN_SPP = [16, 64, 256]
THRESHOLDS = [0.2, 0.1, 0.05]
ADAPTIVE_SPP = 256


def configurations():
    for scene in SCENES:
        for spp in PLAIN_SPP:
            yield {"scene": scene, "adaptive": None, "spp": spp}
        for threshold in THRESHOLDS:
            yield {"scene": scene, "adaptive": threshold, "spp": ADAPTIVE_SPP}


def measure(runner, peer, args):
    truths = {}
    for scene in SCENES:
        path = os.path.join(ROOT, "scenes", scene)
        truths[scene] = peer.converged(path, SIZE, TRUTH_SPP, scene_max_depth(path), args.cache).image

    def measure_one(c, seed):
        extra = ["--adaptive", str(c["adaptive"])] if c["adaptive"] else []
        s = runner.render(os.path.join(ROOT, "scenes", c["scene"]), "wavefront", SIZE, SIZE, c["spp"], extra,
                          image=True, seed=seed)
        image = np.asarray(s["image"], dtype=np.float64)
        truth = truths[c["scene"]]
        return {"time_s": s["time_s"], "relmse": rel_mse(image, truth),
                "mean_ratio": float(image.mean() / truth.mean()),
                "spp_mean": s["adaptive"]["spp_mean"] if s.get("adaptive") else c["spp"],
                "stopped_early": s["adaptive"]["stopped_early"] if s.get("adaptive") else 0.0}

    configs = list(configurations())
    runs = interleaved(configs, args.repeats, measure_one)
    rows = []
    for c, r in zip(configs, runs):
        row = summary(c, r, ["relmse", "mean_ratio", "spp_mean", "stopped_early"])
        row["relmse_sd"] = statistics.stdev(x["relmse"] for x in r) if len(r) > 1 else 0.0
        row["efficiency"] = 1.0 / (row["relmse"] * row["time_s"]["median"])
        rows.append(row)
    for scene in SCENES:
        plain = [r for r in rows if r["scene"] == scene and not r["adaptive"]]
        line = sorted((r["time_s"]["median"], r["relmse"]) for r in plain)
        by_spp = sorted((r["spp"], r["relmse"]) for r in plain)
        cap = next(r for r in plain if r["spp"] == ADAPTIVE_SPP)
        for r in rows:
            if r["scene"] == scene and r["adaptive"]:
                r["gain_equal_spp_cap"] = r["efficiency"] / cap["efficiency"]
                equal_time = loglog_at(line, r["time_s"]["median"])
                r["gain_equal_time"] = equal_time / r["relmse"] if equal_time else None
                equal_samples = loglog_at(by_spp, r["spp_mean"])
                r["gain_equal_samples"] = equal_samples / r["relmse"] if equal_samples else None
    return {"rows": rows, "load": load_range(runs)}


def markdown(result):
    meta, rows = result["meta"], result["rows"]
    lines = ["# Adaptive sampling: efficiency", "",
             f"{generated_by('adaptive.py', meta, result.get('load'))} Wavefront backend, {SIZE}x{SIZE}, "
             f"{result['repeats']} interleaved repetitions (seed = repetition); truth: Mitsuba ({meta['mitsuba']}) "
             f"at {TRUTH_SPP} spp.", "",
             f"{TIME_AND_RELMSE}. Efficiency: 1 / (relMSE x median time). Gain at the "
             f"spp cap: efficiency over the non-adaptive render's at {ADAPTIVE_SPP} spp. Gain at equal time: the "
             "non-adaptive relMSE at the same median time (log-log line through the non-adaptive renders; blank "
             "outside them) over the adaptive one. Gain at equal samples: the non-adaptive relMSE at the adaptive "
             "render's mean spp (log-log line through the non-adaptive spp) over the adaptive one, what placing the "
             "samples gains before the cost of rounds and checks. Mean ratio: the image's mean over the truth's, "
             "averaged over the repetitions (adaptive sampling's stopping bias, docs/long-renders.md, shows here).", "",
             *table(["scene", "adaptive", "spp", "mean spp", "stopped early", "time min (s)", "time median (s)",
                     "relMSE", "efficiency", "gain at spp cap", "gain at equal time", "gain at equal samples",
                     "mean ratio"],
                    [[r["scene"], str(r["adaptive"] or "off"), str(r["spp"]), f"{r['spp_mean']:.1f}",
                      f"{100 * r['stopped_early']:.1f}%", f"{r['time_s']['min']:.3f}",
                      f"{r['time_s']['median']:.3f}", f"{r['relmse']:.4g}", f"{r['efficiency']:.4g}",
                      cell(r.get("gain_equal_spp_cap"), "{:.2f}x"), cell(r.get("gain_equal_time"), "{:.2f}x"),
                      cell(r.get("gain_equal_samples"), "{:.2f}x"), f"{r['mean_ratio']:.4f}"] for r in rows])]
    return "\n".join(lines) + "\n"


if __name__ == "__main__":
    run_study(__doc__, "adaptive", measure, markdown)
