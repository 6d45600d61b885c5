#!/usr/bin/env python3
"""Writes the malformed checkpoints of tests/corpus/bad/checkpoints/ and their table.

Usage: python3 scripts/make_checkpoint_corpus.py BUILD/wavepath

Each case is resumed by `wavepath render scenes/test/room_small.json -o OUT
--width 4 --height 4 --spp 2 --resume CASE` (tests/cli/bad_input_corpus_test.cpp).
The valid films are rendered by the binary; the broken ones are edited bytes
of one of them (docs/long-renders.md, "Film files"), with the checksum
recomputed where the case is about another field. The expected error lines
are written here by hand, never taken from the binary's output.
"""

import struct
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
SCENE = ROOT / "scenes/test/room_small.json"
OUT = ROOT / "tests/corpus/bad/checkpoints"
FNV_OFFSET, FNV_PRIME = 0xCBF29CE484222325, 0x100000001B3
# Byte offsets of the header's fields.
VERSION, FLAGS, WIDTH, BEGIN, LIMBS = 8, 12, 48, 56, 72
HEADER = 80
PIXEL_BYTES = 96  # three sums of four 64-bit limbs


def fnv1a64(data):
    h = FNV_OFFSET
    for byte in data:
        h = ((h ^ byte) * FNV_PRIME) & 0xFFFFFFFFFFFFFFFF
    return h


def resign(data):
    """The bytes with their checksum recomputed."""
    body = bytes(data[:-8])
    return body + struct.pack("<Q", fnv1a64(body))


def with_u32(data, offset, value):
    data = bytearray(data)
    data[offset:offset + 4] = struct.pack("<I", value)
    return resign(data)


def render(binary, scratch, name, *flags, scene=SCENE, height=4, spp=2):
    path = Path(scratch) / f"{name}.wpfilm"
    subprocess.run([binary, "render", str(scene), "-o", str(path), "-q", "--width", "4", "--height", str(height),
                    "--spp", str(spp), *flags], check=True)
    return path.read_bytes()


def main():
    binary = sys.argv[1]
    with tempfile.TemporaryDirectory() as scratch:
        good = render(binary, scratch, "good")
        films = {
            "other_settings": render(binary, scratch, "other_settings", "--seed", "1"),
            "other_size": render(binary, scratch, "other_size", height=8),
            "other_estimator": render(binary, scratch, "other_estimator", "--backend", "reference",
                                      "--intersector", "bvh"),
            "more_samples": render(binary, scratch, "more_samples", spp=3),
            "not_from_the_start": render(binary, scratch, "not_from_the_start", "--samples", "1:2"),
        }
        # Another scene: the same room with its light a little brighter.
        other = SCENE.read_text().replace('"radiance": [14, 14, 14]', '"radiance": [15, 14, 14]')
        assert other != SCENE.read_text()
        other_path = Path(scratch) / "other.json"
        other_path.write_text(other)
        films["other_scene"] = render(binary, scratch, "other_scene", scene=other_path)

    size = len(good)
    flipped = bytearray(good)
    flipped[HEADER + 5 * PIXEL_BYTES + 3] ^= 0x10
    backwards = bytearray(good)
    backwards[BEGIN:BEGIN + 16] = struct.pack("<QQ", 10, 5)
    cases = {
        "empty": (b"", "not a wavepath film file (no WPFILM signature)"),
        "wrong_magic": (b"X" + good[1:], "not a wavepath film file (no WPFILM signature)"),
        "a_pfm_image": (b"PF\n4 4\n-1\n" + bytes(192),
                                     "not a wavepath film file (no WPFILM signature)"),
        "truncated_in_the_version": (good[:10], "truncated (10 bytes)"),
        "truncated_in_the_header": (good[:60], "truncated (60 bytes, shorter than the header)"),
        "truncated": (good[:-100], f"truncated ({size - 100} bytes of {size})"),
        "bytes_after_the_checksum": (good + b"tail\n", "corrupted (5 bytes after the checksum)"),
        "checksum_mismatch": (bytes(flipped), "corrupted (checksum mismatch)"),
        "newer_version": (with_u32(good, VERSION, 5), "film format version 5 is newer than this wavepath reads (4)"),
        "version_zero": (with_u32(good, VERSION, 0), "film format version 0 does not exist"),
        "unknown_flags": (with_u32(good, FLAGS, 8), "unknown flags 8"),
        "squares_flagged_but_absent": (with_u32(good, FLAGS, 1),
                                       f"truncated ({size} bytes of {size + 16 * PIXEL_BYTES})"),
        "zero_width": (with_u32(good, WIDTH, 0), "corrupted header (size 0x4)"),
        "huge_size": (with_u32(good, WIDTH, 1 << 30), f"corrupted header (size {1 << 30}x4)"),
        "other_limbs": (with_u32(good, LIMBS, 3), "film sums of 3 limbs and 100 fraction bits, this wavepath "
                                                  "keeps 4 and 100"),
        "backwards_range": (resign(backwards), "corrupted header (work items 10 to 5)"),
        "other_scene": (films["other_scene"], "rendered from another scene (its content differs)"),
        "other_settings": (films["other_settings"], "rendered with other settings (max_depth, rr_depth, seed, nee, mis, "
                                                    "hemisphere, sampler, adaptive sampling or the "
                                                    "integrator and its settings differ)"),
        "other_size": (films["other_size"], "a film of 4x8 pixels, this render is 4x4"),
        "other_estimator": (films["other_estimator"], "rendered by the reference-float estimator, this render uses "
                                                      "opencl"),
        "more_samples": (films["more_samples"], "holds 3 samples per pixel, more than the 2 this render asks for "
                                                "(--spp, --samples)"),
        "not_from_the_start": (films["not_from_the_start"], "starts at work item 16, this render at 0"),
    }
    OUT.mkdir(parents=True, exist_ok=True)
    lines = [
        "# Each case file of this directory, a tab, and the whole error line wavepath prints for it",
        "# after \"wavepath: error: \"; {input} stands for the case's path. Each is resumed by",
        "# wavepath render scenes/test/room_small.json -o OUT --width 4 --height 4 --spp 2 --resume CASE;",
        "# scripts/make_checkpoint_corpus.py writes them, tests/cli/bad_input_corpus_test.cpp checks them.",
    ]
    for name, (data, message) in sorted(cases.items()):
        (OUT / f"{name}.wpfilm").write_bytes(data)
        lines.append(f"{name}.wpfilm\t{{input}}: {message}")
    (OUT / "expected_errors.tsv").write_text("\n".join(lines) + "\n")
    print(f"wrote {len(cases)} cases to {OUT}")


if __name__ == "__main__":
    main()
