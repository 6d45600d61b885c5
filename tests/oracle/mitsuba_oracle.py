#!/usr/bin/env python3
"""Oracle test: every shipped scene rendered by wavepath and by Mitsuba 3 agrees.

This is the one test that shares no code with the estimator it checks: the
scene goes to Mitsuba through scripts/mitsuba_scene.py, and Mitsuba's `path`
integrator (its own sampling, intersection, BSDFs and emitters) renders it.
A bias in wavepath's estimator -- a light a few percent too bright, a wrong
Fresnel term, a pdf off by a factor -- shows as disagreement; noise does not.

For each scene, at most SIZE pixels on its longer side, both renderers render
SEEDS independent images (fixed seeds) of SPP samples each. Per pixel, the
variance of one image comes from the spread over the seeds; pixels are
independent (each sample lands in its own pixel in both renderers), so the
variance of a block's mean is the sum of its pixels' variances over the
block's pixel count squared, with (SEEDS - 1) x pixels degrees of freedom:
the standard error is estimated from the renders themselves, and the normal
quantile is then exact enough. For every block (BLOCK x BLOCK pixels) and the
whole image, and every channel,

    z = (mean_wavepath - mean_mitsuba) / sqrt(se_wavepath^2 + se_mitsuba^2)

must satisfy |z| <= z_crit, where z_crit makes the false-failure rate of the
whole run at most ALPHA (Bonferroni over every block, channel and scene:
z_crit = Phi^-1(1 - ALPHA / (2 tests))). With the defaults ALPHA = 1e-3:
one run in a thousand fails by chance, at most.

Prints, per scene, the whole-image mean ratio per channel, the largest |z|,
and the smallest uniform bias the whole-image test detects (z_crit standard
errors, relative to the mean); exit 1 when any test fails, 2 when Mitsuba is
missing.

The oracle's own sensitivity (it fails when wavepath's lights are 3% too
bright) is tests/oracle/oracle_sensitivity_test.py's; scripts/mitsuba_figures.py
writes both runs' figures into docs/mitsuba.md (--doc) or compares them with
it (--check-doc).

Usage: mitsuba_oracle.py --binary build/wavepath [--scenes a.json,b.json] [--size 64] [--block 16]
       [--spp 32] [--seeds 8] [--alpha 1e-3] [--json FILE] [--doc FILE | --check-doc FILE]
"""
import argparse
import glob
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "scripts"))
import mitsuba_scene  # noqa: E402

FIRST_SEED = 1000  # the seeds used are FIRST_SEED .. FIRST_SEED + seeds - 1, in both renderers
DOC_BEGIN, DOC_END = "<!-- oracle:begin -->", "<!-- oracle:end -->"


def shipped_scenes():
    return sorted(glob.glob(os.path.join(ROOT, "scenes", "*.json")) + glob.glob(os.path.join(ROOT, "scenes", "test", "*.json")))


def image_size(scene_path, size):
    """(width, height): the scene's own, shrunk to `size` pixels on the longer side when larger."""
    with open(scene_path) as f:
        camera = json.load(f)["camera"]
    w, h = camera["width"], camera["height"]
    scale = min(1.0, size / max(w, h))
    return max(1, round(w * scale)), max(1, round(h * scale))


def read_pfm(path):
    """A colour PFM as a (height, width, 3) float array, top row first."""
    with open(path, "rb") as f:
        assert f.readline().strip() == b"PF"
        width, height = map(int, f.readline().split())
        scale = float(f.readline())
        data = np.frombuffer(f.read(width * height * 12), dtype="<f4" if scale < 0 else ">f4")
    return data.reshape(height, width, 3)[::-1].astype(np.float64)


def render_wavepath(binary, scene_path, width, height, spp, seeds, scratch, options=()):
    """The images of `seeds` renders (with the command-line `options` added), shape (seeds, height, width, 3)."""
    out = os.path.join(scratch, "wavepath.pfm")
    images = []
    for seed in seeds:
        subprocess.run([binary, "render", scene_path, "-o", out, "-q", "--width", str(width), "--height", str(height),
                        "--spp", str(spp), "--seed", str(seed), *options], check=True)
        images.append(read_pfm(out))
    return np.stack(images)


