#!/usr/bin/env python3
"""A mutation study of the test suite: does it catch small bugs in the estimator and its guards?

Each mutant (MUTANTS in scripts/mutants.py) is one small change to one source
file: an exact snippet and its replacement, with the tests that claim to cover
that code (gtest filters of test programs). For each mutant in turn the study

  1. checks that the snippet occurs exactly once in the file (else it stops:
     the code moved, and the mutant must be updated, never silently skipped),
  2. writes the mutated file, rebuilds only the targets those tests need (for
     a kernels/shared mutant only the objects that can contain the mutated
     function: see "which objects" below; ccache makes the rebuilds of the
     restored files cheap), and runs those tests with a timeout,
  3. restores the file, always (also on Ctrl-C or SIGTERM; a copy kept in the
     build directory restores it after a kill -9 on the next start).

A mutant is killed when one of its tests fails, crashes or runs past the
timeout; it survives when they all pass. Before the mutants, a baseline run
builds the unmutated targets and runs each mutant's tests once: they must
pass, or the study stops (a failing suite kills every mutant), and their times
set each mutant's timeout. Kernels (kernels/*.cl, kernels/device,
kernels/shared) are compiled by OpenCL at run time and cached by their source's
content (BUILD/kernel-cache, as under CTest), so a mutated kernel is rebuilt by
the first test that runs it; kernels/shared is also compiled into the C++
reference and tests.

It writes docs/mutation-study.md (the commit, date, machine, each mutant with
its file:line, its change and the test that killed it or "survived", the kill
rate, and each survivor's reason from the mutant's `note`) and keeps
each mutant's result in BUILD/mutation-study.json, so that rerunning some
mutants with --only updates their rows and keeps the others' (from that file,
or, for mutants it has no result of, from the doc's rows: a fresh clone has
the doc, not the build directory).

It runs by hand, not in CI (40 to 60 minutes on the shared 2-core machine,
mostly compiling the mutants). CI runs only --check (the CTest test
mutation_study_snippets_occur_once): every snippet still occurs exactly once
and every gtest filter still names tests, so the study cannot silently rot
when the code moves.

Usage:
  cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_COMPILER_LAUNCHER=ccache
  scripts/mutation_study.py                    # every mutant, then writes the doc
  scripts/mutation_study.py --only balance-heuristic --only resume-start-ignored
  scripts/mutation_study.py --list             # the mutants and their tests
  scripts/mutation_study.py --check [--build build]
"""
import argparse
import datetime
import json
import os
import pathlib
import platform
import re
import signal
import subprocess
import sys
import time

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
from mutants import MUTANTS  # noqa: E402

ROOT = pathlib.Path(__file__).resolve().parent.parent
DOC = ROOT / "docs" / "mutation-study.md"


def fail(message):
    sys.exit(f"mutation_study: {message}")


# ---------------------------------------------------------------- snippets


def snippet_offset(mutant):
    """The offset of the mutant's snippet in its file; exits unless it occurs exactly once."""
    path = ROOT / mutant.file
    if not path.is_file():
        fail(f"{mutant.name}: {mutant.file} does not exist")
    text = path.read_text()
    count = text.count(mutant.original)
    if count != 1:
        fail(f"{mutant.name}: the snippet occurs {count} times in {mutant.file}, not once "
             f"(the code moved: update scripts/mutants.py): {mutant.original!r}")
    return text.index(mutant.original)


def snippet_line(mutant):
    text = (ROOT / mutant.file).read_text()
    return text.count("\n", 0, snippet_offset(mutant)) + 1


