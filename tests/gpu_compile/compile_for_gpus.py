#!/usr/bin/env python3
"""Compiles every kernel program wavepath's renderers can build for the shipped
and bench scenes for GPU targets, with clang-15: nvptx64 (NVIDIA) and amdgcn
(AMD), so that a change that breaks the kernels for GPU compilers fails
without a GPU (docs/architecture.md, "GPU targets").

The programs come from the renderers themselves: wavepath-kernel-programs
(tests/gpu_compile/list_kernel_programs.cpp) asks them, for every scene under
scenes/, bench/scenes/ and tests/gpu_compile/scenes/ (features no other scene
uses), which program each combination of the options that change one would
build, and lists each program once. A feature macro that no listed program
defines fails the check (its code would never be compiled here). Of programs
that differ only in their vector lane count (4, 8, 16), one is compiled, the
widths in turn (one_vector_width_each; --every-lane-width compiles them all).
Two passes, for each target:

  every program: its source as build_program hands it to the OpenCL compiler
    (the kernel files one after the other, each after a #line naming it),
    with its options, through clang's front end for the target
    (-fsyntax-only: parsed and checked with the target's types, builtins and
    extensions; no code generated, which would cost half as much again);
  the GPU defaults (what `wavepath render SCENE` builds on a GPU, with
    either backend): each kernel file of the program on its own (each
    includes what it uses), through the optimiser and the target's back end
    to PTX or AMDGPU assembly (-S).

A compilation that fails prints one line: FAIL, the target, the first error
(file:line: message), the pass, the options and what builds the program.
Exit status 0 when everything compiled, 1 when something did not, 2 when the
check could not run (no clang-15, a target missing from it, no scenes).
"""
import argparse
import concurrent.futures
import glob
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time

# (name, clang's target options). -nogpulib: no ROCm device library, which
# Debian's clang-15 lacks and OpenCL C needs none of (the builtins are clang's).
TARGETS = [
    ("nvptx64", ["-target", "nvptx64-nvidia-cuda", "-march=sm_70"]),
    ("amdgcn", ["-target", "amdgcn-amd-amdhsa", "-mcpu=gfx90a", "-nogpulib"]),
]

# The first error of a clang log, as "file:line: message".
ERROR = re.compile(r"^([^\s:][^:\n]*):(\d+):\d+: (?:fatal )?error: (.*)$", re.M)


def first_error(log):
    m = ERROR.search(log)
    if m:
        return f"{m.group(1)}:{m.group(2)}: {m.group(3)}"
    lines = [line for line in log.splitlines() if "error" in line]
    return (lines or log.splitlines() or ["(no output)"])[0].strip()


def scenes(source_dir):
    # tests/gpu_compile/scenes/: features no shipped or bench scene uses (coverage_problems).
    found = []
    for pattern in ("scenes/*.json", "scenes/*/*.json", "bench/scenes/*.json", "tests/gpu_compile/scenes/*.json"):
        found += sorted(glob.glob(os.path.join(source_dir, pattern)))
    return found


def coverage_problems(source_dir, programs):
    """The macros src/opencl/kernel_options.cpp can put in a program's options (the WP_ names in its string
    literals, as the test KernelOptions.ArchitectureDocListsEveryMacroTheyEmit reads them) that no listed
    program defines: code that this check would never compile."""
    with open(os.path.join(source_dir, "src", "opencl", "kernel_options.cpp")) as f:
        code = f.read()
    emitted = {name for literal in re.findall(r'"((?:[^"\\\n]|\\.)*)"', code)
               for name in re.findall(r"WP_[A-Z0-9_]+", literal)}
    defined = {name for program in programs for name in re.findall(r"-D(WP_[A-Z0-9_]+)", program["options"])}
    return [f"FAIL coverage: no program defines {name}, which src/opencl/kernel_options.cpp can emit: no scene "
            f"uses it; add one that does under tests/gpu_compile/scenes/" for name in sorted(emitted - defined)]


