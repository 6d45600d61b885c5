#!/usr/bin/env bash
# Runs a libFuzzer target of tests/fuzz on its seeds for a while (fixed seed)
# and exits non-zero on any crash, sanitizer report, leak, hang (-timeout) or
# excess memory (-rss_limit_mb). Inputs that fail are written to the current
# directory (crash-*, timeout-*, oom-*, leak-*); rerun one with
# `FUZZER FILE`. New inputs grow a scratch corpus, removed at the end.
# Usage: bash tests/fuzz/run_fuzzer.sh FUZZER scene|mesh|film|xml|serialized|gltf SECONDS|runs=N [libFuzzer flags...]
#   e.g. bash tests/fuzz/run_fuzzer.sh build-asan/tests/fuzz/fuzz_scene scene 600
# runs=N fuzzes N inputs instead of for a time: the same inputs on any
# machine (CTest's short runs), where a time limit reaches further on a faster one.
# With WAVEPATH_FUZZ_IMPORT_FAILURES=DIR, fuzz_mesh and fuzz_scene keep in DIR
# the inputs whose import failed inside wavepath-import (crash, limit,
# malformed answer: wavepath's one error, not a finding; tests/fuzz/import_failures.h).
set -euo pipefail
fuzzer=$(realpath "$1") name=$2 limit=$3
shift 3
case "$limit" in runs=*) budget=-$limit ;; *) budget=-max_total_time=$limit ;; esac
root=$(cd "$(dirname "$0")/../.." && pwd)
corpus=$(mktemp -d "${TMPDIR:-/tmp}/wavepath-fuzz-$name-XXXXXX")
trap 'rm -rf "$corpus"' EXIT

case "$name" in
  # The malformed scenes and the bundled valid ones.
  scene) cp "$root"/tests/corpus/bad/scenes/*.json "$root"/scenes/*.json "$corpus"/ ;;
  # The corpus's mesh files and the Cornell box, each as "<extension>\n<bytes>".
  mesh)
    for file in "$root"/tests/corpus/bad/scenes/* "$root"/scenes/meshes/cornell_box.obj; do
      extension=${file##*.}
      case "$extension" in obj | ply | off | stl | gltf | glb) ;; *) continue ;; esac
      { printf '%s\n' "$extension"; cat "$file"; } > "$corpus/$(basename "$file")"
    done ;;
  # The malformed Mitsuba XML scenes and the valid ones of the tests.
  xml) cp "$root"/tests/corpus/bad/xml/*.xml "$root"/scenes/test/mitsuba/*.xml "$corpus"/ ;;
  # The corpus's serialized files, and a valid one of two meshes (tests/fuzz/seeds).
  serialized) cp "$root"/tests/corpus/bad/xml/*.serialized "$root"/tests/fuzz/seeds/*.serialized "$corpus"/ ;;
  # The malformed glTF scenes and the valid ones of the tests, each as "<extension>\n<bytes>".
  gltf)
    for file in "$root"/tests/corpus/bad/gltf/*.gltf "$root"/scenes/test/gltf/*.gltf "$root"/scenes/test/gltf/*.glb; do
      { printf '%s\n' "${file##*.}"; cat "$file"; } > "$corpus/$(basename "$file")"
    done ;;
  # The corpus's malformed checkpoints and a valid film (tests/fuzz/seeds).
  film) cp "$root"/tests/corpus/bad/checkpoints/*.wpfilm "$root"/tests/fuzz/seeds/*.wpfilm "$corpus"/ ;;
  *) echo "run_fuzzer: unknown fuzzer '$name' (scene, mesh, film, xml, serialized or gltf)" >&2; exit 2 ;;
esac

echo "run_fuzzer: $(basename "$fuzzer") for $limit on $(ls "$corpus" | wc -l) seeds" >&2
"$fuzzer" -seed=1 "$budget" -timeout=15 -rss_limit_mb=2048 -print_final_stats=1 \
  "$@" "$corpus"
