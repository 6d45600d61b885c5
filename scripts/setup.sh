#!/usr/bin/env bash
# Installs what wavepath needs on Debian 12 (idempotent) and builds it in build/.
# Usage: bash scripts/setup.sh [render|test|--list-packages]
#   render           the renderer alone: its packages, then the wavepath binary
#                    (and wavepath-import beside it, the mesh import helper it starts)
#   test (default)   also the test suite and the benchmark: every package, every target
#   --list-packages  print the Debian packages of `test` (what tests/packages checks against)
set -euo pipefail
cd "$(dirname "$0")/.."

# What building and running the renderer needs (assimp reads mesh files, and
# its CMake config names libz.so without libassimp-dev depending on
# zlib1g-dev; tinyobjloader parses OBJ files for it; glmark2-data ships the bunny that scenes/meshes/bunny.obj links to;
# Open MPI for `mpirun -n N wavepath render`, the WAVEPATH_MPI component, which
# the build leaves out where MPI is not found; pugixml reads Mitsuba 3 XML
# scenes, the XML library Mitsuba itself uses, and zlib inflates their
# `serialized` meshes).
RENDER_PACKAGES=(
  build-essential cmake pkg-config
  ocl-icd-opencl-dev opencl-headers opencl-clhpp-headers pocl-opencl-icd
  libglm-dev libopenimageio-dev nlohmann-json3-dev libcli11-dev
  libembree-dev libassimp-dev libtinyobjloader-dev zlib1g-dev libpugixml-dev glmark2-data
  openmpi-bin libopenmpi-dev
)
# What the tests and the benchmark add: GoogleTest (whose CMake config also
# loads GoogleMock's), clang-format for the format check, python3-pip for the
# benchmark's plots and for Mitsuba, libllvm19 for Mitsuba's llvm_ad_rgb
# variant (the oracle test and the benchmark's peer row; Dr.Jit finds it
# through DRJIT_LIBLLVM_PATH, and crashes with Debian's default LLVM 15),
# clang-15 and libFuzzer for the sanitizer build and its fuzzers
# (scripts/test.sh, docs/bad-input.md).
TEST_PACKAGES=(libgtest-dev libgmock-dev clang-format python3 python3-pip libllvm19 clang-15 libfuzzer-15-dev)

mode=${1:-test}
case "$mode" in
  render) packages=("${RENDER_PACKAGES[@]}") ;;
  test) packages=("${RENDER_PACKAGES[@]}" "${TEST_PACKAGES[@]}") ;;
  --list-packages) printf '%s\n' "${RENDER_PACKAGES[@]}" "${TEST_PACKAGES[@]}"; exit 0 ;;
  *) echo "setup: unknown mode '$mode' (render, test or --list-packages)" >&2; exit 2 ;;
esac

missing=()
for package in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed" || missing+=("$package")
done
if ((${#missing[@]})); then
  echo "setup: installing ${missing[*]}" >&2
  SUDO=()
  if [[ $(id -u) -ne 0 ]]; then
    command -v sudo >/dev/null || { echo "setup: need root (or sudo) to install: ${missing[*]}" >&2; exit 1; }
    SUDO=(sudo)
  fi
  "${SUDO[@]}" apt-get update
  DEBIAN_FRONTEND=noninteractive "${SUDO[@]}" apt-get install -y "${missing[@]}"
fi

# scenes/meshes/bunny.obj: a link to glmark2-data's Stanford bunny, so that
# scenes name it relative to themselves and never by its absolute path.
mkdir -p scenes/meshes
ln -sfn /usr/share/glmark2/models/bunny.obj scenes/meshes/bunny.obj

if [[ $mode == render ]]; then
  cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DWAVEPATH_BUILD_TESTS=OFF -DWAVEPATH_BUILD_BENCH=OFF
  cmake --build build -j "$(nproc)" --target wavepath
  exit 0
fi

# pip3 install, also where Debian marks the system Python as externally managed.
pip_install() {
  pip3 install --quiet "$@" 2>/dev/null || pip3 install --quiet --break-system-packages "$@"
}

# matplotlib for bench/run.py's plots (the benchmark runs without it, plots left out).
if ! python3 -c "import matplotlib" 2>/dev/null; then
  pip_install -r bench/requirements.txt || echo "setup: could not install matplotlib; bench/run.py will skip its plots" >&2
fi

# Mitsuba 3, the independent renderer of tests/oracle and the benchmark's peer
# (rendering never needs it). Pinned: the converter (scripts/mitsuba_scene.py)
# and the measured figures are for this version.
MITSUBA_VERSION=3.9.1
if [[ $(python3 -c "import mitsuba; print(mitsuba.__version__)" 2>/dev/null) != "$MITSUBA_VERSION" ]]; then
  pip_install "mitsuba==$MITSUBA_VERSION"
fi

cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DWAVEPATH_BUILD_TESTS=ON -DWAVEPATH_BUILD_BENCH=ON
cmake --build build -j "$(nproc)"
