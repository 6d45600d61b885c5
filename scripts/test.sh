#!/usr/bin/env bash
# Sets up, builds, and runs the whole test suite through CTest; then builds
# everything again with AddressSanitizer and UndefinedBehaviorSanitizer
# (clang, in build-asan, with the libFuzzer targets) and runs the whole suite
# there once more, with the fuzzers' short runs, but the four checks that run
# none of our C++ (docs/bad-input.md, "The sanitizer build": which, and
# where the time goes: test_cli, test_wavefront and test_robustness took 180
# CPU s there at a077ad2, not the 3-20 minutes each once measured, because
# PoCL's cache holds the kernels the normal suite compiled).
# Usage: bash scripts/test.sh
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
ctest --test-dir build --output-on-failure -j "$(nproc)"

# Without MPI: CI also builds wavepath without its optional component (and
# the MPI tests skip). The sanitizer pass reuses the kernels PoCL compiled for
# the suite above from its cache (~/.cache/pocl): compiling them again under
# ASan would cost 1.7 times the CPU of the first compile (docs/bad-input.md).
CXX=clang++-15 cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=RelWithDebInfo -DWAVEPATH_SANITIZE=ON \
  -DWAVEPATH_BUILD_TESTS=ON -DWAVEPATH_BUILD_BENCH=OFF -DWAVEPATH_MPI=OFF
cmake --build build-asan -j "$(nproc)"
ctest --test-dir build-asan --output-on-failure -j "$(nproc)" \
  -E '^(sources_are_clang_formatted|mitsuba_scene_converter|robustness_figures_match_the_doc|wavepath_agrees_with_mitsuba)$'
