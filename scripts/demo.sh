#!/usr/bin/env bash
# The main job on the bundled sample, on a fresh Debian 12 machine: installs what is needed,
# builds, then describes the coloured octahedron and converts it to QSplat and back.
# Outputs go to build/demo/.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
scripts/build.sh >/dev/null
out=build/demo
mkdir -p "$out"
bake=build/bin/qf-bake
set -x
$bake info samples/octahedron.ply
$bake convert samples/octahedron.ply "$out/octahedron.qs"
$bake info "$out/octahedron.qs"
$bake convert "$out/octahedron.qs" "$out/octahedron-from-qs.ply"
