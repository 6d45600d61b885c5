"""Mitsuba 3 in the benchmark: the peer renderer, and the converged images that relMSE is measured against.

The converged images come from Mitsuba, an estimator that shares no code with
wavepath, so the benchmark's bias^2 is wavepath's bias, not the converged
image's noise or a bug both sides share. They are cached on disk under a key
of everything that decides them: the converted scene (with the content, not
the path, of every mesh file), the settings, and Mitsuba's version and
variant, plus the converter's own source.
"""
import collections
import hashlib
import json
import os
import sys
import tempfile
import time

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "scripts"))
import mitsuba_scene  # noqa: E402

# A converged image (flat RGB values, as MitsubaPeer.render's), the variance of each of its values, that of
# each pixel's mean over its channels (one per pixel), and its cache file.
Converged = collections.namedtuple("Converged", "image variance pixel_variance file")

CONVERGED_PASS_SPP = 256  # converged images are rendered in passes of this many spp (memory), seeds apart


class MitsubaPeer:
    def __init__(self, variant="llvm_ad_rgb"):
        mi = mitsuba_scene.open_mitsuba(variant)
        self.mi = mi
        self.variant = variant
        self.version = mi.__version__
        self.workdir = tempfile.mkdtemp(prefix="wavepath-bench-mitsuba-")
        self.loaded = {}
        self.warm = set()

    def describe(self):
        return f"Mitsuba {self.version} {self.variant}"

    def scene_dict(self, scene, size, spp, max_depth=None, sampler="independent"):
        converted = mitsuba_scene.convert(scene, self.workdir, width=size, height=size, spp=spp, max_depth=max_depth)
        converted["sensor"]["sampler"]["type"] = sampler
        return converted

    def load(self, scene, size, spp, max_depth=None, sampler="independent"):
        key = (scene, size, spp, max_depth, sampler)
        if key not in self.loaded:
            self.loaded[key] = mitsuba_scene.load(self.mi, self.scene_dict(scene, size, spp, max_depth, sampler))
        return self.loaded[key]

    def render(self, scene, size, spp, seed=0, max_depth=None, sampler="independent"):
        """One render: time_s (the render and reading the image back; loading left out), samples (those the
        sampler took: some round spp to a square, a prime's square or a power of two), samples_per_s and the
        image as flat linear RGB floats in the bottom-up row order of wavepath's PFM files.

        The first render of each configuration is run twice and the first discarded: Dr.Jit compiles its
        kernels then (or loads them from its cache), which is not the renderer's speed."""
        loaded = self.load(scene, size, spp, max_depth, sampler)
        key = (scene, size, spp, max_depth, sampler)
        if key not in self.warm:
            self.warm.add(key)
            np.array(self.mi.render(loaded, seed=seed + 1_000_003))
        start = time.perf_counter()
        image = np.array(self.mi.render(loaded, seed=seed), dtype=np.float64)
        elapsed = time.perf_counter() - start
        samples = size * size * loaded.sensors()[0].sampler().sample_count()
        return {"time_s": elapsed, "samples": samples, "samples_per_s": samples / elapsed,
                "image": image[::-1].reshape(-1)}

    def cache_key(self, scene, size, spp, max_depth):
        """sha256 of the converted scene (mesh files by content), the settings, Mitsuba and the converter."""
        converted = self.scene_dict(scene, size, CONVERGED_PASS_SPP, max_depth)

        def by_content(value):
            if isinstance(value, dict):
                return {k: file_digest(v) if k == "filename" else by_content(v) for k, v in value.items()}
            return value

        with open(mitsuba_scene.__file__, "rb") as f:
            converter = hashlib.sha256(f.read()).hexdigest()
        text = json.dumps({"scene": by_content(converted), "spp": spp, "pass_spp": CONVERGED_PASS_SPP,
                           "mitsuba": self.version, "variant": self.variant, "converter": converter}, sort_keys=True)
        return hashlib.sha256(text.encode()).hexdigest()[:20]

    def converged(self, scene, size, spp, max_depth, cache_dir):
        """A Converged image at `spp`, rendered in passes of CONVERGED_PASS_SPP; cached.

        The variances (over the passes, of their mean) are the converged image's own noise, which every
        relMSE against it carries as a floor: of each value, and of each pixel's mean over its channels (the
        channels of a pixel come from the same paths, so they are not independent)."""
        key = self.cache_key(scene, size, spp, max_depth)
        path = os.path.join(cache_dir, f"converged-{os.path.basename(scene)}-{size}-{spp}spp-depth{max_depth}-{key}.npz")
        if os.path.exists(path):
            with np.load(path) as cached:
                if "pixel_variance" in cached.files:  # caches written before it had none
                    return Converged(cached["image"], cached["variance"], cached["pixel_variance"], path)
        passes = max(2, spp // CONVERGED_PASS_SPP)
        images = np.stack([self.render(scene, size, spp // passes, seed=20_000 + k, max_depth=max_depth)["image"]
                           for k in range(passes)])
        image, variance = images.mean(axis=0), images.var(axis=0, ddof=1) / passes
        pixel_variance = images.reshape(passes, -1, 3).mean(axis=-1).var(axis=0, ddof=1) / passes
        os.makedirs(cache_dir, exist_ok=True)
        np.savez(path, image=image, variance=variance, pixel_variance=pixel_variance)
        return Converged(image, variance, pixel_variance, path)


def file_digest(path):
    with open(path, "rb") as f:
        return hashlib.sha256(f.read()).hexdigest()
