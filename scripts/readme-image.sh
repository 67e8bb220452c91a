#!/usr/bin/env bash
# The README's picture, docs/img/tree-levels.png: the generated tree (qf-bake generate tree) and the
# four impostor levels of its default bake, each drawn by qf-render's engine method (as a glTF
# engine draws it) at 192 px from the same camera, labelled, side by side.
# usage: scripts/readme-image.sh   (after scripts/build.sh; needs oiiotool and an EGL driver)
set -euo pipefail
cd "$(dirname "$0")/.."
bin=build/bin out=docs/img/tree-levels.png
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$bin/qf-bake" generate tree -o "$work/tree.glb" -q
"$bin/qf-bake" "$work/tree.glb" -o "$work/tree" --no-cache --mesh-lods none --no-report-html -q
draw() {  # FILE LINE1 LINE2 PNG
  "$bin/qf-render" "$1" -o "$4" --size 192 --method engine --background 255,255,255 --frame "$work/tree.glb"
  oiiotool "$4" --text:x=6:y=16:size=14:color=0,0,0:font=DejaVuSans "$2" \
    --text:x=6:y=32:size=14:color=0,0,0:font=DejaVuSans "$3" -o "$4"
}
kb() { echo "$(( ($(stat -c %s "$1") + 512) / 1024 )) KB"; }
triangles=$("$bin/qf-bake" info --json "$work/tree.glb" | python3 -c 'import json, sys; print(json.load(sys.stdin)["triangles"])')
draw "$work/tree.glb" "input tree.glb" "$triangles triangles, $(kb "$work/tree.glb")" "$work/0.png"
frames=("$work/0.png")
while read -r file primitives; do
  draw "$work/tree/$file" "$file" "$primitives quads, $(kb "$work/tree/$file")" "$work/$file.png"
  frames+=("$work/$file.png")
done < <(python3 -c 'import json, sys
for l in json.load(open(sys.argv[1]))["levels"]: print(l["file"], l["primitives"])' "$work/tree/manifest.json")
mkdir -p "$(dirname "$out")"
oiiotool "${frames[@]}" --mosaic "${#frames[@]}x1" -d uint8 -o "$out"
echo "$out: $(stat -c %s "$out") bytes"