def check_mutants(build):
    """--check: unique names, each snippet once, each replacement differs, each gtest filter names tests."""
    problems = []
    names = [m.name for m in MUTANTS]
    for name in sorted({n for n in names if names.count(n) > 1}):
        problems.append(f"two mutants are named {name}")
    for m in MUTANTS:
        path = ROOT / m.file
        if not path.is_file():
            problems.append(f"{m.name}: {m.file} does not exist")
            continue
        count = path.read_text().count(m.original)
        if count != 1:
            problems.append(f"{m.name}: its snippet occurs {count} times in {m.file}, not once: {m.original!r}")
        if m.original == m.replacement:
            problems.append(f"{m.name}: the replacement is the snippet itself")
        if not m.tests:
            problems.append(f"{m.name}: no tests")
    if build is not None:
        listed = {}
        for m in MUTANTS:
            for run in m.tests:
                binary = build / "tests" / run.binary
                if not binary.is_file():
                    problems.append(f"{m.name}: {binary} is not built")
                    continue
                if run not in listed:
                    try:
                        listed[run] = list_gtests(binary, run.filter)
                    except OSError as error:
                        problems.append(f"{m.name}: cannot run {binary}: {error.strerror}")
                        continue
                if not listed[run]:
                    problems.append(f"{m.name}: {run.binary} has no test matching {run.filter!r}")
    for p in problems:
        print(f"mutation_study --check: {p}", file=sys.stderr)
    if problems:
        sys.exit(1)
    print(f"mutation_study --check: {len(MUTANTS)} mutants, every snippet occurs once"
          + (", every gtest filter names tests" if build is not None else ""))


def list_gtests(binary, gtest_filter):
    out = subprocess.run([str(binary), "--gtest_list_tests", f"--gtest_filter={gtest_filter}"],
                         stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True).stdout
    tests, suite = [], None
    for line in out.splitlines():
        if not line.strip() or line.startswith("Running main"):
            continue
        if not line.startswith(" "):
            suite = line.split()[0]
        elif suite:
            tests.append(suite + line.split()[0])
    return tests


# ---------------------------------------------------------------- the file under mutation


class MutatedFile:
    """Writes the mutant into its file and restores the original on exit, whatever happens.
    A copy of the original in BUILD/mutation-backup restores it after a kill -9 (restore_leftover)."""

    def __init__(self, mutant, build):
        self.path = ROOT / mutant.file
        self.mutant = mutant
        self.backup = build / "mutation-backup"

    def __enter__(self):
        self.original = self.path.read_text()
        self.backup.mkdir(exist_ok=True)
        (self.backup / "path").write_text(self.mutant.file)
        (self.backup / "content").write_text(self.original)
        self.path.write_text(self.original.replace(self.mutant.original, self.mutant.replacement, 1))
        return self

    def __exit__(self, *exc):
        self.path.write_text(self.original)
        (self.backup / "content").unlink()
        (self.backup / "path").unlink()
        return False


def restore_leftover(build):
    backup = build / "mutation-backup"
    if (backup / "path").is_file() and (backup / "content").is_file():
        rel = (backup / "path").read_text()
        (ROOT / rel).write_text((backup / "content").read_text())
        (backup / "content").unlink()
        (backup / "path").unlink()
        print(f"mutation_study: restored {rel}, which an interrupted study had left mutated", file=sys.stderr)


def raise_on_sigterm():
    def handler(signum, frame):
        raise KeyboardInterrupt(f"signal {signum}")

    signal.signal(signal.SIGTERM, handler)


# ---------------------------------------------------------------- building and testing


def targets_of(mutant):
    targets = []
    for run in mutant.tests:
        if run.binary not in targets:
            targets.append(run.binary)
    return targets


# ---------------------------------------------------------------- which objects a shared header's mutant reaches
#
# Every C++ object of the lib and the tests includes all of kernels/shared (through
# core/shared_math.h), so make would recompile ~25 objects for any mutant there, minutes each
# on a shared machine, although the mutated function's code lands in two or three of them. A
# shared function is a member of SharedMath<Real> (or, in film_sum.h, an inline function),
# compiled into an object only where that object's own code names it or a shared function that
# calls it: class template members are instantiated only where used. So the objects to rebuild
# are those whose source or project headers (src/, tests/; not kernels/shared itself, which
# every object includes) name a function of the mutated function's callers' closure; the
# others keep their unmutated code (correctly: they contain none of the mutated function) and
# are marked up to date instead of rebuilt. The closure is textual and over-approximates:
# a name in a comment or a same-named function only adds objects to rebuild.

SHARED = ROOT / "kernels" / "shared"
FUNCTION = re.compile(r"^(?:WP_OVERLOAD\s+)?(?:WP_FN|WP_FILM_FN)\b[^;{(]*?\b(\w+)\s*\(", re.M)
MACRO = re.compile(r"^#\s*define\s+(\w+)((?:.*\\\n)*.*)$", re.M)
COMMENT = re.compile(r"/\*.*?\*/|//[^\n]*", re.S)


