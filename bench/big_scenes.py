#!/usr/bin/env python3
"""Big scenes against Mitsuba 3: load time, BVH build time, peak memory and render speed (issue 38, item 3).

Usage: python3 bench/big_scenes.py [--repeats 5] [--levels 2] [--pieces 500] [--baseline BINARY]
           [--out bench/results] [--binary build/wavepath] [--load-bench build/bench/load_bench]

Generates into a temporary directory (never committed), from the Stanford bunny of glmark2-data
(scenes/meshes/bunny.obj, 69,666 triangles):
  pieces: the bunny cut into --pieces OBJ files (consecutive runs of its triangles in a grid order of their
          centroids, each file with its own vertices), four diffuse materials in turn;
  big:    the bunny subdivided --levels times (each triangle into four at its edges' midpoints; 2 levels:
          1,114,656 triangles) as one binary PLY file, one diffuse material;
each as a wavepath JSON scene and a Mitsuba XML scene (constant environment light, 128x128, path tracing).

Measures, in --repeats interleaved repetitions (every configuration once per repetition, the load average
recorded before each):
  - wavepath, phase by phase (build/bench/load_bench, one process per run): a CPU device's path (the
    scene's load with its mesh files, the device's triangles without a BVH, the Embree intersector's build),
    then the path of the devices that trace with our BVH (its build and layout); resident memory after each,
    each path's peak, and the bytes of each structure that holds triangles; on the JSON scene and on the
    XML one;
  - wavepath end to end: `wavepath render` at 1 spp and 16x16 (load, BVH, kernel build from the cache, a
    trivial render): wall time and peak resident memory (wait4), with --baseline's binary beside it (the
    same command: e.g. the build before a change);
  - wavepath's render speed: samples/s of `wavepath render` at 128x128, 16 spp (its stats);
  - Mitsuba 3 (llvm_ad_rgb), one process per run: mitsuba.load_file's time, Embree's build within it (its
    log line "Embree ready. (took ...)"), peak resident memory after the load and at the end, and
    samples/s of a render at 128x128, 16 spp (after one unrecorded render: Dr.Jit compiles its kernels).
Writes big_scenes.json and big_scenes.md to --out.
"""
import argparse
import json
import os
import re
import statistics
import subprocess
import sys
import tempfile
import time

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from run import ROOT, machine, spread  # noqa: E402

BUNNY = os.path.join(ROOT, "scenes", "meshes", "bunny.obj")
SIZE, SPP = 128, 16
COLOURS = [(0.75, 0.75, 0.75), (0.75, 0.3, 0.2), (0.2, 0.35, 0.75), (0.3, 0.7, 0.3)]
LLVM = "/usr/lib/x86_64-linux-gnu/libLLVM-19.so"


# ---- the scenes ----

def read_obj(path):
    vertices, faces = [], []
    with open(path) as f:
        for line in f:
            if line.startswith("v "):
                vertices.append([float(x) for x in line.split()[1:4]])
            elif line.startswith("f "):
                faces.append([int(t.split("/")[0]) - 1 for t in line.split()[1:4]])
    return np.array(vertices, dtype=np.float64), np.array(faces, dtype=np.int64)


def subdivide(vertices, faces):
    """Each triangle into four at its edges' midpoints (shared midpoints made once)."""
    edges = np.sort(np.concatenate([faces[:, [0, 1]], faces[:, [1, 2]], faces[:, [2, 0]]]), axis=1)
    unique, inverse = np.unique(edges, axis=0, return_inverse=True)
    inverse = inverse.reshape(-1)
    midpoints = 0.5 * (vertices[unique[:, 0]] + vertices[unique[:, 1]])
    m = len(faces)
    ab, bc, ca = (inverse[:m] + len(vertices), inverse[m:2 * m] + len(vertices), inverse[2 * m:] + len(vertices))
    a, b, c = faces[:, 0], faces[:, 1], faces[:, 2]
    new_faces = np.concatenate([np.stack(t, axis=1) for t in
                                ((a, ab, ca), (ab, b, bc), (ca, bc, c), (ab, bc, ca))])
    return np.concatenate([vertices, midpoints]), new_faces


def write_obj(path, vertices, faces):
    with open(path, "w") as f:
        f.write("".join(f"v {x:.7g} {y:.7g} {z:.7g}\n" for x, y, z in vertices))
        f.write("".join(f"f {a + 1} {b + 1} {c + 1}\n" for a, b, c in faces))


