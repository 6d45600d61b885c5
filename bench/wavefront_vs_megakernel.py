#!/usr/bin/env python3
"""The wavefront's samples/s against the megakernel's, side by side, for one or more builds.

Usage: python3 bench/wavefront_vs_megakernel.py [--build LABEL=BINARY ...] [--repeats 5]
           [--scenes room.json:256:32,cornell.json:256:32,bunny.json:256:16] [--out bench/results/NAME]

Every repetition renders each scene with each build's wavefront and megakernel
(their default lanes and intersector), one after another, so that the machine's
load is shared out alike (interleaved); the first render of each configuration
is discarded (PoCL compiles each kernel for its launch geometry then). Per
scene and configuration it reports min and median samples/s, and the ratios
wavefront / megakernel of each build, and of each build's wavefront and
megakernel against the first build's, repetition by repetition. The load
average is recorded before and after every render. Writes NAME.json and
NAME.md, headed by the commit, date, machine and OpenCL platform.
"""
import argparse
import json
import os
import resource
import statistics
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from run import ROOT, machine, spread  # noqa: E402

BACKENDS = ("wavefront", "megakernel")


def render(binary, scene, backend, size, spp, scratch):
    stats_path = os.path.join(scratch, "stats.json")
    args = [binary, "render", os.path.join(ROOT, "scenes", scene), "-o", os.path.join(scratch, "image.pfm"), "-q",
            "--backend", backend, "--width", str(size), "--height", str(size), "--spp", str(spp),
            "--stats-json", stats_path]
    load_before = os.getloadavg()[0]
    cpu_before = children_cpu_s()
    subprocess.run(args, check=True, cwd=ROOT)
    cpu_s = children_cpu_s() - cpu_before
    with open(stats_path) as f:
        stats = json.load(f)
    return {"samples_per_s": stats["samples_per_s"], "time_s": stats["time_s"], "cpu_s": cpu_s,
            "samples_per_cpu_s": stats["samples"] / cpu_s, "load_before": load_before,
            "load_after": os.getloadavg()[0]}


def children_cpu_s():
    """CPU time (user and system) of the finished child processes so far."""
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime


def git(*args):
    return subprocess.run(["git", *args], capture_output=True, text=True, cwd=ROOT).stdout.strip()


def measure(builds, scenes, repeats):
    runs = {}  # (scene, build, backend) -> [render]
    with tempfile.TemporaryDirectory(prefix="wavepath-wf-mk-") as scratch:
        for scene, size, spp in scenes:  # warm-up, discarded
            for label, binary in builds:
                for backend in BACKENDS:
                    render(binary, scene, backend, size, spp, scratch)
        for _ in range(repeats):
            for scene, size, spp in scenes:
                for label, binary in builds:
                    for backend in BACKENDS:
                        runs.setdefault((scene, label, backend), []).append(
                            render(binary, scene, backend, size, spp, scratch))
    return runs


def rows_of(runs, builds, scenes):
    rows = []
    first = builds[0][0]
    for scene, size, spp in scenes:
        for label, _ in builds:
            for backend in BACKENDS:
                r = runs[(scene, label, backend)]
                rows.append({"scene": scene, "size": size, "spp": spp, "build": label, "what": backend,
                             **{f"msamples_s_{k}": v for k, v in spread([x["samples_per_s"] / 1e6 for x in r]).items()},
                             **{f"msamples_cpu_s_{k}": v
                                for k, v in spread([x["samples_per_cpu_s"] / 1e6 for x in r]).items()},
                             "load_median": statistics.median(x["load_before"] for x in r)})

        def ratios(a, b):  # repetition by repetition, of samples/s and of samples per CPU second
            return {f"{measure}_{k}": v for measure in ("samples_per_s", "samples_per_cpu_s")
                    for k, v in spread([x[measure] / y[measure] for x, y in zip(runs[a], runs[b])]).items()}

        for label, _ in builds:
            rows.append({"scene": scene, "build": label, "what": "wavefront/megakernel",
                         **ratios((scene, label, "wavefront"), (scene, label, "megakernel"))})
        for label, _ in builds[1:]:
            for backend in BACKENDS:
                rows.append({"scene": scene, "build": label, "what": f"{backend} / {first}'s",
                             **ratios((scene, label, backend), (scene, first, backend))})
    return rows


