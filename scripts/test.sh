#!/usr/bin/env bash
# Sets up, builds, and runs the whole test suite through CTest; then builds
# it again with AddressSanitizer and UndefinedBehaviorSanitizer (clang, in
# build-asan, a unity build, with the libFuzzer targets) and runs all of it
# there but seven checks that would add nothing: the format check, the
# Python-only converter test, a second run of test_robustness and the Mitsuba
# oracles (path tracing's with its sensitivity test, SPPM's and the XML reader's)
# (docs/bad-input.md, "The sanitizer build": why, and what it costs).
# Usage: bash scripts/test.sh
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
# setup installs Open MPI, so build/ has the MPI component: the CTest check
# mpi_is_found_where_setup_installs_it fails where CMake did not find MPI
# (the MPI tests would skip).
ctest --test-dir build --output-on-failure -j "$(nproc)"

# Without MPI: CI also builds wavepath without its optional component.
CXX=clang++-15 cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=RelWithDebInfo -DWAVEPATH_SANITIZE=ON \
  -DWAVEPATH_BUILD_TESTS=ON -DWAVEPATH_BUILD_BENCH=OFF -DWAVEPATH_MPI=OFF
cmake --build build-asan -j "$(nproc)"
ctest --test-dir build-asan --output-on-failure -j "$(nproc)" \
  -E '^(sources_are_clang_formatted|mitsuba_scene_converter|robustness_figures_match_the_doc|wavepath_agrees_with_mitsuba|mitsuba_oracle_fails_on_lights_3_percent_too_bright|sppm_agrees_with_mitsuba|wavepath_reads_mitsuba_xml_as_mitsuba_does)$'
