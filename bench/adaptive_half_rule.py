#!/usr/bin/env python3
"""Would deciding from half of the samples remove --adaptive's stopping bias? (docs/long-renders.md, "Bias")

Usage: python3 bench/adaptive_half_rule.py [--binary build/wavepath] [--spp 64] [--threshold 0.1] [--seeds 1,2,3]

Cycles keeps a second film of every other sample for its noise threshold. The
hope: a pixel stopped on the error of its even samples alone keeps an unbiased
mean of its odd ones, which never took part in the decision. For each seed,
renders the room at 24x24 on the reference backend one sample at a time
(--samples s:s+1, each sample's exact value), replays --adaptive's decisions
on those values (the rule, dilation and check schedule of src/longrun/, in
exact sums rounded once to double as the film does), checks the replay gives
every pixel the sample count wavepath's own --adaptive render gave it, then
replays a second rule that judges each pixel by its even samples only
(their variance over the pixel's count, their mean). For both it prints the
mean spp, the image mean's difference from the render of all --spp samples
with its z (as bench/adaptive_bias.py), and the image's variance (sum over
pixels and channels of s^2 / n) times the mean spp: lower is more efficient.
"""
import argparse
import math
import os
import subprocess
import tempfile

import numpy as np

from adaptive_bias import HEADER, ROOT, read_film

SIZE = 24
PIXELS = SIZE * SIZE


def exact_sums(path):
    """The film's sums, as exact integers in units of 2^-100, pixel-major RGB."""
    b = open(path, "rb").read()
    limbs = np.frombuffer(b, dtype="<u8", count=PIXELS * 12, offset=HEADER).reshape(-1, 4)
    values = [int(l[0]) | int(l[1]) << 64 | int(l[2]) << 128 | int(l[3]) << 192 for l in limbs]
    return [v - (1 << 256) if v >> 255 else v for v in values]


def exact_square(v):
    """film_sum_from_float_squared of the sample v (in units of 2^-100): v^2 / 2^100, to nearest, ties to even."""
    q, r = divmod(v * v, 1 << 100)
    return q + (r > 1 << 99 or (r == 1 << 99 and q & 1))


def next_error_check(spp):
    check = 4
    while check <= spp:
        check += max(1, check // 4)
    return check


def error(sums, squares, k, n):
    """pixel_error (src/longrun/adaptive.cpp) from k samples' exact sums, as the error of a mean of n."""
    variance, mean = 0.0, 0.0
    for s, q in zip(sums, squares):
        s, q = s / (1 << 100), q / (1 << 100)
        variance += max(0.0, (q - s * s / float(k)) / float(k - 1)) / float(n)
        mean += s / float(k)
    return math.sqrt(variance / 3) / (1e-4 + math.sqrt(max(0.0, mean / 3)))


def replay(samples, squares, spp, threshold, even_only):
    """Each pixel's sample count under --adaptive's schedule (render_loop.cpp), judged by all its samples or its even ones."""
    min_spp = max(8, spp // 16)
    counts = np.full(PIXELS, spp)
    active, round_start = list(range(PIXELS)), 0

    def decides_at(n):
        return n >= min_spp and (n - round_start) * len(active) >= PIXELS

    def next_decision(n):
        n = next_error_check(n)
        while not decides_at(n):
            n = next_error_check(n)
        return n

    n = next_decision(0)
    while n < spp:
        step, k = (2, (n + 1) // 2) if even_only else (1, n)
        noisy = set()
        for p in active:
            s = [sum(samples[p][c][0:n:step]) for c in range(3)]
            q = [sum(squares[p][c][0:n:step]) for c in range(3)]
            if error(s, q, k, n) > threshold:
                noisy.add(p)
        near_noisy = [p for p in active if any((p // SIZE + dy) * SIZE + p % SIZE + dx in noisy
                                               for dy in (-1, 0, 1) for dx in (-1, 0, 1)
                                               if 0 <= p % SIZE + dx < SIZE and 0 <= p // SIZE + dy < SIZE)]
        for p in set(active) - set(near_noisy):
            counts[p] = n
        if not near_noisy:
            break
        if len(near_noisy) < len(active):
            active, round_start = near_noisy, n
        n = next_decision(n)
    return counts


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--binary", default=os.path.join(ROOT, "build", "wavepath"))
    parser.add_argument("--spp", type=int, default=64)
    parser.add_argument("--threshold", type=float, default=0.1)
    parser.add_argument("--seeds", default="1,2,3")
    args = parser.parse_args()
    scene = os.path.join(ROOT, "scenes", "room.json")
    with tempfile.TemporaryDirectory() as scratch:
        def render(seed, extra):
            path = os.path.join(scratch, "film.wpfilm")
            subprocess.run([args.binary, "render", scene, "-o", path, "-q", "--width", str(SIZE), "--height",
                            str(SIZE), "--spp", str(args.spp), "--seed", str(seed), "--backend", "reference", *extra],
                           check=True)
            return path
        for seed in (int(s) for s in args.seeds.split(",")):
            values = [exact_sums(render(seed, ["--samples", f"{s}:{s + 1}"])) for s in range(args.spp)]
            samples = [[[values[s][3 * p + c] for s in range(args.spp)] for c in range(3)] for p in range(PIXELS)]
            squares = [[[exact_square(v) for v in channel] for channel in pixel] for pixel in samples]
            x = np.array(samples, dtype=object).astype(np.float64) / 2.0**100  # pixel, channel, sample
            every = x.mean(axis=2)
            variance = x.var(axis=2, ddof=1)
            _, _, wavepath_counts = read_film(render(seed, ["--adaptive", str(args.threshold)]))
            for even_only in (False, True):
                n = replay(samples, squares, args.spp, args.threshold, even_only)
                if not even_only and not np.array_equal(n, wavepath_counts):
                    raise SystemExit("adaptive_half_rule: the replay differs from wavepath's --adaptive render")
                image = np.array([x[p, :, :n[p]].mean(axis=1) for p in range(PIXELS)])
                difference = (image - every).sum(axis=0)
                z = difference / np.sqrt((variance * (1.0 / n[:, None] - 1.0 / args.spp)).sum(axis=0))
                relative = difference / every.sum(axis=0)
                noise = (variance / n[:, None]).sum()
                rule = "even samples" if even_only else "all samples (wavepath's rule, replay matches)"
                print(f"seed {seed}, {args.spp} spp, --adaptive {args.threshold}, judged by {rule}: mean "
                      f"{n.mean():.1f} spp, image mean {', '.join(f'{100 * r:+.2f}%' for r in relative)} (RGB), "
                      f"z {', '.join(f'{v:.2f}' for v in z)}, variance x spp {noise * n.mean():.4g}")


if __name__ == "__main__":
    main()
