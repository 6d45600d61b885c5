#!/usr/bin/env python3
"""Fails when the build uses a Debian package that scripts/setup.sh does not install.

Usage: python3 scripts/check_packages.py --source DIR --build DIR

A package installed by hand on a developer's or CI's machine hides a missing
install step: the build passes there and fails on a fresh one. This collects
every file under /usr that the build touches and maps each to its package:

  - configuring: every path in CMake's expanded trace of a fresh configure of
    the source tree (package configs, and the files their imported targets
    name, which CMake checks exist);
  - compiling: every header in the build tree's compiler depfiles (*.d);
  - linking: every shared library the built executables load (ldd).

Each package must be in the closure of `setup.sh --list-packages` under
Depends and Pre-Depends (apt-cache depends --recurse --installed), or be part
of every Debian system (Essential: yes, or Priority: required). Prints one
line per offending file and exits 1; exits 0 with a summary otherwise.
"""

import argparse
import os
import re
import subprocess
import sys
import tempfile
from pathlib import Path

USR_PATH = re.compile(r"/usr/[A-Za-z0-9_+.,@/-]+")


def run(command, **kwargs):
    return subprocess.run(command, check=True, text=True, capture_output=True, **kwargs).stdout


def configure_trace_paths(source):
    """Paths under /usr named in the expanded trace of a fresh configure."""
    with tempfile.TemporaryDirectory(prefix="wavepath-packages-") as scratch:
        trace = Path(scratch) / "trace.txt"
        result = subprocess.run(
            ["cmake", "-S", str(source), "-B", str(Path(scratch) / "build"), "-DWAVEPATH_BUILD_TESTS=ON",
             "-DWAVEPATH_BUILD_BENCH=ON", "--trace-expand", f"--trace-redirect={trace}"],
            text=True, capture_output=True)
        text = trace.read_text(errors="replace") if trace.exists() else ""
        if result.returncode != 0:
            # A configure that fails on a file that is not there still names it in
            # the trace; report the failure, then check what it did find.
            print("check_packages: configuring a fresh build failed:\n" + result.stderr.strip(), file=sys.stderr)
    return set(USR_PATH.findall(text)), result.returncode == 0


def depfile_paths(build):
    paths = set()
    for depfile in Path(build).rglob("*.d"):
        paths.update(USR_PATH.findall(depfile.read_text(errors="replace")))
    return paths


def executables(build):
    for path in Path(build).iterdir():
        if path.is_file() and os.access(path, os.X_OK) and path.read_bytes()[:4] == b"\x7fELF":
            yield path
    yield from (p for p in Path(build, "tests").glob("test_*") if p.is_file() and os.access(p, os.X_OK))


def linked_library_paths(build):
    paths = set()
    for binary in executables(build):
        for line in run(["ldd", str(binary)]).splitlines():
            match = re.search(r"=> (/\S+)", line) or re.match(r"\s*(/\S+)", line)
            if match:
                paths.add(os.path.realpath(match.group(1)))
    return paths


def owning_packages(paths):
    """{path: package} for the files among `paths` that a package owns."""
    files = {p for p in paths if not p.startswith("/usr/local/") and os.path.isfile(p)}
    # Directories are shared by many packages and /usr/local is no package's;
    # a link (update-alternatives, usrmerge) is owned under its target's name.
    names = {path: {path, os.path.realpath(path)} for path in files}
    queried = sorted(set().union(*names.values())) if names else []
    # One dpkg-query for all; it prints "pkg[:arch][, pkg2]: /path" for each owned path.
    result = subprocess.run(["dpkg-query", "-S", *queried], text=True, capture_output=True)
    owner_of = {}
    for line in result.stdout.splitlines():
        if line.startswith("diversion ") or ": " not in line:
            continue
        packages, owned = line.rsplit(": ", 1)
        owner_of[owned] = packages.split(",")[0].split(":")[0].strip()
    return {path: owner_of[name] for path, candidates in names.items()
            for name in sorted(candidates) if name in owner_of}


def allowed_packages(source):
    listed = run(["bash", str(Path(source) / "scripts" / "setup.sh"), "--list-packages"]).split()
    closure = run(["apt-cache", "depends", "--recurse", "--installed", "--no-recommends", "--no-suggests",
                   "--no-conflicts", "--no-breaks", "--no-replaces", "--no-enhances", *listed])
    allowed = {line.strip().strip("<>").split(":")[0] for line in closure.splitlines()
               if line and not line.lstrip().startswith(("Depends:", "PreDepends:", "|Depends:", "|PreDepends:"))}
    for line in run(["dpkg-query", "-W", "-f", "${Package} ${Essential} ${Priority}\n"]).splitlines():
        name, essential, priority = (line.split() + ["", ""])[:3]
        if essential == "yes" or priority == "required":
            allowed.add(name)
    return listed, allowed


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--source", required=True, type=Path)
    parser.add_argument("--build", required=True, type=Path)
    args = parser.parse_args()

    trace_paths, configured = configure_trace_paths(args.source)
    used = {"configure": trace_paths, "compile": depfile_paths(args.build),
            "link": linked_library_paths(args.build)}
    listed, allowed = allowed_packages(args.source)

    bad = []
    packages_used = set()
    for step, paths in used.items():
        for path, package in owning_packages(paths).items():
            packages_used.add(package)
            if package not in allowed:
                bad.append(f"check_packages: {step} uses {path} from Debian package '{package}', which "
                           f"scripts/setup.sh neither installs nor gets as a dependency of what it installs")
    for line in sorted(set(bad)):
        print(line)
    if bad or not configured:
        return 1
    print(f"check_packages: the build uses {len(packages_used)} Debian packages, all within the closure of "
          f"setup.sh's {len(listed)} ({len(allowed)} packages with the base system's)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