def check_clang(clang):
    path = shutil.which(clang)
    if not path:
        return f"{clang} not found (scripts/setup.sh installs clang-15)"
    listed = subprocess.run([path, "-print-targets"], capture_output=True, text=True).stdout
    missing = [name for name, _ in TARGETS if not re.search(rf"^\s*{name}\s", listed, re.M)]
    if missing:
        return f"{clang} has no {' or '.join(missing)} target"
    return None


def list_programs(lister, scene_files):
    run = subprocess.run([lister, *scene_files], capture_output=True, text=True)
    if run.returncode != 0:
        raise SystemExit(f"gpu_compile: {lister} failed: {run.stderr.strip()}")
    programs = []
    for line in run.stdout.splitlines():
        kind, files, options, what = line.split("\t")
        programs.append({"gpu_default": kind == "gpu-default", "files": files.split(), "options": options,
                         "what": what})
    return programs


def lanes(program):
    match = re.search(r"-DWP_LANES=(\d+)", program["options"])
    return int(match.group(1)) if match else 1


def one_vector_width_each(programs):
    """The programs, but of those that differ only in a vector lane count (4, 8 or 16), one: the widths taken in
    turn, so that each is compiled with about a third of the feature sets. The lane count changes only which
    vector types and builtins the lanes use (shared/prelude.h's WP_FOR_LANES, WP_LANE_VECTOR), the same for every
    feature set; one lane, the GPU defaults and programs with no vector twin are all kept. This halves the
    check's time (3248 programs to 1872 at b4c5f45)."""
    kept, twins = [], {}
    for program in programs:
        if program["gpu_default"] or lanes(program) == 1:
            kept.append(program)
            continue
        key = (tuple(program["files"]), re.sub(r"-DWP_LANES=\d+", "", program["options"]))
        twins.setdefault(key, []).append(program)
    for turn, group in enumerate(twins.values()):
        group.sort(key=lanes)
        kept.append(group[turn % len(group)])
    return kept


def kernel_directory(options):
    # build_program's -I names the kernel directory (compiler_options).
    words = options.split()
    return words[words.index("-I") + 1]


def program_source(program):
    # As build_from_source (src/opencl/program_cache.cpp) concatenates it.
    directory = kernel_directory(program["options"])
    text = ""
    for name in program["files"]:
        path = os.path.join(directory, name)
        with open(path) as f:
            text += f'#line 1 "{path}"\n' + f.read() + "\n"
    return text


def program_name(program):
    backend = "megakernel" if "megakernel.cl" in program["files"] else "wavefront"
    return f"the {backend}'s program ({' '.join(program['files'])})"


def write_logs(directory, clang, failed):
    # Each failing compilation's command, whole log and (for a program) source, to reproduce it by hand.
    os.makedirs(directory, exist_ok=True)
    for n, job in enumerate(failed):
        stem = os.path.join(directory, f"fail{n}_{job['target']}")
        source = job["input"]
        if job["mode"] != ["-S"]:
            shutil.copyfile(job["input"], stem + ".cl")
            source = stem + ".cl"
        command = [clang, "-x", "cl", job["options"], *job["target_options"], *job["mode"], source]
        with open(stem + ".log", "w") as f:
            f.write(" ".join(command) + "\n\n" + job["log"])


def compile_one(clang, job):
    command = [clang, "-x", "cl", *job["options"].split(), *job["target_options"], *job["mode"], "-o", os.devnull,
               job["input"]]
    start = time.monotonic()
    run = subprocess.run(command, capture_output=True, text=True)
    job["seconds"] = time.monotonic() - start
    job["ok"] = run.returncode == 0
    job["log"] = run.stderr
    return job


