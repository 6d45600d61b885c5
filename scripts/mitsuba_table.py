"""The command line of a script that writes a table from Mitsuba 3 into a committed header
(scripts/named_media.py, scripts/plastic_reference.py): it writes the table, or with --check compares it with
the committed one (exit 1 and a diff where they differ, 77 where Mitsuba is not installed, as CTest's
SKIP_RETURN_CODE takes it).

The comparison takes the text between the numbers exactly and each number to within ULPS float32 units in the
last place: Mitsuba's JIT compiles its code for the CPU it runs on, and on another CPU (AVX-512 or AVX2, fused
multiply-adds or not) a value can come out a few float32 ulps away (seen: 4 of the plastic table's 1155
numbers, 1 to 6 ulps, on a haswell-class EPYC against the table written on another machine). Well below what
the tests that read the tables tolerate (tests/shared/plastic_test.cpp: 16 float ulps)."""
import argparse
import difflib
import pathlib
import re
import sys

import numpy as np

ROOT = pathlib.Path(__file__).resolve().parent.parent
SKIP = 77
ULPS = 8
NUMBER = re.compile(r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?")


def ulps_apart(a, b):
    """How many float32 units in the last place lie between two decimal numbers' float32 values."""
    x, y = np.float32(float(a)), np.float32(float(b))
    if x == y:
        return 0
    if not (np.isfinite(x) and np.isfinite(y)):
        return float("inf")
    return abs(float(x) - float(y)) / float(np.spacing(max(abs(x), abs(y))))


def same_table(committed, text):
    """The two texts equal but for numbers within ULPS float32 ulps of each other; and the most ulps seen."""
    if NUMBER.split(committed) != NUMBER.split(text):
        return False, None
    apart = [ulps_apart(a, b) for a, b in zip(NUMBER.findall(committed), NUMBER.findall(text))]
    worst = max(apart, default=0)
    return worst <= ULPS, worst


def table_main(name, description, path, table):
    """`table(mi, variant)` gives the text of `path`; `name` prefixes every line printed."""
    parser = argparse.ArgumentParser(description=description)
    parser.add_argument("--check", action="store_true", help="compare with the committed table, write nothing")
    parser.add_argument("--variant", default="llvm_ad_rgb")
    args = parser.parse_args()
    try:
        import mitsuba_scene

        mi = mitsuba_scene.open_mitsuba(args.variant)
        mi.set_log_level(mi.LogLevel.Error)  # not its warnings about spectra clamped into the sRGB gamut
    except ImportError as error:
        print(f"{name}: skipped, Mitsuba is not installed ({error})")
        return SKIP
    text = table(mi, args.variant)
    shown = path.relative_to(ROOT)
    if args.check:
        committed = path.read_text() if path.exists() else ""
        same, worst = same_table(committed, text)
        if not same:
            sys.stdout.writelines(difflib.unified_diff(committed.splitlines(True), text.splitlines(True), str(path),
                                                       "from Mitsuba"))
            print(f"{name}: the table differs from Mitsuba's (beyond {ULPS} float32 ulps); run scripts/{name}.py")
            return 1
        print(f"{name}: {shown} matches Mitsuba {mi.__version__} (values within {worst:g} float32 ulps, "
              f"at most {ULPS})")
        return 0
    path.write_text(text)
    print(f"{name}: wrote {shown}")
    return 0