def shared_bodies():
    """Every function (and macro) defined in kernels/shared: its name and the text up to the next definition."""
    bodies = {}
    for path in sorted(SHARED.rglob("*.h")):
        text = COMMENT.sub(" ", path.read_text())
        starts = sorted([(m.start(), m.group(1)) for m in FUNCTION.finditer(text)] +
                        [(m.start(), m.group(1)) for m in MACRO.finditer(text)])
        for i, (start, name) in enumerate(starts):
            end = starts[i + 1][0] if i + 1 < len(starts) else len(text)
            bodies[name] = bodies.get(name, "") + text[start:end]
    return bodies


def callers_closure(function):
    """The function and every shared function or macro that calls it, directly or not."""
    bodies = shared_bodies()
    closure, grew = {function}, True
    while grew:
        grew = False
        for name, body in bodies.items():
            if name not in closure and re.search(r"\b(" + "|".join(map(re.escape, closure)) + r")\b", body):
                closure.add(name)
                grew = True
    return closure


def mutated_function(mutant):
    """The shared function whose body holds the mutant's snippet, or None outside kernels/shared."""
    path = ROOT / mutant.file
    if SHARED not in path.parents:
        return None
    text = path.read_text()
    offset = snippet_offset(mutant)
    definitions = [m for m in FUNCTION.finditer(text) if m.start() <= offset]
    return definitions[-1].group(1) if definitions else None


def objects_in(build, targets):
    """The object files (with their depfiles) of the libraries of src/ and the binary and of the test
    programs named."""
    dirs = sorted((build / "CMakeFiles").glob("*.dir")) + sorted((build / "src" / "CMakeFiles").glob("*.dir"))
    dirs += [build / "tests" / "CMakeFiles" / f"{t}.dir" for t in targets]
    return [o for d in dirs if d.is_dir() for o in sorted(d.rglob("*.o")) if o.with_suffix(".o.d").is_file()]


def depfile_paths(obj):
    """The files an object was compiled from, as absolute paths (depfiles name them relative to the object's
    build directory, the compiler's working directory)."""
    text = obj.with_suffix(".o.d").read_text().replace("\\\n", " ")
    words = text.split(":", 1)[1].split()
    cwd = obj.parent
    while cwd.name != "CMakeFiles":
        cwd = cwd.parent
    cwd = cwd.parent
    return [(cwd / w).resolve() for w in words]


def selective_plan(build, mutant, targets):
    """For a mutant in a kernels/shared function: (objects that must be rebuilt, objects to mark up to date),
    or None where make's own rebuild is used."""
    function = mutated_function(mutant)
    if function is None:
        return None
    names = re.compile(r"\b(" + "|".join(map(re.escape, sorted(callers_closure(function)))) + r")\b")
    mutated = (ROOT / mutant.file).resolve()
    rebuild, keep = [], []
    # Every test program's objects, not only the targets': one left out would be taken as out of date after
    # the file's restore and rebuilt by the next mutant that needs it.
    programs = [d.name[:-len(".dir")] for d in (build / "tests" / "CMakeFiles").glob("test_*.dir")]
    for obj in objects_in(build, programs):
        paths = depfile_paths(obj)
        if mutated not in paths:
            continue
        project = [p for p in paths if ROOT in p.parents and SHARED not in p.parents and p.is_file()]
        uses = any(names.search(COMMENT.sub(" ", p.read_text())) for p in project)
        # Only an object as new as everything it was compiled from holds the sources' code now: one
        # that an earlier mutant rebuilt (and whose file was restored since) must be left to make.
        if uses or not up_to_date(obj, paths):
            rebuild.append(obj)
        else:
            keep.append(obj)
    return rebuild, keep


def up_to_date(obj, paths):
    built = obj.stat().st_mtime
    return all(not p.exists() or p.stat().st_mtime <= built for p in paths)


def mark_up_to_date(objects):
    now = time.time()  # not before the mutated file's time stamp: make then leaves them be
    for obj in objects:
        os.utime(obj, (now, now))


