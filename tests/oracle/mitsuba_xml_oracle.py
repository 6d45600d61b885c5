#!/usr/bin/env python3
"""Oracle test of the Mitsuba XML reader: Mitsuba 3 and wavepath render the same XML files alike.

The scenes of scenes/test/mitsuba/ exercise every element the reader supports
(docs/scene-format.md, "Mitsuba XML"): each transform step, each fov_axis,
$defaults set with -D, refs, includes, each shape, a serialized mesh (written
here with zlib, named through -D), the path integrator's depths. Mitsuba loads
each XML file itself (mi.load_file, the -D values as its parameters) and
wavepath reads it with its own reader (`wavepath render SCENE.xml -D ...`), so
an element the reader maps wrongly -- a mirrored image, a fov on the wrong
axis, a transform composed in the wrong order, a shape's front on the wrong
side -- shows as disagreement.

The statistics are tests/oracle/mitsuba_oracle.py's: per pixel the variance
over SEEDS renders, block means of BLOCK x BLOCK pixels and the whole image
compared per channel by z = difference / combined standard error, |z| below
the Bonferroni threshold of the whole run (false-failure rate ALPHA). The
scenes use a box pixel filter, so that pixels are independent in both
renderers as that method needs, but for filters.xml: there Mitsuba splats each
sample into the pixels its tent or gaussian reaches, so its pixels correlate
and the sum of their variances understates its blocks' variance, which errs
towards failing, not passing.

--write-docs writes the run's table into docs/scene-format.md, between
<!-- xml-oracle:begin --> and <!-- xml-oracle:end -->, with the commit, date
and Mitsuba's version: the docs' figures are those of a run.

Usage: mitsuba_xml_oracle.py --binary build/wavepath [--cases a,b] [--spp 32] [--seeds 8] [--block 16]
       [--alpha 1e-3] [--list] [--write-docs]
"""
import argparse
import datetime
import os
import re
import struct
import subprocess
import sys
import tempfile
import time
import zlib

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import mitsuba_oracle  # noqa: E402

ROOT = mitsuba_oracle.ROOT
SCENES = os.path.join(ROOT, "scenes", "test", "mitsuba")
# Float rounding between the renderers, relative: blocks of a constant environment seen directly have no noise.
ROUNDING = 1e-6

# (name, scene file, -D definitions): `{serialized}` stands for the serialized mesh written into the scratch folder.
CASES = [
    ("cornell_box", "cornell_box.xml", {}),
    ("fov_axis_x", "camera.xml", {"fov_axis": "x"}),
    ("fov_axis_y", "camera.xml", {"fov_axis": "y"}),
    ("fov_axis_diagonal", "camera.xml", {"fov_axis": "diagonal"}),
    ("fov_axis_smaller", "camera.xml", {"fov_axis": "smaller"}),
    ("fov_axis_larger", "camera.xml", {"fov_axis": "larger"}),
    ("shapes", "shapes.xml", {"serialized": "{serialized}"}),
    ("include_ref_dielectric", "materials.xml", {"max_depth": "8"}),
    ("metals_and_glass", "metals_and_glass.xml", {}),
    ("plastics", "plastics.xml", {}),
    ("filter_box", "filters.xml", {"filter": "box"}),
    ("filter_tent", "filters.xml", {"filter": "tent"}),
    ("filter_gaussian", "filters.xml", {"filter": "gaussian"}),
    ("textures", "textures.xml", {}),
    ("textured_materials", "textured_materials.xml", {}),
    ("normal_map", "normal_map.xml", {}),
    ("bump_map", "bump_map.xml", {}),
    ("mask", "mask.xml", {}),
    ("envmap", "envmap.xml", {}),
    ("point_light", "point_light.xml", {}),
    ("spot", "spot.xml", {}),
    ("anisotropic", "anisotropic.xml", {}),
]
# Cases compared in blocks of 8 x 8 rather than of --block: filters.xml's edges lie on those blocks' borders, so
# the light a filter spreads across them (the mean offset beyond 0: 0 for the box, r / 6 for a tent, s / sqrt(2 pi)
# for a gaussian) moves the blocks on either side by 1-3% of the contrast. (Pixel by pixel, the gaussian's far tail
# puts a handful of samples into a pixel 1.5 px from an edge: the spread over seeds is then no standard error.)
FILTER_CASES = {"filter_box", "filter_tent", "filter_gaussian"}


