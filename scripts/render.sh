#!/usr/bin/env bash
# Sets up, builds, and renders the default scene to out/room.png.
# Usage: bash scripts/render.sh [extra wavepath render flags]
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
mkdir -p out
./build/wavepath render scenes/room.json -o out/room.png "$@"
echo "wrote $(pwd)/out/room.png"