def markdown(meta, rows, repeats):
    lines = [f"# Wavefront against megakernel, samples/s ({meta['title']})", "",
             f"- Commit {meta['commit']}, {meta['date']}; builds: " +
             ", ".join(f"`{label}` = {desc}" for label, desc in meta["builds"].items()),
             f"- Machine: {meta['cpu']}, {meta['cores']} cores; OpenCL: {meta['opencl_platform']}; "
             f"device {meta['opencl_device']}",
             f"- {repeats} interleaved repetitions after one discarded warm-up render per configuration; "
             f"load average (1 min) {meta['load_start']:.2f} at the start, {meta['load_end']:.2f} at the end",
             "- Samples per CPU second: the render's samples over the CPU time (user and system) of its process, "
             "start-up included; on a machine shared with other work it is steadier than samples/s, whose wall "
             "time counts the other work's share of the cores",
             "", "| scene | build | backend | Msamples/s min | median | max | Msamples/CPU s min | median | max "
             "| load (median) |", "|---|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        if "msamples_s_min" in r:
            lines.append(f"| {r['scene']} {r['size']}x{r['size']} {r['spp']} spp | {r['build']} | {r['what']} | "
                         f"{r['msamples_s_min']:.3f} | {r['msamples_s_median']:.3f} | {r['msamples_s_max']:.3f} | "
                         f"{r['msamples_cpu_s_min']:.3f} | {r['msamples_cpu_s_median']:.3f} | "
                         f"{r['msamples_cpu_s_max']:.3f} | {r['load_median']:.1f} |")
    lines += ["", "Ratios, repetition by repetition:", "",
              "| scene | build | ratio | samples/s min | median | max | samples/CPU s min | median | max |",
              "|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        if "samples_per_s_min" in r:
            lines.append(f"| {r['scene']} | {r['build']} | {r['what']} | " + " | ".join(
                f"{r[f'{m}_{k}']:.3f}" for m in ("samples_per_s", "samples_per_cpu_s") for k in ("min", "median", "max"))
                + " |")
    return "\n".join(lines) + "\n"


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--build", action="append", default=[],
                    help="LABEL=BINARY[=DESCRIPTION]; the first is the one the others are compared with")
    ap.add_argument("--repeats", type=int, default=5)
    ap.add_argument("--scenes", default="room.json:256:32,cornell.json:256:32,bunny.json:256:16")
    ap.add_argument("--title", default="")
    ap.add_argument("--out", default=os.path.join(ROOT, "bench", "results", "wavefront_vs_megakernel"))
    args = ap.parse_args()
    builds, descriptions = [], {}
    for spec in args.build or [f"this=build/wavepath=the worktree's build"]:
        label, binary, *desc = spec.split("=", 2)
        builds.append((label, os.path.abspath(os.path.join(ROOT, binary))))
        descriptions[label] = desc[0] if desc else binary
    scenes = [(s, int(size), int(spp)) for s, size, spp in (x.split(":") for x in args.scenes.split(","))]
    load_start = os.getloadavg()[0]
    runs = measure(builds, scenes, args.repeats)
    meta = {"title": args.title, "commit": git("describe", "--always", "--dirty", "--abbrev=12"),
            "date": time.strftime("%Y-%m-%d %H:%M:%S UTC", time.gmtime()), "builds": descriptions,
            "load_start": load_start, "load_end": os.getloadavg()[0], **machine(builds[0][1])}
    rows = rows_of(runs, builds, scenes)
    with open(args.out + ".json", "w") as f:
        json.dump({"meta": meta, "rows": rows,
                   "runs": {" ".join(k): v for k, v in runs.items()}}, f, indent=1)
    text = markdown(meta, rows, args.repeats)
    with open(args.out + ".md", "w") as f:
        f.write(text)
    print(text)


if __name__ == "__main__":
    main()