def build_targets(build, targets, jobs, log):
    """Builds the targets; returns (ok, seconds). Interrupted, it kills every compiler first (run_process),
    so that none writes an object of the mutated file after the file is restored."""
    start = time.monotonic()
    code, _ = run_process(["cmake", "--build", str(build), f"-j{jobs}", "--target", *targets], None,
                          os.environ, log)
    return code == 0, time.monotonic() - start


def run_process(command, timeout, env, log):
    """Runs the command in its own session; on timeout kills the whole session. Returns
    (exit code or None on timeout, output)."""
    process = subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, env=env,
                               cwd=ROOT, start_new_session=True)
    try:
        output, _ = process.communicate(timeout=timeout)
        code = process.returncode
    except subprocess.TimeoutExpired:
        os.killpg(process.pid, signal.SIGKILL)
        output, _ = process.communicate()
        code = None
    except BaseException:
        os.killpg(process.pid, signal.SIGKILL)
        process.communicate()
        time.sleep(0.5)  # the killed session's grandchildren too
        raise
    log.write(output)
    return code, output


def run_tests(build, runs, timeout, log):
    """Runs the gtest runs in turn, stopping at the first failure. Returns (verdict, seconds): verdict is None
    when every test passed, else the test that failed (or crashed, or was running at the timeout)."""
    env = dict(os.environ, WAVEPATH_CACHE_DIR=str(build / "kernel-cache"))
    start = time.monotonic()
    for run in runs:
        left = max(timeout - (time.monotonic() - start), 1.0)
        command = [str(build / "tests" / run.binary), f"--gtest_filter={run.filter}", "--gtest_fail_fast",
                   "--gtest_color=no"]
        log.write(f"\n$ {' '.join(command)}\n")
        code, output = run_process(command, left, env, log)
        if code is None:
            return f"timeout after {timeout:.0f} s in {running_test(output) or run.binary}", time.monotonic() - start
        if code != 0:
            return failed_test(run, output, code), time.monotonic() - start
        if not re.search(r"^\[  PASSED  \] [1-9]", output, re.M):
            fail(f"{run.binary} ran no test for {run.filter!r}")
    return None, time.monotonic() - start


def kernel_program_mutant(mutant):
    """Whether the mutant changes only OpenCL code (kernels/*.cl, kernels/device), which its tests rebuild."""
    path = ROOT / mutant.file
    return ROOT / "kernels" in path.parents and SHARED not in path.parents


def mutant_timeout(mutant, baseline, fixed):
    """--timeout, else 5 times its tests' unmutated time, at least 180 s, plus 600 s where OpenCL must
    first rebuild the mutated kernels (baseline times are with the kernel cache warm)."""
    if fixed:
        return fixed
    return max(180.0, 5 * sum(baseline[run] for run in mutant.tests)) + (600.0 if kernel_program_mutant(mutant) else 0)


def running_test(output):
    runs = re.findall(r"^\[ RUN      \] (\S+)", output, re.M)
    return runs[-1] if runs else None


def failed_test(run, output, code):
    failed = re.findall(r"^\[  FAILED  \] ([^\s,]+)", output, re.M)
    failed = [f for f in failed if not re.fullmatch(r"\d+", f)]
    if failed:
        return failed[0]
    return f"{run.binary} exit {code} in {running_test(output) or 'its start'}"


# ---------------------------------------------------------------- results and the doc


def git(*args):
    return subprocess.run(["git", *args], cwd=ROOT, stdout=subprocess.PIPE, text=True).stdout.strip()


def commit_described():
    """HEAD's short hash, -dirty when the tree differs from it in more than the doc and the study's own files."""
    changed = [line[3:] for line in git("status", "--porcelain", "--untracked-files=no").splitlines()]
    others = [c for c in changed if c != "docs/mutation-study.md"]
    return git("rev-parse", "--short=7", "HEAD") + ("-dirty" if others else "")