def write_ply(path, vertices, faces):
    header = (f"ply\nformat binary_little_endian 1.0\nelement vertex {len(vertices)}\n"
              "property float x\nproperty float y\nproperty float z\n"
              f"element face {len(faces)}\nproperty list uchar int vertex_indices\nend_header\n")
    face_records = np.zeros(len(faces), dtype=[("n", "u1"), ("i", "<i4", (3,))])
    face_records["n"] = 3
    face_records["i"] = faces
    with open(path, "wb") as f:
        f.write(header.encode())
        f.write(vertices.astype("<f4").tobytes())
        f.write(face_records.tobytes())


def bunny_pieces(vertices, faces, count, directory):
    """`count` OBJ files of consecutive triangles in a grid order of their centroids; their names."""
    centroids = vertices[faces].mean(axis=1)
    cells = np.floor((centroids - centroids.min(axis=0)) / np.ptp(centroids, axis=0).max() * 7.999).astype(int)
    order = np.lexsort((cells[:, 2], cells[:, 1], cells[:, 0]))
    names = []
    for i, chunk in enumerate(np.array_split(order, count)):
        used, local = np.unique(faces[chunk], return_inverse=True)
        name = f"piece_{i:03d}.obj"
        write_obj(os.path.join(directory, name), vertices[used], local.reshape(-1, 3))
        names.append(name)
    return names


def json_scene(path, files):
    """files: [(file, material index)]."""
    scene = {
        "camera": {"position": [0, 0.3, 3.6], "look_at": [0, 0, 0], "up": [0, 1, 0], "fov_y": 35,
                   "width": SIZE, "height": SIZE},
        "render": {"spp": SPP, "max_depth": 4, "rr_depth": 5, "seed": 0},
        "background": [0.8, 0.8, 0.8],
        "materials": {f"m{i}": {"type": "diffuse", "albedo": list(c)} for i, c in enumerate(COLOURS)},
        "shapes": [{"type": "mesh", "file": f, "material": f"m{m}"} for f, m in files],
    }
    with open(path, "w") as f:
        json.dump(scene, f, indent=1)


def xml_scene(path, files):
    lines = ['<scene version="3.0.0">',
             '  <integrator type="path"><integer name="max_depth" value="5"/></integrator>',
             '  <sensor type="perspective">',
             '    <float name="fov" value="35"/><string name="fov_axis" value="y"/>',
             '    <transform name="to_world"><lookat origin="0, 0.3, 3.6" target="0, 0, 0" up="0, 1, 0"/></transform>',
             f'    <sampler type="independent"><integer name="sample_count" value="{SPP}"/></sampler>',
             f'    <film type="hdrfilm"><integer name="width" value="{SIZE}"/><integer name="height" value="{SIZE}"/>'
             '<rfilter type="box"/></film>',
             '  </sensor>',
             '  <emitter type="constant"><rgb name="radiance" value="0.8, 0.8, 0.8"/></emitter>']
    for i, c in enumerate(COLOURS):
        lines.append(f'  <bsdf type="diffuse" id="m{i}"><rgb name="reflectance" value="{c[0]}, {c[1]}, {c[2]}"/></bsdf>')
    for f, m in files:
        kind = os.path.splitext(f)[1][1:]
        lines.append(f'  <shape type="{kind}"><string name="filename" value="{f}"/>'
                     f'<boolean name="face_normals" value="true"/><ref id="m{m}"/></shape>')
    lines.append('</scene>')
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")


def generate(directory, pieces, levels):
    """The two scenes: {name: {"json", "xml", "files", "triangles"}}."""
    vertices, faces = read_obj(BUNNY)
    scenes = {}
    os.makedirs(os.path.join(directory, "pieces"))
    names = bunny_pieces(vertices, faces, pieces, os.path.join(directory, "pieces"))
    files = [(f"pieces/{n}", i % len(COLOURS)) for i, n in enumerate(names)]
    scenes["pieces"] = {"files": len(files), "triangles": len(faces)}
    big_v, big_f = vertices, faces
    for _ in range(levels):
        big_v, big_f = subdivide(big_v, big_f)
    write_ply(os.path.join(directory, "big.ply"), big_v, big_f)
    scenes["big"] = {"files": 1, "triangles": len(big_f)}
    for name, scene_files in (("pieces", files), ("big", [("big.ply", 0)])):
        scenes[name]["json"] = os.path.join(directory, f"{name}.json")
        scenes[name]["xml"] = os.path.join(directory, f"{name}.xml")
        json_scene(scenes[name]["json"], scene_files)
        xml_scene(scenes[name]["xml"], scene_files)
    return scenes


