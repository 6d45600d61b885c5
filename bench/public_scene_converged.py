#!/usr/bin/env python3
"""Converged agreement of one public scene with Mitsuba 3: many samples, independent renders.

bench/public_scenes.py compares renders of a few dozen samples per pixel, block by block; where a scene's
estimator is heavy-tailed (a rough glass of tiny roughness under a small light, whose rare paths carry
thousands) such a comparison can fail by chance, or hide a bias. This renders the scene SEEDS times with
each renderer at SPP samples per pixel (fixed, different seeds), at the scene's own camera and pixel filter
(Mitsuba through a sensor of the same size, as public_scenes.py does), and compares the whole image's mean:
the standard error of each renderer's mean comes from the spread of its renders' means (independent by their
seeds), and z = (ours - theirs) / sqrt(se_ours^2 + se_theirs^2). Printed, with the commit, date, machine and
load; not a test (a heavy tail's standard error from 8 renders is itself rough).

Usage: python3 bench/public_scene_converged.py --ppg CLONE --scene torus [--width 64 --spp 512 --seeds 8]
"""
import argparse
import datetime
import os
import platform
import subprocess
import sys
import tempfile

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "bench"))
import public_scenes  # noqa: E402  (the scene table and Mitsuba's renders at another size)


def read_pfm(path):
    with open(path, "rb") as f:
        f.readline(), f.readline(), f.readline()
        return np.frombuffer(f.read(), dtype="<f4").astype(np.float64)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    public_scenes.add_one_scene_arguments(parser)
    parser.add_argument("--binary", default=os.path.join(ROOT, "build", "wavepath"))
    parser.add_argument("--width", type=int, default=64)
    parser.add_argument("--spp", type=int, default=512)
    parser.add_argument("--seeds", type=int, default=8)
    args = parser.parse_args()
    name, path, defines = public_scenes.one_scene(args, "public_scene_converged")
    os.environ.setdefault("DRJIT_LIBLLVM_PATH", "/usr/lib/x86_64-linux-gnu/libLLVM-19.so")
    import mitsuba as mi
    mi.set_variant("llvm_ad_rgb")
    peer = public_scenes.MitsubaXml(mi, path, defines, args.width)
    width, height = peer.size
    commit = subprocess.run(["git", "-C", ROOT, "rev-parse", "--short", "HEAD"], capture_output=True,
                            text=True).stdout.strip()
    print(f"{name}: {path}, {width}x{height}, {args.seeds} renders of {args.spp} spp per renderer; commit {commit}, "
          f"{datetime.datetime.now(datetime.timezone.utc):%Y-%m-%d %H:%M} UTC, {platform.node()}, "
          f"{os.cpu_count()} CPUs, load {os.getloadavg()[0]:.1f}; Mitsuba {mi.__version__} llvm_ad_rgb", flush=True)
    ours, theirs = [], []
    with tempfile.TemporaryDirectory() as scratch:
        for k in range(args.seeds):
            out = os.path.join(scratch, f"{k}.pfm")
            subprocess.run([args.binary, "render", path, *public_scenes.scene_options(defines), "--width", str(width),
                            "--height", str(height), "--spp", str(args.spp), "--seed", str(100 + k), "-q", "-o", out],
                           check=True)
            ours.append(read_pfm(out).mean())
            theirs.append(peer.render(args.spp, 500 + k)["image"].mean())
            print(f"  render {k}: wavepath {ours[-1]:.5f}, Mitsuba {theirs[-1]:.5f}", flush=True)
    o, t = np.array(ours), np.array(theirs)
    se_o, se_t = o.std(ddof=1) / np.sqrt(len(o)), t.std(ddof=1) / np.sqrt(len(t))
    z = (o.mean() - t.mean()) / np.hypot(se_o, se_t)
    print(f"{name}: wavepath {o.mean():.5f} +- {se_o:.5f}, Mitsuba {t.mean():.5f} +- {se_t:.5f}, "
          f"ratio {o.mean() / t.mean():.4f}, z {z:.2f}; per-render means {o.min():.3f}-{o.max():.3f} and "
          f"{t.min():.3f}-{t.max():.3f}; load {os.getloadavg()[0]:.1f}")


if __name__ == "__main__":
    main()