def machine():
    cpu = "unknown CPU"
    try:
        for line in pathlib.Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                cpu = line.split(":", 1)[1].strip()
                break
    except OSError:
        pass
    distro = ""
    try:
        for line in pathlib.Path("/etc/os-release").read_text().splitlines():
            if line.startswith("PRETTY_NAME="):
                distro = line.split("=", 1)[1].strip('"')
    except OSError:
        pass
    compiler = subprocess.run(["c++", "--version"], stdout=subprocess.PIPE, text=True).stdout.splitlines()
    return f"{cpu}, {os.cpu_count()} cores, {distro or platform.platform()}, {compiler[0] if compiler else 'c++'}"


# A row of the doc's table (write_doc): its mutant, verdict, the commit it ran at when the doc names several,
# and its build and test seconds.
DOC_ROW = re.compile(r"^\| \d+ \| `(?P<name>[^`]+)` \| .* \| (?P<verdict>killed: .*?|\*\*survived\*\*|build failed "
                     r"\(not counted\))(?: \(at (?P<commit>\w+)\))? \| (?P<build>\d+) \+ (?P<test>\d+) \|$")


def results_from_doc(doc):
    """The results the doc records (a clone has the doc, not the build directory's results): each run mutant's
    verdict, commit and seconds, and the run's start."""
    results = {"mutants": {}}
    if not doc.is_file():
        return results
    text = doc.read_text()
    commits = re.search(r"^- Commit: (.*)$", text, re.M)
    only_commit = commits.group(1).strip() if commits and "," not in commits.group(1) else None
    started = re.search(r"^- Run: (\d{4}-\d\d-\d\d \d\d:\d\d)", text, re.M)
    if started:
        results["started"] = started.group(1)
    for line in text.splitlines():
        row = DOC_ROW.match(line)
        if not row or not (row["commit"] or only_commit):
            continue
        verdict = row["verdict"]
        verdict = ("survived" if verdict == "**survived**" else "build failed" if verdict.startswith("build failed")
                   else verdict[len("killed: "):])
        results["mutants"][row["name"]] = {"verdict": verdict, "commit": row["commit"] or only_commit,
                                           "build_s": float(row["build"]), "test_s": float(row["test"])}
    return results


def load_results(path, doc):
    """The build directory's results of earlier runs, and for mutants it has none of, the doc's."""
    results = results_from_doc(doc)
    if path.is_file():
        kept = json.loads(path.read_text())
        started = min(filter(None, [results.get("started"), kept.get("started")]))
        results["mutants"].update(kept["mutants"])
        results.update({key: value for key, value in kept.items() if key != "mutants"})
        results["started"] = started
    return results


def save_results(path, results):
    path.write_text(json.dumps(results, indent=1, sort_keys=True) + "\n")


def tests_text(mutant):
    return "; ".join(f"{run.binary} `{run.filter}`" for run in mutant.tests)


def escape_cell(text):
    return text.replace("|", "\\|").replace("\n", " ")