# ---- the measurements ----

def timed_child(args, env=None):
    """Runs a command to its end: (stdout, stderr, wall seconds, peak resident bytes: the largest of it and the
    children it waited for). The peak comes from /usr/bin/time, a small process: Linux carries a process's
    ru_maxrss across exec, so a child started from this one (hundreds of MiB of meshes) would report this
    one's."""
    with tempfile.NamedTemporaryFile("r", prefix="wavepath-bench-time-") as peak_file:
        start = time.perf_counter()
        done = subprocess.run(["/usr/bin/time", "-f", "%M", "-o", peak_file.name, *args], capture_output=True,
                              text=True, env=env, cwd=ROOT)
        wall = time.perf_counter() - start
        if done.returncode != 0:
            raise RuntimeError(f"{args[0]} failed ({done.returncode}): {done.stderr.strip()[-2000:]}")
        peak = int(peak_file.read().split()[-1]) * 1024
    return done.stdout, done.stderr, wall, peak


def wavepath_phases(load_bench, scene):
    stdout, _, wall, _ = timed_child([load_bench, scene])
    result = json.loads(stdout)
    result["wall_s"] = wall
    return result


def wavepath_end_to_end(binary, scene, scratch, cache):
    env = {**os.environ, "WAVEPATH_CACHE_DIR": cache}
    args = [binary, "render", scene, "-o", os.path.join(scratch, "tiny.pfm"), "-q", "--spp", "1", "--width", "16",
            "--height", "16"]
    _, _, wall, peak = timed_child(args, env)
    return {"wall_s": wall, "peak_bytes": peak}


def wavepath_render(binary, scene, scratch, cache):
    env = {**os.environ, "WAVEPATH_CACHE_DIR": cache}
    stats = os.path.join(scratch, "stats.json")
    args = [binary, "render", scene, "-o", os.path.join(scratch, "image.pfm"), "-q", "--stats-json", stats]
    _, _, wall, peak = timed_child(args, env)
    with open(stats) as f:
        s = json.load(f)
    return {"wall_s": wall, "peak_bytes": peak, "samples_per_s": s["samples_per_s"], "render_s": s["time_s"]}


MITSUBA_CHILD = r"""
import json, sys, time
import mitsuba as mi


def peak_bytes():  # VmHWM: this process's own peak (ru_maxrss would carry a parent's across exec)
    with open("/proc/self/status") as f:
        return next(int(line.split()[1]) * 1024 for line in f if line.startswith("VmHWM:"))



mi.set_variant("llvm_ad_rgb")
mi.set_log_level(mi.LogLevel.Info)
start = time.perf_counter()
scene = mi.load_file(sys.argv[1])
load_s = time.perf_counter() - start
after_load = peak_bytes()
mi.render(scene, seed=1).numpy()
start = time.perf_counter()
image = mi.render(scene, seed=0).numpy()
render_s = time.perf_counter() - start
samples = image.shape[0] * image.shape[1] * scene.sensors()[0].sampler().sample_count()
print("RESULT " + json.dumps({"load_s": load_s, "peak_after_load_bytes": after_load, "render_s": render_s,
                              "samples_per_s": samples / render_s,
                              "peak_bytes": peak_bytes()}))
"""


def duration_s(text):
    """Mitsuba's time_string: "12ms", "1.5s", "3m", "250us"."""
    match = re.fullmatch(r"([0-9.]+)\s*(us|ms|s|m|h)", text.strip())
    scale = {"us": 1e-6, "ms": 1e-3, "s": 1.0, "m": 60.0, "h": 3600.0}[match.group(2)]
    return float(match.group(1)) * scale


def mitsuba_run(scene):
    env = {**os.environ, "DRJIT_LIBLLVM_PATH": LLVM}
    stdout, stderr, wall, peak = timed_child([sys.executable, "-c", MITSUBA_CHILD, scene], env)
    text = stdout + stderr
    result = json.loads(next(line[7:] for line in text.splitlines() if line.startswith("RESULT ")))
    embree = re.search(r"Embree ready\. \(took ([^)]+)\)", text)
    result["embree_s"] = duration_s(embree.group(1)) if embree else None
    result["wall_s"] = wall
    return result


