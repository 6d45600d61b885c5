#!/usr/bin/env bash
# Installs wavepath's Debian 12 packages (idempotent) and builds it in build/.
# Usage: bash scripts/setup.sh
set -euo pipefail
cd "$(dirname "$0")/.."

PACKAGES=(
  build-essential cmake pkg-config
  ocl-icd-opencl-dev opencl-headers opencl-clhpp-headers pocl-opencl-icd clinfo
  libglm-dev libopenimageio-dev nlohmann-json3-dev libcli11-dev libtinyobjloader-dev
  libgtest-dev libbenchmark-dev python3 python3-pip
)

missing=()
for package in "${PACKAGES[@]}"; do
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

# matplotlib for bench/run.py's plots (the benchmark runs without it, plots left out).
if ! python3 -c "import matplotlib" 2>/dev/null; then
  pip3 install --quiet -r bench/requirements.txt 2>/dev/null ||
    pip3 install --quiet --break-system-packages -r bench/requirements.txt ||
    echo "setup: could not install matplotlib; bench/run.py will skip its plots" >&2
fi

cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
cmake --build build -j "$(nproc)"