def write_doc(results, doc):
    rows, survivors, killed, counted = [], [], 0, 0
    commits = sorted({r["commit"] for r in results["mutants"].values()})
    for i, m in enumerate(MUTANTS, 1):
        r = results["mutants"].get(m.name)
        where = f"{m.file}:{snippet_line(m)}"
        if r is None:
            verdict = "not run"
        elif r["verdict"] == "build failed":
            verdict = "build failed (not counted)"
        else:
            counted += 1
            if r["verdict"] == "survived":
                verdict = "**survived**"
                survivors.append((i, m))
            else:
                killed += 1
                verdict = f"killed: {r['verdict']}"
        if r is not None and len(commits) > 1:
            verdict += f" (at {r['commit']})"
        seconds = f"{r['build_s']:.0f} + {r['test_s']:.0f}" if r else ""
        rows.append(f"| {i} | `{m.name}` | {where} | {escape_cell(m.change)} | {escape_cell(tests_text(m))} "
                    f"| {escape_cell(verdict)} | {seconds} |")
    rate = f"{killed} of {counted} killed ({100.0 * killed / counted:.1f}%)" if counted else "no mutant run"
    lines = [
        "# Mutation study of the test suite",
        "",
        "<!-- Written by scripts/mutation_study.py; do not edit by hand: rerun the study. -->",
        "",
        "Each mutant is one small change to the estimator or one of its guards; the study",
        "applies it, rebuilds what the tests it names need, runs those tests (the ones that",
        "claim to cover the code) and restores the file. A mutant is **killed** when one of",
        "those tests fails, crashes or runs past the timeout, and **survives** when they all pass.",
        "The mutants, their snippets and their tests are in `scripts/mutants.py`.",
        "",
        f"- Commit: {', '.join(commits) if commits else 'none'}",
        (f"- Run: {results.get('started', '?')} (UTC), **interrupted** after {len(results['mutants'])} of "
         f"{len(MUTANTS)} mutants: the rows \"not run\" were not tried" if results.get("interrupted") else
         f"- Run: {results.get('started', '?')} to {results.get('finished', '?')} (UTC)"),
        f"- Machine: {results.get('machine', '?')}",
        f"- Timeout per mutant: {results.get('timeout', '?')}",
        f"- **Kill rate: {rate}.** Target: at least 90%.",
        "",
        "| # | Mutant | Where | Change | Tests run | Result | Build + test s |",
        "|---|---|---|---|---|---|---|",
        *rows,
        "",
        "## Survivors",
        "",
    ]
    if not survivors:
        lines.append("None.")
    for i, m in survivors:
        lines.append(f"- **{i}. `{m.name}`**: {m.note or 'no reason written yet.'}")
    noted = [(i, m) for i, m in enumerate(MUTANTS, 1) if m.note and (i, m) not in survivors]
    if noted:
        lines += ["", "## Notes on killed mutants", ""]
        lines += [f"- **{i}. `{m.name}`**: {m.note}" for i, m in noted]
    lines += [
        "",
        "## Running the study",
        "",
        "By hand, not in CI (40 to 60 minutes on the shared 2-core machine, mostly compiling the mutants):",
        "",
        "```sh",
        "cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_COMPILER_LAUNCHER=ccache",
        "scripts/mutation_study.py                         # every mutant; writes this file",
        "scripts/mutation_study.py --only NAME [--only ...] # rerun some; keeps the others' rows",
        "scripts/mutation_study.py --list                  # the mutants and their tests",
        "```",
        "",
        "The source tree must be clean apart from this file. The mutated file is restored",
        "after each mutant, also on Ctrl-C; after a kill -9 the next start restores it from",
        "`build/mutation-backup`. CI runs `scripts/mutation_study.py --check` (the CTest test",
        "`mutation_study_snippets_occur_once`): every snippet still occurs exactly once in its",
        "file and every gtest filter still names tests, so a mutant whose code moved fails",
        "the check instead of silently surviving or vanishing from the study.",
        "",
    ]
    doc.write_text("\n".join(lines))