def block_of(name, args):
    return 8 if name in FILTER_CASES else args.block


def serialized_mesh_bytes():
    """A Mitsuba serialized file (version 4) of two meshes: 0, a unit square of two triangles in double
    precision with normals; 1, a tetrahedron in single precision without normals (Mitsuba smooths it)."""
    def mesh(flags, positions, normals, triangles, real):
        body = struct.pack("<I", flags) + b"mesh\0" + struct.pack("<QQ", len(positions), len(triangles))
        for p in positions:
            body += struct.pack("<3" + real, *p)
        for n in normals:
            body += struct.pack("<3" + real, *n)
        for t in triangles:
            body += struct.pack("<3I", *t)
        return struct.pack("<HH", 0x041C, 4) + zlib.compress(body)

    square = mesh(0x2001, [(-1, -1, 0), (1, -1, 0), (1, 1, 0), (-1, 1, 0)], [(0, 0, 1)] * 4,
                  [(0, 1, 2), (0, 2, 3)], "d")
    tetrahedron = mesh(0x1000, [(1, 1, 1), (1, -1, -1), (-1, 1, -1), (-1, -1, 1)], [],
                       [(0, 1, 2), (0, 3, 1), (0, 2, 3), (1, 3, 2)], "f")
    return square + tetrahedron + struct.pack("<QQI", 0, len(square), 2)


def defines_for(case_defines, serialized):
    return {k: v.replace("{serialized}", serialized) for k, v in case_defines.items()}


def film_size(mi, scene):
    size = scene.sensors()[0].film().size()
    return int(size[0]), int(size[1])


def compare_case(mi, name, scene_file, defines, args, seeds, z_crit, scratch):
    path = os.path.join(SCENES, scene_file)
    options = []
    for key, value in defines.items():
        options += ["-D", f"{key}={value}"]
    start = time.time()
    scene = mi.load_file(path, **defines)
    width, height = film_size(mi, scene)
    theirs = np.stack([np.array(mi.render(scene, seed=seed, spp=args.spp), dtype=np.float64) for seed in seeds])
    middle = time.time()
    ours = mitsuba_oracle.render_wavepath(args.binary, path, width, height, args.spp, seeds, scratch, options)
    end = time.time()
    z, mean_ours, mean_theirs, se = mitsuba_oracle.z_scores(ours, theirs, block_of(name, args), ROUNDING)
    ratio = mean_ours[-1] / mean_theirs[-1]
    detectable = z_crit * se[-1] / mean_theirs[-1]
    shown = ", ".join(f"{k}={v}" for k, v in defines.items() if k != "serialized")
    row = (f"| {name} | {scene_file}{', ' + shown if shown else ''} | {width}x{height} | "
           f"{', '.join(f'{r:.4f}' for r in ratio)} | {', '.join(f'{v:.2f}' for v in z[-1])} | {z.max():.2f} | "
           f"{100 * max(detectable):.2f}% |")
    print(f"{name}: {scene_file} {' '.join(f'-D {k}={v}' for k, v in defines.items() if k != 'serialized')} "
          f"{width}x{height}, whole-image ratio wavepath/Mitsuba {' '.join(f'{r:.4f}' for r in ratio)} (RGB), "
          f"|z| whole {' '.join(f'{v:.2f}' for v in z[-1])}, largest |z| {z.max():.2f}; detects a uniform bias of "
          f"{100 * max(detectable):.2f}%; Mitsuba {middle - start:.1f} s, wavepath {end - middle:.1f} s", flush=True)
    if z.max() <= z_crit:
        return row, None
    bad = [(int(b), "RGB"[c]) for b, c in zip(*np.nonzero(z > z_crit))]
    return row, f"{name}: {len(bad)} of {z.size} tests beyond |z| {z_crit:.2f} (block, channel: {bad[:8]})"


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--binary", default=os.path.join(ROOT, "build", "wavepath"))
    parser.add_argument("--cases", help="comma-separated case names (default: all)")
    parser.add_argument("--spp", type=int, default=32)
    parser.add_argument("--seeds", type=int, default=8)
    parser.add_argument("--block", type=int, default=16)
    parser.add_argument("--alpha", type=float, default=1e-3)
    parser.add_argument("--variant", default="llvm_ad_rgb")
    parser.add_argument("--list", action="store_true", help="list the cases and exit")
    parser.add_argument("--write-docs", action="store_true", help="write the run's table into docs/scene-format.md")
    args = parser.parse_args()
    cases = [c for c in CASES if not args.cases or c[0] in args.cases.split(",")]
    if args.list:
        for name, scene_file, defines in cases:
            print(name, scene_file, defines)
        return 0
    mi = mitsuba_oracle.open_mitsuba_or_explain(args.variant)
    if mi is None:
        return 2
    seeds = list(range(mitsuba_oracle.FIRST_SEED, mitsuba_oracle.FIRST_SEED + args.seeds))
    failures = []
    with tempfile.TemporaryDirectory(prefix="wavepath-xml-oracle-") as scratch:
        serialized = os.path.join(scratch, "meshes.serialized")
        with open(serialized, "wb") as f:
            f.write(serialized_mesh_bytes())
        tests = 0
        for name, scene_file, defines in cases:
            scene = mi.load_file(os.path.join(SCENES, scene_file), **defines_for(defines, serialized))
            tests += mitsuba_oracle.critical_z_for_sizes([film_size(mi, scene)], block_of(name, args), args.alpha)[1]
        z_crit = mitsuba_oracle.critical_z_for_tests(tests, args.alpha)
        print(f"mitsuba_xml_oracle: {len(cases)} cases, {tests} tests, {args.seeds} seeds x {args.spp} spp per "
              f"renderer; |z| <= {z_crit:.2f} (false-failure rate <= {args.alpha:g}, Bonferroni), Mitsuba "
              f"{mi.__version__} {args.variant}", flush=True)
        rows = []
        start = time.time()
        for name, scene_file, defines in cases:
            row, failure = compare_case(mi, name, scene_file, defines_for(defines, serialized), args, seeds, z_crit,
                                        scratch)
            rows.append(row)
            if failure:
                failures.append(failure)
    for failure in failures:
        print(f"mitsuba_xml_oracle: FAIL {failure}")
    print(f"mitsuba_xml_oracle: {'FAILED' if failures else 'passed'}")
    if args.write_docs:
        write_docs(rows, args, mi, tests, z_crit, time.time() - start, passed=not failures)
    return 1 if failures else 0


