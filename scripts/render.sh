#!/usr/bin/env bash
# Installs what rendering needs, builds the wavepath binary and its mesh import
# helper wavepath-import (not the tests),
# and renders the default scene to out/room.png.
# Usage: bash scripts/render.sh [extra wavepath render flags]
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh render
mkdir -p out
./build/wavepath render scenes/room.json -o out/room.png "$@"
echo "render.sh: the image is $(pwd)/out/room.png"