def defines(options):
    # The options but the ones build_program always passes (-cl-std, -I ...): what varies.
    words = options.split()
    return " ".join(w for w in words if w.startswith("-D"))


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--lister", required=True, help="the wavepath-kernel-programs executable")
    parser.add_argument("--source-dir", required=True, help="the source tree (its scenes/ and bench/scenes/)")
    parser.add_argument("--clang", default="clang-15")
    parser.add_argument("--jobs", type=int, default=2, help="compilations at once")
    parser.add_argument("--scene", action="append", help="only these scenes (default: every shipped and bench scene)")
    parser.add_argument("--every-lane-width", action="store_true",
                        help="compile each program at every vector lane count, not one per feature set")
    parser.add_argument("--log-dir", help="also write each failing compilation's whole log here")
    args = parser.parse_args()

    problem = check_clang(args.clang)
    if problem:
        print(f"gpu_compile: cannot run: {problem}", file=sys.stderr)
        return 2
    scene_files = args.scene or scenes(args.source_dir)
    if not scene_files:
        print(f"gpu_compile: cannot run: no scenes under {args.source_dir}", file=sys.stderr)
        return 2
    start = time.monotonic()
    programs = list_programs(args.lister, scene_files)
    # Only over every scene: --scene chooses fewer on purpose.
    uncovered = [] if args.scene else coverage_problems(args.source_dir, programs)
    listed = len(programs)
    if not args.every_lane_width:
        programs = one_vector_width_each(programs)

    with tempfile.TemporaryDirectory(prefix="wavepath-gpu-compile-") as scratch:
        jobs = []
        for index, program in enumerate(programs):
            source = os.path.join(scratch, f"program{index}.cl")
            with open(source, "w") as f:
                f.write(program_source(program))
            for target, target_options in TARGETS:
                jobs.append({"pass": "program, front end", "target": target, "target_options": target_options,
                             "mode": ["-fsyntax-only"], "input": source, "options": program["options"],
                             "what": program["what"], "unit": program_name(program)})
        seen = set()
        for program in programs:
            if not program["gpu_default"]:
                continue
            directory = kernel_directory(program["options"])
            for name in program["files"]:
                if (name, program["options"]) in seen:
                    continue
                seen.add((name, program["options"]))
                for target, target_options in TARGETS:
                    jobs.append({"pass": "kernel file to assembly", "target": target, "target_options": target_options,
                                 "mode": ["-S"], "input": os.path.join(directory, name),
                                 "options": program["options"], "what": program["what"], "unit": name})
        # The slow ones first, so that the two workers finish together.
        jobs.sort(key=lambda job: job["mode"] != ["-S"])
        with concurrent.futures.ThreadPoolExecutor(max_workers=max(1, args.jobs)) as pool:
            done = list(pool.map(lambda job: compile_one(args.clang, job), jobs))
        failed = [job for job in done if not job["ok"]]
        if failed and args.log_dir:
            write_logs(args.log_dir, args.clang, failed)

    for line in uncovered:
        print(line)
    for job in failed:
        print(f"FAIL {job['target']}: {first_error(job['log'])} [{job['pass']}: {job['unit']}; "
              f"options {defines(job['options'])}; built by {job['what']}]")
    # Many failures are usually one error in many programs: each error once, with its count.
    errors = {}
    for job in failed:
        key = (job["target"], first_error(job["log"]))
        errors[key] = errors.get(key, 0) + 1
    if len(failed) > len(errors):
        for (target, error), count in sorted(errors.items()):
            print(f"gpu_compile: {count} of the failures: {target}: {error}")
    programs_compiled = sum(1 for job in done if job["mode"] != ["-S"]) // len(TARGETS)
    files_compiled = sum(1 for job in done if job["mode"] == ["-S"]) // len(TARGETS)
    slowest = max(done, key=lambda job: job["seconds"])
    targets = " and ".join(name for name, _ in TARGETS)
    widths = sorted({lanes(program) for program in programs})
    front_end_s = sum(job["seconds"] for job in done if job["mode"] != ["-S"])
    assembly_s = sum(job["seconds"] for job in done if job["mode"] == ["-S"])
    print(f"gpu_compile: {len(scene_files)} scenes, {listed} programs listed, {programs_compiled} of them (lanes "
          f"{', '.join(map(str, widths))}) through the front end and "
          f"{files_compiled} kernel files of the GPU defaults to assembly, for {targets}: {len(done)} compilations "
          f"in {time.monotonic() - start:.0f} s with {args.jobs} jobs ({front_end_s:.0f} s in the front end, "
          f"{assembly_s:.0f} s to assembly; slowest {slowest['seconds']:.1f} s: "
          f"{slowest['unit']} for {slowest['target']}); {len(failed)} failed")
    return 1 if failed or uncovered else 0


if __name__ == "__main__":
    sys.exit(main())