def render_mitsuba(mi, scene_path, width, height, spp, seeds, scratch):
    """The images of `seeds` Mitsuba renders of the converted scene, shape (seeds, height, width, 3)."""
    scene_dict = mitsuba_scene.convert(scene_path, os.path.join(scratch, "meshes"), width=width, height=height,
                                       spp=spp)
    scene = mitsuba_scene.load(mi, scene_dict)
    return np.stack([np.array(mi.render(scene, seed=seed), dtype=np.float64) for seed in seeds])


def block_means(image, block):
    """Per block of BLOCK x BLOCK pixels (row by row, then the whole image, last) and channel: the mean of the
    (h, w, channels) array `image`, shape (blocks + 1, channels), and each block's pixel count, shape (blocks + 1,)."""
    h, w = image.shape[:2]
    means, counts = [], []
    for y in range(0, h, block):
        for x in range(0, w, block):
            part = image[y:y + block, x:x + block]
            means.append(part.mean(axis=(0, 1)))
            counts.append(part.shape[0] * part.shape[1])
    means.append(image.mean(axis=(0, 1)))
    counts.append(h * w)
    return np.array(means), np.array(counts)


def block_statistics(images, block):
    """Per block (and the whole image, last) and channel: the mean and the variance of that mean.

    images: (seeds, h, w, 3). Pixels are independent, so a block's variance is
    the sum of its pixels' variances (each over the seeds, of the seeds' mean)
    over its pixel count squared."""
    seeds = images.shape[0]
    means, _ = block_means(images.mean(axis=0), block)
    variance_means, counts = block_means(images.var(axis=0, ddof=1) / seeds, block)  # of each pixel's seed mean
    return means, variance_means / counts[:, None]


def z_scores(a, b, block, rounding=0.0):
    """|z| per block (whole image last) and channel; 0 where both are exactly equal with no variance. `rounding`,
    relative to the mean, is added to the standard error: blocks that both render without noise (a constant
    environment seen directly) then differ by float rounding without an infinite z."""
    mean_a, var_a = block_statistics(a, block)
    mean_b, var_b = block_statistics(b, block)
    difference, se = mean_a - mean_b, np.sqrt(var_a + var_b) + rounding * np.abs(mean_b)
    with np.errstate(divide="ignore", invalid="ignore"):
        z = np.where(se > 0, np.abs(difference) / np.where(se > 0, se, 1), np.where(difference == 0, 0.0, np.inf))
    return z, mean_a, mean_b, se


def critical_z(scenes, size, block, alpha):
    """(|z| threshold, number of tests) of a run over `scenes`: every block and the whole image of each, every
    channel, Bonferroni so that the run's false-failure rate is at most `alpha`."""
    return critical_z_for_sizes([image_size(path, size) for path in scenes], block, alpha)


