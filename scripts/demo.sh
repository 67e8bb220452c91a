#!/usr/bin/env bash
# The main job on the bundled sample, on a fresh Debian 12 machine: installs what is needed,
# builds, and bakes the coloured octahedron into impostor levels (.glb), then checks every level
# with the Khronos glTF-Validator. Outputs go to build/demo/.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
scripts/build.sh >/dev/null
out=build/demo
mkdir -p "$out"
bake=build/bin/qf-bake
set -x
$bake info samples/octahedron.ply
$bake samples/octahedron.ply -o "$out/octahedron" --cache "$out/cache"
cat "$out/octahedron/manifest.json"
node scripts/validate-gltf/validate.js "$out"/octahedron/*.glb
