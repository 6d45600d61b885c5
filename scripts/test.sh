#!/usr/bin/env bash
# Sets up, builds, and runs the whole test suite through CTest; then builds
# part of it again with AddressSanitizer and UndefinedBehaviorSanitizer
# (clang, in build-asan, with the libFuzzer targets) and runs it with the
# fuzzers' short runs. The whole suite under the sanitizers passes too, but
# building all of it there took the script to 2021 s on 2 cores (a939766),
# past the suite's 1800: it runs by hand (docs/bad-input.md, "The sanitizer
# build": the commands, the last run and where the time goes).
# Usage: bash scripts/test.sh
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
ctest --test-dir build --output-on-failure -j "$(nproc)"

SANITIZED=(test_scene test_shared test_image test_megakernel test_reference test_accel test_opencl fuzz_scene fuzz_mesh fuzz_film)
# Without MPI (none of these programs uses it): CI also builds wavepath without its optional component.
CXX=clang++-15 cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=RelWithDebInfo -DWAVEPATH_SANITIZE=ON \
  -DWAVEPATH_BUILD_TESTS=ON -DWAVEPATH_BUILD_BENCH=OFF -DWAVEPATH_MPI=OFF
cmake --build build-asan -j "$(nproc)" --target "${SANITIZED[@]}"
ctest --test-dir build-asan --output-on-failure -j "$(nproc)" \
  -R '^(test_scene|test_shared|test_image|test_megakernel|test_reference|test_accel|test_opencl|fuzz_scene_short|fuzz_mesh_short|fuzz_film_short)$'
