#!/usr/bin/env python3
"""Russian roulette starts at the same vertex in wavepath and in the Mitsuba scene it converts to.

rr_depth changes no mean, only the variance, so the mean-based oracle (mitsuba_oracle.py) cannot see a
converter that hands Mitsuba another rr_depth: it did, for months (ours + 1), and every efficiency comparison
against Mitsuba then set our roulette against a later one. Here both render the cornell box with independent
samples at a small rr_depth, where a vertex more or less before the roulette changes the variance by tens of
percent, and their per-pixel variances over seeds are compared, pixel by pixel.

The statistic: for each pixel, the variance over the seeds of its channel mean, over (mean^2 + 0.01) as
relMSE weighs it, in each renderer; d = wavepath's - Mitsuba's. Pixels are independent, and under the same
estimator every pixel's d has mean 0, so z = mean(d) / (sd(d) / sqrt(pixels)) is standard normal (4096 pixels:
the central limit holds well; the variance estimates' own tails are those of a diffuse scene without
fireflies). The test asks |z| < 4 (false-failure rate 6e-5 a run) and, so that it shows it can fail, the same
comparison against Mitsuba given rr_depth + 1 (the old converter's error) at |z| >= 4: with the seeds below,
z +10.3 there (wavepath's variance 1.21x Mitsuba's) and +1.2 against the right depth (1.02x); at rr_depth 2 and
24 seeds the wrong depth stood at only z 5.6, hence rr_depth 1 and 40 seeds (about 20 s).

Usage: roulette_variance_test.py --binary build/wavepath; exit 0 when both hold, 1 when one does not, 2 when
Mitsuba is missing.
"""
import argparse
import json
import os
import sys
import tempfile

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import mitsuba_oracle  # noqa: E402
from mitsuba_oracle import FIRST_SEED, ROOT, mitsuba_scene  # noqa: E402

SIZE, SPP, SEEDS, RR_DEPTH = 64, 16, 40, 2
Z_LIMIT = 4.0


def weighted_pixel_variance(images):
    """Per pixel: the variance over seeds of its channel mean, over (mean^2 + 0.01). images: (seeds, h, w, 3)."""
    pixels = images.mean(axis=-1)
    mean = pixels.mean(axis=0)
    return (pixels.var(axis=0, ddof=1) / (mean * mean + 1e-2)).reshape(-1)


def paired_z(a, b):
    d = a - b
    return float(d.mean() / (d.std(ddof=1) / np.sqrt(d.size))), float(a.mean() / b.mean())


def render_mitsuba(mi, scene_path, seeds, rr_depth, scratch):
    scene_dict = mitsuba_scene.convert(scene_path, scratch, width=SIZE, height=SIZE, spp=SPP)
    scene_dict["integrator"]["rr_depth"] = rr_depth
    scene = mitsuba_scene.load(mi, scene_dict)
    return np.stack([np.array(mi.render(scene, seed=seed), dtype=np.float64) for seed in seeds])


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--binary", required=True)
    parser.add_argument("--variant", default="llvm_ad_rgb")
    args = parser.parse_args()
    mi = mitsuba_oracle.open_mitsuba_or_explain(args.variant)
    if mi is None:
        return 2
    seeds = range(FIRST_SEED, FIRST_SEED + SEEDS)
    with tempfile.TemporaryDirectory(prefix="wavepath-roulette-") as scratch:
        with open(os.path.join(ROOT, "scenes", "cornell.json")) as f:
            scene = json.load(f)
        scene["render"]["rr_depth"] = RR_DEPTH
        path = os.path.join(scratch, "cornell-rr.json")
        with open(path, "w") as f:
            json.dump(scene, f)
        converted = mitsuba_scene.convert(path, scratch)["integrator"]["rr_depth"]
        ours = weighted_pixel_variance(mitsuba_oracle.render_wavepath(
            args.binary, path, SIZE, SIZE, SPP, seeds, scratch, options=("--sampler", "independent")))
        same_z, same_ratio = paired_z(ours, weighted_pixel_variance(render_mitsuba(mi, path, seeds, converted, scratch)))
        later_z, later_ratio = paired_z(ours, weighted_pixel_variance(
            render_mitsuba(mi, path, seeds, converted + 1, scratch)))
    print(f"cornell at rr_depth {RR_DEPTH}, {SIZE}x{SIZE}, {SEEDS} seeds x {SPP} spp, independent samples: variance "
          f"over Mitsuba's at the converted rr_depth {converted}: {same_ratio:.3f}x (z {same_z:+.2f}, asked |z| < "
          f"{Z_LIMIT:g}); at rr_depth {converted + 1}: {later_ratio:.3f}x (z {later_z:+.2f}, asked |z| >= {Z_LIMIT:g})")
    return 0 if abs(same_z) < Z_LIMIT and abs(later_z) >= Z_LIMIT else 1


if __name__ == "__main__":
    sys.exit(main())
