#!/usr/bin/env python3
"""The oracle's own sensitivity: wavepath's lights 3% too bright must fail it.

tests/oracle/mitsuba_oracle.py is only as good as the biases it detects. Here
wavepath renders each scene with every light 3% brighter (every emitter's
radiance, every glow, the background and every light at infinity or at a point times 1.03) and Mitsuba renders it
as it is, at the oracle's default settings (64 pixels, 8 seeds x 32 spp,
blocks of 16^2), and the two are compared as the oracle compares them,
against the |z| threshold of the oracle's default run over every shipped
scene (its Bonferroni correction). The test passes when the oracle fails
every scene given: a comparison that let 3% through would pass it.

By default the room (scenes/room.json), the scene whose whole image the
oracle resolves best (about 1.2% at its settings, so a 3% bias stands at
about 2.5 times the threshold; about 20 s). scripts/mitsuba_figures.py runs
it on every shipped scene for docs/mitsuba.md (--doc, --check-doc).

Usage: oracle_sensitivity_test.py --binary build/wavepath [--scenes a.json,b.json | --all] [--brighter 1.03]
       [--doc FILE | --check-doc FILE]; exit 0 when every scene fails the oracle, 1 when one passes it, 2 when
       Mitsuba is missing.
"""
import argparse
import json
import os
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import mitsuba_oracle  # noqa: E402
from mitsuba_oracle import FIRST_SEED, ROOT  # noqa: E402

DOC_BEGIN, DOC_END = "<!-- oracle-sensitivity:begin -->", "<!-- oracle-sensitivity:end -->"


def brighter_scene(path, factor, scratch):
    """A copy of the scene `path` in `scratch` with every light `factor` times as bright (its mesh and texture
    files named by absolute path, since the copy lies elsewhere): its path."""
    with open(path) as f:
        scene = json.load(f)
    scale = lambda rgb: [factor * c for c in rgb]  # noqa: E731
    for material in scene.get("materials", {}).values():
        for key in ("radiance", "emission"):
            if key in material:
                material[key] = scale(material[key])
    if "background" in scene:
        scene["background"] = scale(scene["background"])
    here = os.path.dirname(os.path.abspath(path))
    for light in scene.get("lights", []):
        if light["type"] == "envmap":
            light["scale"] = factor * light.get("scale", 1.0)
            light["filename"] = os.path.join(here, light["filename"])
        elif light["type"] in ("point", "spot"):
            light["intensity"] = scale(light.get("intensity", [1, 1, 1]))
        else:
            light["irradiance"] = scale(light.get("irradiance", [1, 1, 1]))
    for named in [*scene.get("shapes", []), *scene.get("textures", {}).values()]:
        if "file" in named:
            named["file"] = os.path.join(here, named["file"])
    copy = os.path.join(scratch, "brighter-" + os.path.basename(path))
    with open(copy, "w") as f:
        json.dump(scene, f)
    return copy


def sensitivity_table(report, factor, z_crit, tests, args, version):
    """The run's figures as the markdown lines of docs/mitsuba.md's sensitivity table."""
    lines = [f"Written by `scripts/mitsuba_figures.py` {mitsuba_oracle.run_description(args, version)}; wavepath's "
             f"lights x {factor:g}; the threshold of the oracle's run over every shipped scene, {tests} tests, "
             f"|z| <= {z_crit:.2f}.", "",
             "| scene | size | mean ratio wavepath/Mitsuba (R, G, B) | whole-image abs(z) | largest abs(z) | "
             "oracle | wavepath s | Mitsuba s |", "|---|---|---|---|---|---|---|---|"]
    for r in report:
        lines.append(f"| {r['scene']} | {r['width']}x{r['height']} | {', '.join(f'{v:.4f}' for v in r['ratio'])} | "
                     f"{', '.join(f'{v:.2f}' for v in r['z_whole'])} | {r['max_abs_z']:.2f} | "
                     f"{'fails' if r['max_abs_z'] > z_crit else 'passes'} | {r['wavepath_s']:.1f} | "
                     f"{r['mitsuba_s']:.1f} |")
    return lines


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    mitsuba_oracle.add_common_arguments(parser)
    scenes = parser.add_mutually_exclusive_group()
    scenes.add_argument("--scenes", default=os.path.join(ROOT, "scenes", "room.json"),
                        help="comma-separated scene files (default: scenes/room.json)")
    scenes.add_argument("--all", action="store_true", help="every shipped scene")
    parser.add_argument("--brighter", type=float, default=1.03, help="wavepath's lights times this")
    args = parser.parse_args()
    mi = mitsuba_oracle.open_mitsuba_or_explain(args.variant)
    if mi is None:
        return 2

    scenes = mitsuba_oracle.shipped_scenes() if args.all else args.scenes.split(",")
    seeds = list(range(FIRST_SEED, FIRST_SEED + args.seeds))
    z_crit, tests = mitsuba_oracle.critical_z(mitsuba_oracle.shipped_scenes(), args.size, args.block, args.alpha)
    print(f"oracle_sensitivity: wavepath's lights x {args.brighter:g} against Mitsuba's as given, {len(scenes)} "
          f"scenes, |z| <= {z_crit:.2f} (the oracle's over every shipped scene, {tests} tests)", flush=True)
    report, passed = [], []
    with tempfile.TemporaryDirectory(prefix="wavepath-oracle-sensitivity-") as scratch:
        for path in scenes:
            brighter = brighter_scene(path, args.brighter, scratch)
            row, failure = mitsuba_oracle.compare_scene(mi, path, args, seeds, z_crit, scratch, wavepath_scene=brighter)
            report.append(row)
            if failure is None:
                passed.append(row["scene"])
    if args.json:
        with open(args.json, "w") as f:
            json.dump({"brighter": args.brighter, "z_crit": z_crit, "tests": tests, "scenes": report}, f, indent=1)
    lines = sensitivity_table(report, args.brighter, z_crit, tests, args, mi.__version__)
    doc_agrees = mitsuba_oracle.finish_doc(args, DOC_BEGIN, DOC_END, lines, slice(0, 6))
    for scene in passed:
        print(f"oracle_sensitivity: FAIL {scene}: the oracle passes it with lights x {args.brighter:g}")
    print(f"oracle_sensitivity: {'FAILED' if passed else 'passed'} (the oracle failed "
          f"{len(scenes) - len(passed)} of {len(scenes)} scenes)")
    return 1 if passed or not doc_agrees else 0


if __name__ == "__main__":
    sys.exit(main())
