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
# Side by side: the reference (the points as splats), then every level of the LOD set with its
# primitive count, all from the same camera; then the fidelity of the coarsest level.
render=build/bin/qf-render
$render samples/octahedron.ply -o "$out/reference.png" --size 256
oiiotool "$out/reference.png" --text:x=8:y=20:size=16:font=DejaVuSans "reference: 16000 points" -o "$out/reference.png"
frames=("$out/reference.png")
while read -r file primitives; do
  png="$out/octahedron/${file%.glb}.png"
  $render "$out/octahedron/$file" -o "$png" --size 256 --frame samples/octahedron.ply
  oiiotool "$png" --text:x=8:y=20:size=16:font=DejaVuSans "${file%.glb}: $primitives quads" -o "$png"
  frames+=("$png")
done < <(python3 -c 'import json,sys; [print(l["file"], l["primitives"]) for l in json.load(open(sys.argv[1]))["levels"]]' "$out/octahedron/manifest.json")
oiiotool "${frames[@]}" --mosaic "${#frames[@]}x1" -o "$out/side_by_side.png"
coarsest=$(ls "$out"/octahedron/*.glb | tail -1)
$render eval samples/octahedron.ply "$coarsest" --size 128 -o "$out/eval.json"
set +x
echo "demo: reference and every level side by side in $out/side_by_side.png; fidelity of $coarsest in $out/eval.json"