# ---------------------------------------------------------------- main


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--build", type=pathlib.Path, default=ROOT / "build",
                        help="configured build directory (default: build)")
    parser.add_argument("--check", action="store_true",
                        help="only check that every snippet occurs once (and, with --build given or built, "
                             "that every gtest filter names tests); changes nothing")
    parser.add_argument("--list", action="store_true", help="list the mutants and their tests")
    parser.add_argument("--only", action="append", default=[], metavar="NAME", help="run only this mutant")
    parser.add_argument("--timeout", type=float, default=0,
                        help="seconds per mutant's tests (default: 5 x their unmutated time, at least 180, "
                             "+600 for OpenCL-only mutants)")
    parser.add_argument("--jobs", type=int, default=2, help="build jobs (default 2)")
    parser.add_argument("--doc", type=pathlib.Path, default=DOC, help="the document to write")
    parser.add_argument("--no-doc", action="store_true", help="do not write the document")
    args = parser.parse_args()
    build = args.build.resolve()

    if args.check:
        check_mutants(build if (build / "tests").is_dir() else None)
        return
    if args.list:
        for i, m in enumerate(MUTANTS, 1):
            print(f"{i:2}. {m.name}: {m.file}:{snippet_line(m)}: {m.change}\n    tests: {tests_text(m)}")
        return
    unknown = [n for n in args.only if n not in {m.name for m in MUTANTS}]
    if unknown:
        fail(f"no mutant named {', '.join(unknown)} (see --list)")
    if not (build / "CMakeCache.txt").is_file():
        fail(f"{build} is not a configured build directory (see --help)")

    restore_leftover(build)
    raise_on_sigterm()
    check_mutants(None)
    if [c for c in git("status", "--porcelain", "--untracked-files=no").splitlines()
            if c[3:] != "docs/mutation-study.md"] and not os.environ.get("MUTATION_STUDY_DIRTY_OK"):
        fail("the source tree has uncommitted changes; commit them first (the doc records the commit)")
    chosen = [m for m in MUTANTS if not args.only or m.name in args.only]

    results_path = build / "mutation-study.json"
    results = load_results(results_path, args.doc) if args.only else {"mutants": {}}
    log_path = build / "mutation-study.log"
    started = datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M")
    with open(log_path, "w") as log:
        # The baseline: every chosen mutant's tests pass unmutated, and their times set the timeout.
        targets = []
        for m in chosen:
            targets += [t for t in targets_of(m) if t not in targets]
        print(f"baseline: building {' '.join(targets)}", flush=True)
        ok, _ = build_targets(build, targets, args.jobs, log)
        if not ok:
            fail(f"the unmutated build fails (see {log_path})")
        baseline = {}
        for m in chosen:
            for run in m.tests:
                if run in baseline:
                    continue
                verdict, baseline[run] = run_tests(build, [run], 3600, log)
                if verdict is not None:
                    fail(f"{run.binary} {run.filter!r} fails without any mutation ({verdict}); see {log_path}")
                print(f"baseline: {run.binary} {run.filter}: pass, {baseline[run]:.0f} s", flush=True)

        commit = commit_described()
        results["started"] = started if not args.only else results.get("started", started)
        results["machine"] = machine()
        results["timeout"] = (f"{args.timeout:.0f} s" if args.timeout else
                              "5 times the mutant's tests' unmutated time, at least 180 s, plus 600 s for a "
                              "mutant of kernels/*.cl or kernels/device (OpenCL rebuilds the kernels first)")
        try:
            run_mutants(build, chosen, baseline, commit, results, results_path, args, log)
        except KeyboardInterrupt:
            results["interrupted"] = True
            save_results(results_path, results)
            if not args.no_doc:
                write_doc(results, args.doc)
            raise
        # Leave the build as the sources are (the restored files' rebuilds are ccache hits).
        build_targets(build, targets, args.jobs, log)
    results["interrupted"] = False
    results["finished"] = datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M")
    save_results(results_path, results)
    if not args.no_doc:
        write_doc(results, args.doc)
        print(f"wrote {args.doc}")


def run_mutants(build, chosen, baseline, commit, results, results_path, args, log):
    """Each mutant in turn; its result is saved as soon as it is known."""
    for i, m in enumerate(chosen, 1):
        line = snippet_line(m)
        log.write(f"\n======== {m.name} ({m.file}:{line})\n")
        plan = selective_plan(build, m, targets_of(m))
        rebuilt = "make's" if plan is None else f"{len(plan[0])} of {len(plan[0]) + len(plan[1])}"
        log.write(f"objects rebuilt: {rebuilt}" +
                  ("" if plan is None else ": " + " ".join(o.name for o in plan[0])) + "\n")
        try:
            with MutatedFile(m, build):
                if plan is not None:
                    mark_up_to_date(plan[1])
                built, build_s = build_targets(build, targets_of(m), args.jobs, log)
                if built:
                    timeout = mutant_timeout(m, baseline, args.timeout)
                    verdict, test_s = run_tests(build, m.tests, timeout, log)
                    verdict = verdict or "survived"
                else:
                    verdict, test_s = "build failed", 0.0
        finally:
            if plan is not None:
                mark_up_to_date(plan[1])  # they hold the restored file's code already
        results["mutants"][m.name] = {"verdict": verdict, "build_s": build_s, "test_s": test_s,
                                      "commit": commit, "line": line, "objects_rebuilt": rebuilt}
        save_results(results_path, results)
        print(f"[{i}/{len(chosen)}] {m.name}: {verdict} ({build_s:.0f} s build of {rebuilt} objects, "
              f"{test_s:.0f} s tests)",
              flush=True)


if __name__ == "__main__":
    try:
        main()
    except KeyboardInterrupt:
        sys.exit("mutation_study: interrupted; the mutated file was restored")
