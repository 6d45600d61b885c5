#!/usr/bin/env python3
"""What starting a wavepath process costs: user + system CPU seconds of `wavepath version` and of a scene
that fails to parse (what every CLI call and every bad-input case pays before it does anything).

Usage: python3 bench/process_start.py [--binary build/wavepath] [--baseline BINARY] [--repeats 7] [--runs 10]

Each repetition runs every binary --runs times per command, interleaved; the figure of a repetition is the
mean CPU time of its runs (getrusage of the children). Prints min and median over repetitions, the ratio of
the medians against --baseline's binary, and the commit, date, machine and OpenCL platform.
"""
import argparse
import os
import resource
import statistics
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from run import ROOT, machine  # noqa: E402


def cpu_seconds(command, runs):
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    for _ in range(runs):
        subprocess.run(command, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return (after.ru_utime + after.ru_stime - before.ru_utime - before.ru_stime) / runs


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--binary", default=os.path.join(ROOT, "build", "wavepath"))
    parser.add_argument("--baseline", help="another build's wavepath, measured beside it")
    parser.add_argument("--repeats", type=int, default=7)
    parser.add_argument("--runs", type=int, default=10)
    args = parser.parse_args()
    binaries = {"binary": args.binary, **({"baseline": args.baseline} if args.baseline else {})}
    with tempfile.TemporaryDirectory() as scratch:
        bad_scene = os.path.join(scratch, "bad.json")
        with open(bad_scene, "w") as f:
            f.write("{ not json")
        commands = {"version": ["version"],
                    "scene error": ["render", bad_scene, "-o", os.path.join(scratch, "out.png")]}
        cpu = {(b, c): [] for b in binaries for c in commands}
        for _ in range(args.repeats):
            for command, extra in commands.items():
                for name, binary in binaries.items():
                    cpu[(name, command)].append(cpu_seconds([binary] + extra, args.runs))
    commit = subprocess.run(["git", "describe", "--always", "--dirty", "--abbrev=12"], capture_output=True,
                            text=True, cwd=ROOT).stdout.strip()
    print(f"commit {commit}, {subprocess.run(['date', '-u'], capture_output=True, text=True).stdout.strip()}")
    print(f"machine {machine(args.binary)}")
    for name, binary in binaries.items():
        source = subprocess.run(["git", "-C", os.path.dirname(os.path.abspath(binary)), "describe", "--always",
                                 "--dirty", "--abbrev=12"], capture_output=True, text=True).stdout.strip()
        print(f"{name}: {binary} (built from {source or 'an unknown commit'})")
    for command in commands:
        for name in binaries:
            values = cpu[(name, command)]
            print(f"{command:12s} {name:9s} CPU s per process: min {min(values):.4f}, median "
                  f"{statistics.median(values):.4f} ({args.repeats} repetitions of {args.runs})")
        if args.baseline:
            ratio = statistics.median(cpu[("baseline", command)]) / statistics.median(cpu[("binary", command)])
            print(f"{command:12s} baseline / binary, medians: {ratio:.1f}x")


if __name__ == "__main__":
    main()
