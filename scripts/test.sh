#!/usr/bin/env bash
# Sets up, builds, and runs the whole test suite through CTest; then builds
# it again with AddressSanitizer and UndefinedBehaviorSanitizer (clang, in
# build-asan, with the libFuzzer targets) and runs it once more, the fuzzers'
# short runs included (docs/bad-input.md).
# Usage: bash scripts/test.sh
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
ctest --test-dir build --output-on-failure -j "$(nproc)"

CXX=clang++-15 cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=RelWithDebInfo -DWAVEPATH_SANITIZE=ON \
  -DWAVEPATH_BUILD_TESTS=ON -DWAVEPATH_BUILD_BENCH=OFF
cmake --build build-asan -j "$(nproc)"
ctest --test-dir build-asan --output-on-failure -j "$(nproc)"
