#!/usr/bin/env python3
"""Writes docs/mitsuba.md's figures at this commit, or checks them.

Two runs, each writing its table between its markers in the doc: the oracle
over every shipped scene (tests/oracle/mitsuba_oracle.py, the CTest
wavepath_agrees_with_mitsuba at its default settings) and its sensitivity on
every shipped scene (tests/oracle/oracle_sensitivity_test.py --all: wavepath's
lights 3% too bright must fail it). --check renders the same and compares the
figures (every column but the times) with the doc's, writing nothing: exit 1
when they differ, so that the doc's figures are known to be this commit's
(the renders are deterministic: fixed seeds in both renderers). About 5
minutes on the 2-core development machine; not part of CTest.

Usage: python3 scripts/mitsuba_figures.py [--check] [--binary build/wavepath] [--doc docs/mitsuba.md]
"""
import argparse
import os
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
ORACLE = os.path.join(ROOT, "tests", "oracle")


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--binary", default=os.path.join(ROOT, "build", "wavepath"))
    parser.add_argument("--doc", default=os.path.join(ROOT, "docs", "mitsuba.md"))
    parser.add_argument("--check", action="store_true", help="compare the doc's figures with this run's")
    args = parser.parse_args()
    doc = ["--check-doc" if args.check else "--doc", args.doc]
    runs = [[os.path.join(ORACLE, "mitsuba_oracle.py"), "--binary", args.binary, *doc],
            [os.path.join(ORACLE, "oracle_sensitivity_test.py"), "--all", "--binary", args.binary, *doc]]
    failed = [os.path.basename(run[0]) for run in runs if subprocess.run([sys.executable, *run]).returncode != 0]
    if failed:
        print(f"mitsuba_figures: {', '.join(failed)} failed{' or differ from ' + args.doc if args.check else ''}")
        return 1
    print(f"mitsuba_figures: {args.doc} {'agrees with this run' if args.check else 'written'}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
