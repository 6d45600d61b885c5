#!/usr/bin/env python3
"""How much a busy machine slows each backend and Mitsuba 3, on the material-test scene (issue 36).

Usage: python3 bench/load_sensitivity.py [--binary build/wavepath] [--out bench/results] [--repeats 5]

bench/scenes/materials.json at 256x256, 64 spp, rendered by the default command, by the default with
--wavefront 262144 (4x the paths in flight, a quarter of the launches), by --backend megakernel (one launch per
pass) and by Mitsuba llvm_ad_rgb with its independent sampler: each without and then with one busy loop (a shell
`while :; do :; done`) beside it, every configuration once per repetition in turn. The efficiency bench's runs
are taken on a shared machine whose load moves; this says which of the renderers that load slows most, and why
the median speed ratio there moves more than the fastest renders' (bench/results/analysis.md, issue 36).
Writes load_sensitivity.json and load_sensitivity.md into --out.
"""
import os
import statistics
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from run import ROOT, spread  # noqa: E402
from study import generated_by, load_range, run_study, table  # noqa: E402

SCENE = os.path.join(ROOT, "bench", "scenes", "materials.json")
SIZE, SPP = 256, 64
CONFIGURATIONS = [
    {"name": "default", "extra": []},
    {"name": "--wavefront 262144", "extra": ["--wavefront", "262144"]},
    {"name": "--backend megakernel", "extra": ["--backend", "megakernel"]},
    {"name": "Mitsuba (independent)", "extra": None},
]
BUSY_LOOPS = (0, 1)


def render_time(runner, peer, configuration, seed):
    if configuration["extra"] is None:
        return peer.render(SCENE, SIZE, SPP, seed=seed)["time_s"]
    return runner.render(SCENE, None, SIZE, SIZE, SPP, extra=configuration["extra"], seed=seed)["time_s"]


def measure(runner, peer, args):
    for configuration in CONFIGURATIONS:  # compile and warm each once, unloaded
        render_time(runner, peer, configuration, seed=99)
    runs = {(c["name"], busy): [] for c in CONFIGURATIONS for busy in BUSY_LOOPS}
    for seed in range(args.repeats):
        for busy in BUSY_LOOPS:
            loops = [subprocess.Popen(["sh", "-c", "while :; do :; done"]) for _ in range(busy)]
            time.sleep(0.2)
            try:
                for configuration in CONFIGURATIONS:
                    load = os.getloadavg()[0]
                    runs[(configuration["name"], busy)].append(
                        {"time_s": render_time(runner, peer, configuration, seed), "load": load})
            finally:
                for loop in loops:
                    loop.kill()
                    loop.wait()
    rows = []
    for configuration in CONFIGURATIONS:
        name = configuration["name"]
        unloaded = [r["time_s"] for r in runs[(name, 0)]]
        loaded = [r["time_s"] for r in runs[(name, 1)]]
        rows.append({"configuration": name, "unloaded_s": spread(unloaded), "one_busy_loop_s": spread(loaded),
                     "slowdown_of_medians": statistics.median(loaded) / statistics.median(unloaded)})
    return {"rows": rows, "load": load_range([runs[key] for key in runs if key[1] == 0])}


def markdown(result):
    lines = ["# Load sensitivity (issue 36)", "",
             generated_by("load_sensitivity.py", result["meta"], result["load"]) +
             f" {result['repeats']} repetitions; `materials.json` at {SIZE}x{SIZE}, {SPP} spp; times are the "
             "renders' own (after the kernel build), min / median.", ""]
    lines += table(["configuration", "unloaded, s", "one busy loop beside it, s", "slowdown (medians)"],
                   [[r["configuration"], f"{r['unloaded_s']['min']:.3f} / {r['unloaded_s']['median']:.3f}",
                     f"{r['one_busy_loop_s']['min']:.3f} / {r['one_busy_loop_s']['median']:.3f}",
                     f"{r['slowdown_of_medians']:.2f}x"] for r in result["rows"]])
    return "\n".join(lines) + "\n"


if __name__ == "__main__":
    run_study(__doc__, "load_sensitivity", measure, markdown)
