#!/usr/bin/env bash
# The GPU check, for a machine with an OpenCL GPU (docs/architecture.md, "GPU
# targets"): runs the test programs that render on the first GPU (wavepath and
# the tests take it when no device is named) and the benchmark's throughput
# series, and writes what they print into bench/results/gpu-<device>/, the
# device's name in lower case with every other character a '-':
#   summary.md      the device, the commit, each program's result and time
#   test_<name>.txt each test program's output (test_<name>.json: GoogleTest's)
#   render.txt      a small render's --explain, which names the device it ran on
#   bench/          bench/run.py --series throughput's files (summary.md, throughput.csv, ...)
# Without an OpenCL GPU it prints one line and exits 1, having run nothing.
# Exit status 0 when the render ran on the GPU, every program passed (each
# within an hour) and the bench ran, else 1.
#
# Usage: bash scripts/gpu_check.sh [--quick] [--no-bench] [--build DIR]
#   --quick      the bench's --quick sizes (a few minutes) instead of its full throughput series
#   --no-bench   the test programs only
#   --build DIR  the build tree (default build/): configured if it has no CMakeCache.txt,
#                and the targets run here built in it (scripts/setup.sh installs what they need)
# GTEST_FILTER narrows the tests as usual (e.g. GTEST_FILTER='*Lanes*').
set -euo pipefail
cd "$(dirname "$0")/.."

build=build
bench=full
while (($#)); do
  case "$1" in
    --quick) bench=quick ;;
    --no-bench) bench=none ;;
    --build)
      (($# >= 2)) || { echo "gpu_check: --build needs a directory" >&2; exit 2; }
      build=$2
      shift
      ;;
    *) echo "gpu_check: unknown argument '$1' (--quick, --no-bench, --build DIR)" >&2; exit 2 ;;
  esac
  shift
done
jobs=$(nproc)

configure() {
  [[ -f $build/CMakeCache.txt ]] ||
    cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release -DWAVEPATH_BUILD_TESTS=ON -DWAVEPATH_BUILD_BENCH=ON >/dev/null
}

# The device first: wavepath lists them (building it if it is not there yet).
if [[ ! -x $build/wavepath ]]; then
  configure
  cmake --build "$build" -j "$jobs" --target wavepath >/dev/null
fi
if ! listing=$("$build/wavepath" devices 2>&1); then
  echo "gpu_check: no OpenCL GPU: $(printf '%s\n' "$listing" | grep -v '^$' | tail -n 1); nothing run" >&2
  exit 1
fi
# "[0] NAME" then "    type: GPU, compute units: ..." for each device, in choose_device's order.
gpu=$(printf '%s\n' "$listing" | awk '
  /^\[[0-9]+\] / { name = $0; sub(/^\[[0-9]+\] /, "", name) }
  /^ +type: GPU,/ { print name; exit }')
if [[ -z $gpu ]]; then
  others=$(printf '%s\n' "$listing" | awk '
    /^\[[0-9]+\] / { name = $0; sub(/^\[[0-9]+\] /, "", name) }
    /^ +type: / { type = $2; sub(/,$/, "", type); printf "%s%s (%s)", sep, name, type; sep = ", " }')
  echo "gpu_check: no OpenCL GPU device (wavepath devices lists: ${others:-none}); nothing run" >&2
  exit 1
fi
slug=$(printf '%s' "$gpu" | tr '[:upper:]' '[:lower:]' | sed -E 's/[^a-z0-9]+/-/g; s/^-+//; s/-+$//')
out=bench/results/gpu-$slug
mkdir -p "$out"
echo "gpu_check: $gpu: writing $out/" >&2

# The test programs that render: those whose rooms (tests/CMakeLists.txt,
# WAVEPATH_TEST_ROOMS_<name>) include an OpenCL backend, or the command line,
# which runs them.
mapfile -t programs < <(sed -nE 's/^set\(WAVEPATH_TEST_ROOMS_([a-z_]+) (.*)\)$/\1 \2/p' tests/CMakeLists.txt |
  awk '{ for (i = 2; i <= NF; ++i)
           if ($i == "wavefront" || $i == "megakernel" || $i == "cli") { print "test_" $1; break } }')
((${#programs[@]})) || { echo "gpu_check: no test programs found in tests/CMakeLists.txt" >&2; exit 1; }
configure
cmake --build "$build" -j "$jobs" --target wavepath "${programs[@]}" >"$out/build.txt" 2>&1 ||
  { echo "gpu_check: the build failed (its output: $out/build.txt)" >&2; exit 1; }

export WAVEPATH_CACHE_DIR="$(cd "$build" && pwd)/kernel-cache"  # as CTest's (tests/CMakeLists.txt)
failed=0
{
  echo "# GPU check: $gpu"
  echo
  commit=$(git describe --always --dirty --abbrev=12 2>/dev/null || echo unknown)
  echo "- commit $commit, $(date -u '+%Y-%m-%d %H:%M:%S UTC'), $(uname -n)"
  echo "- GTEST_FILTER: ${GTEST_FILTER:-(none: every test)}"
  echo
  echo '```'
  printf '%s\n' "$listing"
  echo '```'
  echo
} >"$out/summary.md"

# A small render first: its --explain names the device the renders run on.
if "$build/wavepath" render scenes/cornell.json -o "$out/render.pfm" --spp 1 --width 32 --height 32 --explain \
  >"$out/render.txt" 2>&1; then
  device=$(grep -m 1 '^device:' "$out/render.txt" || true)
  if [[ $device == "device: $gpu ("* ]]; then
    echo "- render: $device" >>"$out/summary.md"
  else
    echo "- render: NOT ON THE GPU ($device): the tests would not run there either" >>"$out/summary.md"
    failed=1
  fi
else
  echo "- render: FAILED (render.txt)" >>"$out/summary.md"
  failed=1
fi
rm -f "$out/render.pfm"

echo >>"$out/summary.md"
echo "| test program | result | seconds | GoogleTest's last line |" >>"$out/summary.md"
echo "| --- | --- | --- | --- |" >>"$out/summary.md"
for program in "${programs[@]}"; do
  echo "gpu_check: $program" >&2
  start=$(date +%s)
  if timeout 3600 "$build/tests/$program" --gtest_output="json:$PWD/$out/$program.json" >"$out/$program.txt" 2>&1; then
    result=passed
  else
    result=FAILED
    failed=1
  fi
  last=$(grep -E '^\[  (PASSED|FAILED)  \]|tests? ran\.' "$out/$program.txt" | tail -n 1 || true)
  echo "| $program | $result | $(($(date +%s) - start)) | ${last:-(none)} |" >>"$out/summary.md"
done

if [[ $bench != none ]]; then
  echo "gpu_check: bench/run.py --series throughput" >&2
  quick=()
  [[ $bench == quick ]] && quick=(--quick)
  start=$(date +%s)
  if python3 bench/run.py --series throughput "${quick[@]}" --out "$out/bench" --binary "$build/wavepath" \
    >"$out/bench.txt" 2>&1; then
    result=passed
  else
    result=FAILED
    failed=1
  fi
  {
    echo
    echo "- bench/run.py --series throughput ${quick[*]}: $result in $(($(date +%s) - start)) s" \
      "(bench.txt, bench/summary.md)"
  } >>"$out/summary.md"
fi

if ((failed)); then
  echo "gpu_check: $gpu: something failed; see $out/summary.md" >&2
  exit 1
fi
echo "gpu_check: $gpu: every test program passed; see $out/summary.md" >&2
