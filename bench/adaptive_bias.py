#!/usr/bin/env python3
"""Adaptive sampling's stopping bias (docs/long-renders.md, "Bias").

Usage: python3 bench/adaptive_bias.py [--binary build/wavepath]

For seeds 1-3 and (spp, threshold) in (64, 0.1), (256, 0.1), (256, 0.05),
renders the room at 24x24 on the reference backend twice into film files:
without --adaptive (keeping sums of squares through --target-error 1e-9,
which never stops it) and with it. Every adaptive pixel holds the first n of
the same N samples, so per channel the image means differ by a variance of
sum over pixels of s^2 (1/n - 1/N) / pixels^2 (s^2 from the N samples); prints
the relative difference of the image means and its z.
"""
import argparse
import os
import struct
import subprocess
import tempfile

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
HEADER = 8 + 4 + 4 + 8 + 8 + 16 + 8 + 16 + 8  # up to the sums (docs/long-renders.md, "Film files")


def read_film(path):
    """(sums, squares or None, per-pixel sample counts) of a .wpfilm file."""
    b = open(path, "rb").read()
    _, flags = struct.unpack_from("<II", b, 8)
    width, height = struct.unpack_from("<II", b, 48)
    begin, end = struct.unpack_from("<QQ", b, 56)
    pixels, at = width * height, HEADER

    def sums():
        nonlocal at
        limbs = np.frombuffer(b, dtype="<u8", count=pixels * 12, offset=at).reshape(-1, 4)
        at += pixels * 96
        values = [int(l[0]) | int(l[1]) << 64 | int(l[2]) << 128 | int(l[3]) << 192 for l in limbs]
        return np.array([(v - (1 << 256) if v >> 255 else v) / 2.0**100 for v in values]).reshape(pixels, 3)

    def items_of(n, begin, end):
        i = np.arange(n)
        return (end // n + (i < end % n)) - (begin // n + (i < begin % n))

    s = sums()
    q = sums() if flags & 1 else None
    if flags & 2:
        n, = struct.unpack_from("<I", b, at)
        round_pixels = np.frombuffer(b, dtype="<u4", count=n, offset=at + 4)
        counts = np.frombuffer(b, dtype="<u4", count=pixels, offset=at + 4 + 4 * n).astype(np.int64)
        counts[round_pixels] += items_of(n, begin, end)
    else:
        counts = items_of(pixels, begin, end)
    return s, q, counts


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--binary", default=os.path.join(ROOT, "build", "wavepath"))
    args = parser.parse_args()
    scene = os.path.join(ROOT, "scenes", "room.json")
    with tempfile.TemporaryDirectory() as scratch:
        def render(name, spp, seed, extra):
            path = os.path.join(scratch, name + ".wpfilm")
            subprocess.run([args.binary, "render", scene, "-o", path, "-q", "--width", "24", "--height", "24",
                            "--spp", str(spp), "--seed", str(seed), "--backend", "reference", *extra], check=True)
            return read_film(path)
        for seed in (1, 2, 3):
            for spp, threshold in ((64, 0.1), (256, 0.1), (256, 0.05)):
                s, q, _ = render("plain", spp, seed, ["--target-error", "1e-9"])
                sa, _, n = render("adaptive", spp, seed, ["--adaptive", str(threshold)])
                variance = np.maximum(0.0, (q - s * s / spp) / (spp - 1))
                difference = (sa / n[:, None] - s / spp).sum(axis=0)
                z = difference / np.sqrt((variance * (1.0 / n[:, None] - 1.0 / spp)).sum(axis=0))
                relative = difference / (s / spp).sum(axis=0)
                print(f"seed {seed}, {spp} spp, --adaptive {threshold}: mean {n.mean():.1f} spp, image mean "
                      f"{', '.join(f'{100 * r:+.2f}%' for r in relative)} (RGB), z {', '.join(f'{x:.2f}' for x in z)}")


if __name__ == "__main__":
    main()
