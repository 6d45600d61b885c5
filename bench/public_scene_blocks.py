#!/usr/bin/env python3
"""Where a public scene's block comparison with Mitsuba 3 fails: the map of blocks' |z|, and the worst block.

bench/public_scenes.py compares 8x8 block means of REPEATS renders per renderer by z = difference / combined
standard error, each renderer's from its own renders (public_scenes.block_variances). This renders one scene of
its table the same way and prints the largest |z| of each block as a map, then the worst block's pixel means in
both renderers and how many of its pixels vary at all over our renders. With --box-filter the scene's pixel
filter is replaced by a box in a copy of the file, so that a difference the filter causes goes away with it.
Printed, with the commit, date, machine and load; not a test.

Usage: python3 bench/public_scene_blocks.py --mitsuba-data CLONE --scene bsdf_twosided_cbox [--box-filter]
"""
import argparse
import datetime
import os
import platform
import re
import subprocess
import sys
import tempfile

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "bench"))
import public_scenes  # noqa: E402  (the scene table, Mitsuba's renders at another size, the block statistics)
from run import Runner  # noqa: E402


def with_box_filter(path, scratch):
    """A copy of the XML file beside it (its relative paths still resolve) whose rfilter is a box."""
    with open(path) as f:
        text = f.read()
    boxed, count = re.subn(r'<rfilter\s+type="[a-z]+"\s*/>', '<rfilter type="box"/>', text)
    if count == 0:
        sys.exit(f"public_scene_blocks: {path} names no rfilter to replace")
    copy = os.path.join(os.path.dirname(path), f".{os.path.basename(scratch)}_box.xml")
    with open(copy, "w") as f:
        f.write(boxed)
    return copy


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    public_scenes.add_one_scene_arguments(parser)
    parser.add_argument("--binary", default=os.path.join(ROOT, "build", "wavepath"))
    parser.add_argument("--box-filter", action="store_true", help="replace the scene's pixel filter by a box")
    parser.add_argument("--width", type=int, default=128)
    parser.add_argument("--spp", type=int, default=32)
    parser.add_argument("--repeats", type=int, default=6)
    args = parser.parse_args()
    name, path, defines = public_scenes.one_scene(args, "public_scene_blocks")
    os.environ.setdefault("DRJIT_LIBLLVM_PATH", "/usr/lib/x86_64-linux-gnu/libLLVM-19.so")
    import mitsuba as mi
    mi.set_variant("llvm_ad_rgb")
    mi.set_log_level(mi.LogLevel.Error)
    commit = subprocess.run(["git", "-C", ROOT, "rev-parse", "--short", "HEAD"], capture_output=True,
                            text=True).stdout.strip()
    with tempfile.TemporaryDirectory() as scratch:
        copy = with_box_filter(path, scratch) if args.box_filter else None
        try:
            measure(args, mi, name + (" (box filter)" if copy else ""), copy or path, defines, commit, scratch)
        finally:
            if copy:
                os.remove(copy)


def measure(args, mi, name, path, defines, commit, scratch):
    peer = public_scenes.MitsubaXml(mi, path, defines, args.width)
    width, height = peer.size
    block = public_scenes.BLOCK
    print(f"{name}: {width}x{height}, {args.repeats} renders of {args.spp} spp per renderer, {block}x{block} blocks; "
          f"commit {commit}, {datetime.datetime.now(datetime.timezone.utc):%Y-%m-%d %H:%M} UTC, {platform.node()}, "
          f"{os.cpu_count()} CPUs, load {os.getloadavg()[0]:.1f}; Mitsuba {mi.__version__} llvm_ad_rgb", flush=True)
    runner = Runner(args.binary, scratch)
    ours, theirs = [], []
    for seed in range(args.repeats):
        r = runner.render(path, None, width, height, args.spp, extra=public_scenes.scene_options(defines),
                          image=True, seed=seed)
        ours.append(np.asarray(r["image"], dtype=np.float64).reshape(height, width, 3))
        theirs.append(np.asarray(peer.render(args.spp, seed)["image"], dtype=np.float64).reshape(height, width, 3))
    ours, theirs = np.stack(ours), np.stack(theirs)
    z, mean_ours, mean_theirs = public_scenes.block_z(ours, theirs)
    columns = width // block
    print(f"largest |z| over the channels, block by block (row 0 at the image's top); whole image "
          f"{z[-1].max():.2f}, ratio {' / '.join(f'{v:.4f}' for v in mean_ours[-1] / mean_theirs[-1])}:")
    for row in z[:-1].max(axis=1).reshape(-1, columns):
        print("  " + " ".join(f"{v:5.1f}" for v in row))
    worst = int(np.argmax(z[:-1].max(axis=1)))
    by, bx = divmod(worst, columns)
    pixels = (slice(None), slice(by * block, (by + 1) * block), slice(bx * block, (bx + 1) * block))
    varying = int((ours[pixels].std(axis=0).max(axis=-1) > 0).sum())
    print(f"worst block: row {by}, column {bx}: |z| {' / '.join(f'{v:.1f}' for v in z[worst])}, block means "
          f"wavepath {' / '.join(f'{v:.6f}' for v in mean_ours[worst])}, Mitsuba "
          f"{' / '.join(f'{v:.6f}' for v in mean_theirs[worst])}; {varying} of its {block * block} pixels vary "
          f"over our renders")
    for who, images in (("wavepath", ours), ("Mitsuba", theirs)):
        print(f"  {who}'s pixel means there (mean of the channels):")
        for row in images[pixels].mean(axis=0).mean(axis=-1):
            print("    " + " ".join(f"{v:.5f}" for v in row))
    print(f"load {os.getloadavg()[0]:.1f}", flush=True)


if __name__ == "__main__":
    main()