def critical_z_for_sizes(sizes, block, alpha):
    """critical_z of a run over images of these (width, height) sizes."""
    tests = 0
    for width, height in sizes:
        tests += 3 * ((-(-width // block)) * (-(-height // block)) + 1)
    return critical_z_for_tests(tests, alpha), tests


def critical_z_for_tests(tests, alpha):
    """The two-sided |z| threshold of `tests` tests at a run's false-failure rate `alpha`, Bonferroni."""
    return statistics.NormalDist().inv_cdf(1.0 - alpha / (2 * tests))


def compare_scene(mi, path, args, seeds, z_crit, scratch, wavepath_scene=None):
    """Renders `path` with Mitsuba and (or `wavepath_scene`, a variant of it) with wavepath at the run's settings
    and compares them: (the scene's figures, a failure line or None)."""
    name = os.path.relpath(path, ROOT)
    width, height = image_size(path, args.size)
    start = time.time()
    ours = render_wavepath(args.binary, wavepath_scene or path, width, height, args.spp, seeds, scratch)
    middle = time.time()
    theirs = render_mitsuba(mi, path, width, height, args.spp, seeds, scratch)
    end = time.time()
    z, mean_ours, mean_theirs, se = z_scores(ours, theirs, args.block)
    whole_ratio = mean_ours[-1] / mean_theirs[-1]
    detectable = z_crit * se[-1] / mean_theirs[-1]  # smallest uniform relative bias the whole image shows
    worst = np.unravel_index(np.argmax(z), z.shape)
    row = {"scene": name, "width": width, "height": height, "spp": args.spp, "seeds": args.seeds,
           "mean_wavepath": mean_ours[-1].tolist(), "mean_mitsuba": mean_theirs[-1].tolist(),
           "ratio": whole_ratio.tolist(), "max_abs_z": float(z.max()), "z_whole": z[-1].tolist(),
           "detectable_bias": detectable.tolist(), "wavepath_s": middle - start, "mitsuba_s": end - middle}
    print(f"{name}: {width}x{height}, whole-image ratio wavepath/Mitsuba "
          f"{' '.join(f'{r:.4f}' for r in whole_ratio)} (RGB), |z| whole "
          f"{' '.join(f'{v:.2f}' for v in z[-1])}, largest |z| {z.max():.2f} "
          f"({'whole image' if worst[0] == len(z) - 1 else f'block {worst[0]}'}, channel {'RGB'[worst[1]]}); "
          f"detects a uniform bias of {100 * max(detectable):.2f}%; "
          f"wavepath {middle - start:.1f} s, Mitsuba {end - middle:.1f} s", flush=True)
    if z.max() <= z_crit:
        return row, None
    bad = [(int(b), "RGB"[c]) for b, c in zip(*np.nonzero(z > z_crit))]
    return row, (f"{name}: {len(bad)} of {z.size} tests beyond |z| {z_crit:.2f} (block, channel: "
                 f"{bad[:8]}{' ...' if len(bad) > 8 else ''}; block {len(z) - 1} is the whole image)")


def run_description(args, version):
    """What ran a table's figures: the commit (-dirty for changes other than the doc's own tables), date,
    machine, Mitsuba and the settings."""
    git = lambda *command: subprocess.run(["git", *command], cwd=ROOT, capture_output=True, text=True)  # noqa: E731
    commit = git("rev-parse", "--short", "HEAD").stdout.strip()
    if git("diff", "--quiet", "HEAD", "--", ".", ":(exclude)docs/mitsuba.md").returncode != 0:
        commit += "-dirty"
    with open("/proc/cpuinfo") as f:
        cpu = next((line.split(":", 1)[1].strip() for line in f if line.startswith("model name")), "unknown CPU")
    return (f"at commit `{commit}`, {time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}, on {cpu} "
            f"({os.cpu_count()} cores); Mitsuba {version} `{args.variant}`; {args.seeds} seeds x {args.spp} spp per "
            f"renderer, blocks of {args.block}^2")


def replace_doc_table(doc, begin_marker, end_marker, lines):
    """Writes `lines` between the markers in the markdown file `doc`."""
    with open(doc) as f:
        text = f.read()
    begin, end = text.index(begin_marker), text.index(end_marker) + len(end_marker)
    with open(doc, "w") as f:
        f.write(text[:begin] + "\n".join([begin_marker, *lines, end_marker]) + text[end:])


def doc_table_differences(doc, begin_marker, end_marker, rows, figure_columns):
    """Where the table rows between the markers in `doc` differ from `rows` (markdown lines) in the columns
    `figure_columns` (a slice; times are left out): a list of lines, empty when they agree."""
    with open(doc) as f:
        text = f.read()
    table = text[text.index(begin_marker):text.index(end_marker)]
    documented = [line for line in table.splitlines() if line.startswith("| ") and not line.startswith("| scene |")]

    def figures(line):
        return [cell.strip() for cell in line.strip("|").split("|")][figure_columns]

    found = {figures(line)[0]: figures(line) for line in rows}
    written = {figures(line)[0]: figures(line) for line in documented}
    return [f"{scene}: the doc has {written.get(scene)}, this run {found.get(scene)}"
            for scene in sorted(set(found) | set(written)) if found.get(scene) != written.get(scene)]


def oracle_table(report, z_crit, tests, args, version, failed):
    """The run's figures as the markdown lines of docs/mitsuba.md's oracle table."""
    lines = [f"Written by `scripts/mitsuba_figures.py` {run_description(args, version)}; {tests} tests, "
             f"|z| <= {z_crit:.2f}; {'FAILED' if failed else 'passed'}.", "",
             "| scene | size | mean ratio wavepath/Mitsuba (R, G, B) | whole-image abs(z) | largest abs(z) | "
             "smallest uniform bias detected | wavepath s | Mitsuba s |", "|---|---|---|---|---|---|---|---|"]
    for r in report:
        lines.append(f"| {r['scene']} | {r['width']}x{r['height']} | {', '.join(f'{v:.4f}' for v in r['ratio'])} | "
                     f"{', '.join(f'{v:.2f}' for v in r['z_whole'])} | {r['max_abs_z']:.2f} | "
                     f"{100 * max(r['detectable_bias']):.2f}% | {r['wavepath_s']:.1f} | {r['mitsuba_s']:.1f} |")
    return lines


def add_common_arguments(parser):
    """The settings every oracle comparison takes (this script's and the sensitivity test's)."""
    parser.add_argument("--binary", default=os.path.join(ROOT, "build", "wavepath"))
    parser.add_argument("--size", type=int, default=64, help="most pixels on the image's longer side")
    parser.add_argument("--block", type=int, default=16, help="block side in pixels")
    parser.add_argument("--spp", type=int, default=32)
    parser.add_argument("--seeds", type=int, default=8, help="independent renders per renderer and scene")
    parser.add_argument("--alpha", type=float, default=1e-3, help="false-failure rate of the whole run")
    parser.add_argument("--variant", default="llvm_ad_rgb", help="Mitsuba variant (scalar_rgb needs no LLVM)")
    parser.add_argument("--json", help="also write every scene's figures here")
    doc = parser.add_mutually_exclusive_group()
    doc.add_argument("--doc", help="also write the figures as the table between this script's markers of this "
                     "markdown file (docs/mitsuba.md)")
    doc.add_argument("--check-doc", help="exit 1 (after the run) when the figures (not the times) of the table "
                     "between this script's markers of this markdown file differ from this run's")


def open_mitsuba_or_explain(variant):
    """The mitsuba module under `variant`, or None after a line saying why not."""
    try:
        return mitsuba_scene.open_mitsuba(variant)
    except (ImportError, AttributeError) as e:
        print(f"{os.path.basename(sys.argv[0])}: error: Mitsuba 3 ({variant}) not available: {e} "
              "(bash scripts/setup.sh test)")
        return None


def finish_doc(args, begin_marker, end_marker, lines, figure_columns):
    """--doc writes the table lines, --check-doc compares them: False when they differ from the doc's."""
    if args.doc:
        replace_doc_table(args.doc, begin_marker, end_marker, lines)
    if not args.check_doc:
        return True
    rows = [line for line in lines if line.startswith("| ") and not line.startswith("| scene |")]
    differences = doc_table_differences(args.check_doc, begin_marker, end_marker, rows, figure_columns)
    for difference in differences:
        print(f"{os.path.basename(sys.argv[0])}: {args.check_doc} differs: {difference}")
    return not differences


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    add_common_arguments(parser)
    parser.add_argument("--scenes", help="comma-separated scene files (default: scenes/*.json, scenes/test/*.json)")
    args = parser.parse_args()
    mi = open_mitsuba_or_explain(args.variant)
    if mi is None:
        return 2

    scenes = args.scenes.split(",") if args.scenes else shipped_scenes()
    seeds = list(range(FIRST_SEED, FIRST_SEED + args.seeds))
    z_crit, tests = critical_z(scenes, args.size, args.block, args.alpha)
    print(f"mitsuba_oracle: {len(scenes)} scenes, {tests} tests (blocks of {args.block}^2 and whole images, 3 "
          f"channels), {args.seeds} seeds x {args.spp} spp per renderer; |z| <= {z_crit:.2f} (false-failure rate "
          f"<= {args.alpha:g}, Bonferroni), Mitsuba {mi.__version__} {args.variant}", flush=True)
    failures, report = [], []
    with tempfile.TemporaryDirectory(prefix="wavepath-oracle-") as scratch:
        for path in scenes:
            row, failure = compare_scene(mi, path, args, seeds, z_crit, scratch)
            report.append(row)
            if failure:
                failures.append(failure)
    if args.json:
        with open(args.json, "w") as f:
            json.dump({"z_crit": z_crit, "alpha": args.alpha, "tests": tests, "mitsuba": mi.__version__,
                       "variant": args.variant, "scenes": report}, f, indent=1)
    lines = oracle_table(report, z_crit, tests, args, mi.__version__, bool(failures))
    doc_agrees = finish_doc(args, DOC_BEGIN, DOC_END, lines, slice(0, 6))
    for failure in failures:
        print(f"mitsuba_oracle: FAIL {failure}")
    print(f"mitsuba_oracle: {'FAILED' if failures else 'passed'}")
    return 1 if failures or not doc_agrees else 0


if __name__ == "__main__":
    sys.exit(main())