def measure(args, scenes, scratch):
    cache = os.path.join(scratch, "program-cache")
    baseline_cache = os.path.join(scratch, "baseline-program-cache")
    configurations = []
    for name, scene in scenes.items():
        configurations += [
            (name, "wavepath phases (JSON)", lambda s=scene: wavepath_phases(args.load_bench, s["json"])),
            (name, "wavepath phases (XML)", lambda s=scene: wavepath_phases(args.load_bench, s["xml"])),
            (name, "wavepath end to end", lambda s=scene: wavepath_end_to_end(args.binary, s["json"], scratch, cache)),
            (name, "wavepath render", lambda s=scene: wavepath_render(args.binary, s["json"], scratch, cache)),
            (name, "mitsuba", lambda s=scene: mitsuba_run(s["xml"])),
        ]
        if args.baseline:
            configurations.append((name, "baseline end to end", lambda s=scene: wavepath_end_to_end(
                args.baseline, s["json"], scratch, baseline_cache)))
    # One unrecorded round: kernel caches, Dr.Jit's cache, the page cache.
    for _, _, run in configurations:
        run()
    runs = {(name, what): [] for name, what, _ in configurations}
    for repetition in range(args.repeats):
        for name, what, run in configurations:
            load = os.getloadavg()[0]
            runs[(name, what)].append({**run(), "load": load})
            print(f"bench: {name} {what} repetition {repetition}", file=sys.stderr)
    return runs


# ---- the report ----

def ratio_spread(numerators, denominators):
    """Repetition by repetition: numerator / denominator (taken side by side), min and median."""
    ratios = [n / d for n, d in zip(numerators, denominators)]
    return {"min": min(ratios), "median": statistics.median(ratios)}


def fmt(spread_, form="{:.3f}"):
    return f"{form.format(spread_['min'])} / {form.format(spread_['median'])}"


def summarise(scenes, runs, has_baseline):
    summary = {}
    for name, scene in scenes.items():
        phases = runs[(name, "wavepath phases (JSON)")]
        xml = runs[(name, "wavepath phases (XML)")]
        end = runs[(name, "wavepath end to end")]
        render = runs[(name, "wavepath render")]
        mitsuba = runs[(name, "mitsuba")]
        col = lambda rs, key: [r[key] for r in rs]  # noqa: E731
        s = {"files": scene["files"], "triangles": phases[0]["triangles"],
             "wavepath_load_s": spread(col(phases, "load_s")),
             "wavepath_xml_load_s": spread(col(xml, "load_s")),
             "wavepath_bvh_s": spread(col(phases, "bvh_s")),
             "wavepath_layout_s": spread(col(phases, "layout_s")),
             "wavepath_bvh_peak_bytes": spread(col(phases, "bvh_peak_bytes")),
             "wavepath_embree_s": spread(col(phases, "embree_s")),
             "wavepath_end_to_end_s": spread(col(end, "wall_s")),
             "wavepath_peak_bytes": spread(col(phases, "peak_bytes")),
             "wavepath_children_peak_bytes": spread(col(phases, "children_peak_bytes")),
             "wavepath_render_peak_bytes": spread(col(render, "peak_bytes")),
             "wavepath_samples_per_s": spread(col(render, "samples_per_s")),
             "mitsuba_load_s": spread(col(mitsuba, "load_s")),
             "mitsuba_peak_after_load_bytes": spread(col(mitsuba, "peak_after_load_bytes")),
             "mitsuba_peak_bytes": spread(col(mitsuba, "peak_bytes")),
             "mitsuba_samples_per_s": spread(col(mitsuba, "samples_per_s")),
             "load_ratio": ratio_spread(col(phases, "load_s"), col(mitsuba, "load_s")),
             "xml_load_ratio": ratio_spread(col(xml, "load_s"), col(mitsuba, "load_s")),
             "load_layout_embree_ratio": ratio_spread([p["load_s"] + p["layout_s"] + p["embree_s"]
                                                       for p in phases], col(mitsuba, "load_s")),
             "end_to_end_ratio": ratio_spread(col(end, "wall_s"), col(mitsuba, "load_s")),
             "speed_ratio": ratio_spread(col(render, "samples_per_s"), col(mitsuba, "samples_per_s")),
             "peak_ratio": ratio_spread(col(render, "peak_bytes"), col(mitsuba, "peak_bytes")),
             "memory": {k: v for k, v in phases[0].items() if k.endswith("_bytes") and isinstance(v, dict)},
             "resident": {k: phases[0][k] for k in ("resident_after_load", "resident_after_layout",
                                                    "resident_after_embree", "resident_added_by_bvh")},
             "load": spread([r["load"] for rs in (phases, xml, end, render, mitsuba) for r in rs])}
        embree = [r["embree_s"] for r in mitsuba if r["embree_s"] is not None]
        s["mitsuba_embree_s"] = spread(embree) if embree else None
        if has_baseline:
            base = runs[(name, "baseline end to end")]
            s["baseline_end_to_end_s"] = spread(col(base, "wall_s"))
            s["baseline_over_now"] = ratio_spread(col(base, "wall_s"), col(end, "wall_s"))
            s["baseline_end_to_end_ratio"] = ratio_spread(col(base, "wall_s"), col(mitsuba, "load_s"))
        summary[name] = s
    return summary


