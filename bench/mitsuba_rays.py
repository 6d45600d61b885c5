#!/usr/bin/env python3
"""Mitsuba 3's closest-hit rays/s on the bunny scene, beside which mesh_bench's figures for Embree and our
intersector read (bench/results/analysis.md, "What the bunny's target asks").

Usage: python3 bench/mitsuba_rays.py [--size 512] [--repeats 5] [--scene scenes/bunny.json]

The scene converted as the efficiency bench hands it to Mitsuba (llvm_ad_rgb); rays: one camera ray through
each pixel's centre, and one cosine-distributed bounce from each camera ray's hit (as mesh_bench's
incoherent set), traced by `mi.Scene.ray_intersect` in pixel order and shuffled. The rays are evaluated
before they are timed, so each time is the query's alone (Dr.Jit would otherwise recompute a lazy ray with
it); best of --repeats after one warm-up. Prints the figures with the commit, date and machine.
"""
import argparse
import os
import subprocess
import sys
import time

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from mitsuba_peer import MitsubaPeer  # noqa: E402
from run import ROOT, machine  # noqa: E402


def evaluated(mi, origins, directions):
    """A ray batch from (3, N) numpy arrays: data, not an expression."""
    return mi.Ray3f(mi.Point3f(*origins), mi.Vector3f(*directions))


def rays_per_s(mi, dr, scene, rays, count, repeats):
    best = float("inf")
    for _ in range(repeats + 1):
        start = time.perf_counter()
        hit = scene.ray_intersect(rays)
        dr.eval(hit.t)
        dr.sync_thread()
        best = min(best, time.perf_counter() - start)
    return count / best / 1e6


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--size", type=int, default=512)
    parser.add_argument("--repeats", type=int, default=5)
    parser.add_argument("--scene", default="scenes/bunny.json")
    args = parser.parse_args()
    peer = MitsubaPeer()
    mi = peer.mi
    import drjit as dr
    scene = peer.load(os.path.join(ROOT, args.scene), args.size, 1)
    n = args.size * args.size
    rng = np.random.default_rng(1)
    ys, xs = np.divmod(np.arange(n), args.size)
    camera, _ = scene.sensors()[0].sample_ray(0.0, 0.5, mi.Point2f((xs + 0.5) / args.size, (ys + 0.5) / args.size),
                                              mi.Point2f(0.5, 0.5))
    camera = evaluated(mi, np.array(camera.o), np.array(camera.d))
    hit = scene.ray_intersect(camera)
    frame = mi.Frame3f(hit.n)
    local = mi.warp.square_to_cosine_hemisphere(mi.Point2f(rng.random(n, dtype=np.float32),
                                                           rng.random(n, dtype=np.float32)))
    direction = frame.to_world(local)
    direction = dr.select(dr.dot(direction, hit.n) * dr.dot(camera.d, hit.n) > 0, -direction, direction)
    bounce = hit.spawn_ray(direction)
    origins, directions = np.array(bounce.o), np.array(bounce.d)
    order = rng.permutation(n)
    figures = {
        "camera rays, pixel order": rays_per_s(mi, dr, scene, camera, n, args.repeats),
        "bounce rays, pixel order": rays_per_s(mi, dr, scene, evaluated(mi, origins, directions), n, args.repeats),
        "bounce rays, shuffled": rays_per_s(mi, dr, scene, evaluated(mi, origins[:, order], directions[:, order]), n,
                                            args.repeats),
    }
    meta = machine(os.path.join(ROOT, "build", "wavepath"))
    commit = subprocess.run(["git", "describe", "--always", "--dirty", "--abbrev=12"], capture_output=True,
                            text=True, cwd=ROOT).stdout.strip()
    print(f"mitsuba_rays: {peer.describe()}, {args.scene} at {args.size}x{args.size} ({n} rays per set), commit "
          f"{commit}, {time.strftime('%Y-%m-%d %H:%M:%S UTC', time.gmtime())}, {meta['cpu']}, {meta['cores']} cores, "
          f"load average {os.getloadavg()[0]:.2f}")
    for name, value in figures.items():
        print(f"  {name}: {value:.2f} Mrays/s (best of {args.repeats})")


if __name__ == "__main__":
    main()
