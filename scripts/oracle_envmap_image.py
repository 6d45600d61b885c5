#!/usr/bin/env python3
"""Writes scenes/test/envmaps/sky.exr, the small environment map of
scenes/test/oracle_envmap.json: 32 x 16 texels of linear RGB (float EXR,
through Mitsuba 3's Bitmap), a bluish sky brightening towards the horizon, a
dim brown ground, a warm band around one side and a 2 x 2-texel sun of
radiance 40 high on another: a map whose light importance sampling must find.

    python3 scripts/oracle_envmap_image.py [output.exr]
"""
import math
import os
import sys

import numpy as np

WIDTH, HEIGHT = 32, 16


def sky():
    image = np.zeros((HEIGHT, WIDTH, 3), dtype=np.float32)
    for y in range(HEIGHT):
        theta = math.pi * y / (HEIGHT - 1)  # rows are corner-aligned: row 0 at the zenith (+y)
        for x in range(WIDTH):
            phi = 2.0 * math.pi * (x + 0.5) / WIDTH
            if theta < math.pi / 2:
                glow = 1.0 - math.cos(theta)  # brighter towards the horizon
                rgb = [0.25 + 0.5 * glow, 0.35 + 0.5 * glow, 0.7 + 0.4 * glow]
            else:
                rgb = [0.12, 0.09, 0.06]
            band = max(0.0, math.cos(phi - 1.0)) ** 4  # a warm glow around phi = 1
            rgb = [rgb[0] + 1.5 * band, rgb[1] + 0.8 * band, rgb[2] + 0.2 * band]
            image[y, x] = rgb
    image[3:5, 20:22] = [40.0, 36.0, 30.0]  # the sun
    return image


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.join(
        os.path.dirname(__file__), "..", "scenes", "test", "envmaps", "sky.exr")
    os.environ.setdefault("DRJIT_LIBLLVM_PATH", "/usr/lib/x86_64-linux-gnu/libLLVM-19.so")
    import mitsuba as mi
    mi.set_variant("scalar_rgb")
    mi.Bitmap(sky()).write(out)
    print(out)


if __name__ == "__main__":
    main()