def markdown(result):
    meta, summary = result["meta"], result["summary"]
    mib = lambda b: b / 2**20  # noqa: E731
    lines = ["# Big scenes against Mitsuba 3", "",
             f"Generated by `python3 bench/big_scenes.py --repeats {result['repeats']}` (bench/big_scenes.py, "
             "bench/load_bench.cpp); do not edit by hand.", "",
             f"- commit `{meta['commit']}`, {meta['date']}",
             f"- machine: {meta['cpu']}, {meta['cores']} cores, shared with other work; load average "
             f"{result['load_before'][0]:.2f} {result['load_before'][1]:.2f} {result['load_before'][2]:.2f} before, "
             f"{result['load_after'][0]:.2f} {result['load_after'][1]:.2f} {result['load_after'][2]:.2f} after "
             "(1, 5, 15 min)",
             f"- OpenCL {meta['opencl_platform']} / {meta['opencl_device']}; {meta['mitsuba']} "
             "(DRJIT_LIBLLVM_PATH=" + LLVM + ")",
             f"- {result['repeats']} repetitions, interleaved (every configuration once per repetition) after one "
             "unrecorded round; min / median. Ratios are taken repetition by repetition, side by side.", "",
             "Scenes (generated in a temporary directory from glmark2-data's bunny): "
             f"**pieces**: the bunny cut into {summary['pieces']['files']} OBJ files "
             f"({summary['pieces']['triangles']:,} triangles, four materials in turn); **big**: the bunny subdivided "
             f"{result['levels']} times, one binary PLY file ({summary['big']['triangles']:,} triangles). "
             "Each as wavepath JSON and Mitsuba XML (constant environment, "
             f"{SIZE}x{SIZE}, {SPP} spp, path tracing).", "",
             "## Time", "",
             "wavepath load: the scene and its mesh files read and checked (load_bench, in one process: `load_scene`, "
             "or `load_mitsuba_scene` for the XML). A CPU device's render (Embree traces the meshes, no BVH is "
             "built): layout, the device's triangles in the scene's order (`mesh_layout`); Embree, the Embree "
             "intersector's own build. The devices that trace with our BVH (GPUs, the megakernel): "
             "`mesh_layout`: `build_bvh` (Embree's SAH builder, flattened) and the device's triangles and nodes. End "
             "to end: `wavepath render` at 1 spp, 16x16 on the CPU device (load, layout, Embree, kernels from "
             "the cache, a trivial render). Mitsuba: `mitsuba.load_file` (its Embree build included, given "
             "apart from its log).", "",
             "| scene | measure | wavepath (s) | Mitsuba (s) | wavepath / Mitsuba (min, median) |",
             "|---|---|---|---|---|"]
    for name, s in summary.items():
        lines += [
            f"| {name} | load (JSON) | {fmt(s['wavepath_load_s'])} | {fmt(s['mitsuba_load_s'])} | "
            f"{fmt(s['load_ratio'], '{:.2f}')} |",
            f"| {name} | load (the same XML) | {fmt(s['wavepath_xml_load_s'])} | {fmt(s['mitsuba_load_s'])} | "
            f"{fmt(s['xml_load_ratio'], '{:.2f}')} |",
            f"| {name} | layout (CPU device: no BVH) | {fmt(s['wavepath_layout_s'])} | | |",
            f"| {name} | Embree intersector build | {fmt(s['wavepath_embree_s'])} | "
            f"{fmt(s['mitsuba_embree_s']) if s['mitsuba_embree_s'] else 'n/a'} (Embree) | |",
            f"| {name} | load + layout + Embree | | {fmt(s['mitsuba_load_s'])} | "
            f"{fmt(s['load_layout_embree_ratio'], '{:.2f}')} |",
            f"| {name} | our BVH build + layout (GPUs, megakernel) | {fmt(s['wavepath_bvh_s'])} | "
            f"{fmt(s['mitsuba_embree_s']) if s['mitsuba_embree_s'] else 'n/a'} (Embree) | |",
            f"| {name} | end to end, 1 spp 16x16 | {fmt(s['wavepath_end_to_end_s'])} | {fmt(s['mitsuba_load_s'])} "
            f"(load_file) | {fmt(s['end_to_end_ratio'], '{:.2f}')} |"]
        if "baseline_end_to_end_s" in s:
            lines.append(f"| {name} | end to end, --baseline binary | {fmt(s['baseline_end_to_end_s'])} | "
                         f"{fmt(s['mitsuba_load_s'])} (load_file) | {fmt(s['baseline_end_to_end_ratio'], '{:.2f}')}"
                         f"; baseline / now {fmt(s['baseline_over_now'], '{:.2f}')} |")
    lines += ["", "## Render speed", "",
              f"| scene | wavepath samples/s | Mitsuba samples/s | wavepath / Mitsuba (min, median) |",
              "|---|---|---|---|"]
    for name, s in summary.items():
        lines.append(f"| {name} | {fmt(s['wavepath_samples_per_s'], '{:,.0f}')} | "
                     f"{fmt(s['mitsuba_samples_per_s'], '{:,.0f}')} | {fmt(s['speed_ratio'], '{:.2f}')} |")
    lines += ["", "## Memory", "",
              "Peak resident memory. wavepath phases: load_bench's own peak (VmHWM) on a CPU device's path "
              "(load, layout, Embree; its import helper apart, getrusage of its children) and, the peak reset "
              "with the scene loaded, on our BVH's path (build and layout); wavepath render: `wavepath render` at "
              "128x128, 16 spp (/usr/bin/time's %M: the largest of it and its children); Mitsuba: the "
              "process's VmHWM after load_file and at the end of its render (Python, Dr.Jit and the LLVM JIT "
              "included). Per triangle: the peak over the "
              "triangles, so a small scene's figure is mostly the process's base.", "",
              "| scene | measure | wavepath (MiB) | Mitsuba (MiB) | wavepath / Mitsuba (min, median) | "
              "wavepath B/triangle | Mitsuba B/triangle |", "|---|---|---|---|---|---|---|"]
    for name, s in summary.items():
        t = s["triangles"]
        lines += [
            f"| {name} | peak, load + layout + Embree (load_bench) | {mib(s['wavepath_peak_bytes']['median']):.0f} "
            f"(helper {mib(s['wavepath_children_peak_bytes']['median']):.0f}) | "
            f"{mib(s['mitsuba_peak_after_load_bytes']['median']):.0f} (after load_file) | | "
            f"{s['wavepath_peak_bytes']['median'] / t:.0f} | {s['mitsuba_peak_after_load_bytes']['median'] / t:.0f} |",
            f"| {name} | peak, load + our BVH + layout (load_bench) | "
            f"{mib(s['wavepath_bvh_peak_bytes']['median']):.0f} | | | "
            f"{s['wavepath_bvh_peak_bytes']['median'] / t:.0f} | |",
            f"| {name} | peak, render | {mib(s['wavepath_render_peak_bytes']['median']):.0f} | "
            f"{mib(s['mitsuba_peak_bytes']['median']):.0f} | {fmt(s['peak_ratio'], '{:.2f}')} | "
            f"{s['wavepath_render_peak_bytes']['median'] / t:.0f} | {s['mitsuba_peak_bytes']['median'] / t:.0f} |"]
    small, big = summary["pieces"], summary["big"]

    def marginal(key):
        """Bytes per triangle the big scene adds over the pieces scene (medians): the processes' bases cancel."""
        return (big[key]["median"] - small[key]["median"]) / (big["triangles"] - small["triangles"])
    lines += ["", "Per triangle beyond each process's base: (peak on big - peak on pieces) / (their difference in "
              "triangles), medians:", "",
              f"- load + layout + Embree: wavepath (load_bench) {marginal('wavepath_peak_bytes'):.0f} B, Mitsuba "
              f"(after load_file) {marginal('mitsuba_peak_after_load_bytes'):.0f} B",
              f"- load + our BVH + layout: wavepath (load_bench) {marginal('wavepath_bvh_peak_bytes'):.0f} B",
              f"- render: wavepath {marginal('wavepath_render_peak_bytes'):.0f} B, Mitsuba "
              f"{marginal('mitsuba_peak_bytes'):.0f} B",
              f"- wavepath's import helper and importers (their largest): "
              f"{marginal('wavepath_children_peak_bytes'):.0f} B"]
    lines += ["", "Where wavepath's memory goes (bytes per triangle, from the sizes of the structures; the "
              "big scene):", "", "| structure | bytes per triangle | MiB | held |", "|---|---|---|---|"]
    s = summary["big"]
    t = s["triangles"]
    held = {"positions": "the scene, to the end", "normals": "the scene, to the end",
            "indices": "the scene, to the end",
            "device_triangles": "the render: the Embree intersector's, which the device buffer uses in place",
            "device_normals": "the render, with shading normals", "device_uvs": "the render, with textures",
            "bvh_device_triangles": "our BVH's path: the render (device buffer)",
            "device_nodes": "our BVH's path: the render (device buffer)"}
    for group in s["memory"].values():
        for key, value in group.items():
            lines.append(f"| {key} | {value / t:.1f} | {mib(value):.1f} | {held.get(key, '')} |")
    r = s["resident"]
    lines += ["", f"Resident memory added by each phase of load_bench on the big scene: load "
              f"{mib(r['resident_after_load']):.0f} MiB, layout "
              f"{mib(r['resident_after_layout'] - r['resident_after_load']):.0f} MiB, Embree intersector "
              f"{mib(r['resident_after_embree'] - r['resident_after_layout']):.0f} MiB "
              f"({r['resident_after_embree'] / t:.0f} B per triangle in all); on our BVH's path, its build and "
              f"layout {mib(r['resident_added_by_bvh']):.0f} MiB.", ""]
    return "\n".join(lines)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--out", default=os.path.join(ROOT, "bench", "results"))
    parser.add_argument("--binary", default=os.path.join(ROOT, "build", "wavepath"))
    parser.add_argument("--load-bench", default=os.path.join(ROOT, "build", "bench", "load_bench"))
    parser.add_argument("--baseline", help="another wavepath binary, measured end to end beside this one")
    parser.add_argument("--repeats", type=int, default=5)
    parser.add_argument("--pieces", type=int, default=500)
    parser.add_argument("--levels", type=int, default=2)
    args = parser.parse_args()
    args.binary = os.path.abspath(args.binary)
    args.load_bench = os.path.abspath(args.load_bench)
    start = time.time()
    with tempfile.TemporaryDirectory(prefix="wavepath-big-scenes-") as scratch:
        scenes = generate(scratch, args.pieces, args.levels)
        load_before = os.getloadavg()
        runs = measure(args, scenes, scratch)
        load_after = os.getloadavg()
    import mitsuba
    meta = {"commit": subprocess.run(["git", "describe", "--always", "--dirty", "--abbrev=12"], capture_output=True,
                                     text=True, cwd=ROOT).stdout.strip(),
            "date": time.strftime("%Y-%m-%d %H:%M:%S UTC", time.gmtime()),
            "mitsuba": f"Mitsuba {mitsuba.__version__} llvm_ad_rgb", **machine(args.binary)}
    result = {"meta": meta, "repeats": args.repeats, "levels": args.levels, "load_before": load_before,
              "load_after": load_after, "summary": summarise(scenes, runs, bool(args.baseline)),
              "runs": {f"{k[0]}: {k[1]}": v for k, v in runs.items()}, "elapsed_s": time.time() - start}
    os.makedirs(args.out, exist_ok=True)
    with open(os.path.join(args.out, "big_scenes.json"), "w") as f:
        json.dump(result, f, indent=1)
    with open(os.path.join(args.out, "big_scenes.md"), "w") as f:
        f.write(markdown(result))
    print(f"bench: wrote {args.out}/big_scenes.md in {result['elapsed_s']:.0f} s")


if __name__ == "__main__":
    main()