def write_docs(rows, args, mi, tests, z_crit, seconds, passed):
    """The run's table into docs/scene-format.md's xml-oracle block."""
    commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], capture_output=True, text=True, cwd=ROOT,
                            check=True).stdout.strip()
    dirty = subprocess.run(["git", "status", "--porcelain", "--untracked-files=no"], capture_output=True, text=True,
                           cwd=ROOT, check=True).stdout.strip()
    block = "\n".join([
        f"Run by `python3 tests/oracle/mitsuba_xml_oracle.py --binary build/wavepath --write-docs` on the sources of "
        f"`{commit}`{' (with uncommitted changes)' if dirty else ''}, "
        f"{datetime.datetime.now(datetime.timezone.utc):%Y-%m-%d}, on the 2-core development machine; Mitsuba "
        f"{mi.__version__} `{args.variant}`; {args.seeds} seeds × {args.spp} spp per renderer, blocks of "
        f"{args.block}^2 (8^2 for the filter cases); {tests} tests, |z| <= {z_crit:.2f}; "
        f"{'passed' if passed else 'FAILED'} in {seconds:.0f} s.",
        "",
        "| case | scene, -D | size | mean ratio wavepath/Mitsuba (R, G, B) | whole-image abs(z) | largest abs(z) | "
        "smallest uniform bias detected |",
        "|---|---|---|---|---|---|---|",
        *rows])
    path = os.path.join(ROOT, "docs", "scene-format.md")
    with open(path) as f:
        text = f.read()
    pattern = re.compile(r"(<!-- xml-oracle:begin -->\n).*?(\n<!-- xml-oracle:end -->)", re.S)
    if not pattern.search(text):
        sys.exit("mitsuba_xml_oracle: docs/scene-format.md has no xml-oracle block")
    with open(path + ".tmp", "w") as f:
        f.write(pattern.sub(lambda m: m.group(1) + block + m.group(2), text))
    os.replace(path + ".tmp", path)


if __name__ == "__main__":
    sys.exit(main())
