#!/usr/bin/env bash
# The main job on the bundled sample, on a fresh Debian 12 machine: installs what is needed,
# builds, and bakes the coloured octahedron into impostor levels (.glb), then checks every level
# with the Khronos glTF-Validator, renders the reference and every level side by side, and measures
# the coarsest level's fidelity. Prints one line per step and, at the end, the paths it made; what
# the tools print goes to build/demo/demo.log. Outputs go to build/demo/.
set -euo pipefail
cd "$(dirname "$0")/.."
out=build/demo
log=$out/demo.log
mkdir -p "$out"
: >"$log"
bake=build/bin/qf-bake
render=build/bin/qf-render
sample=samples/octahedron.ply
# run CMD...: runs CMD with its output appended to the log; on failure shows the log's end and stops.
run() {
  { printf '+'; printf ' %q' "$@"; echo; } >>"$log"
  "$@" >>"$log" 2>&1 && return
  echo "demo: failed: $*" >&2
  echo "demo: the last lines of $log:" >&2
  tail -n 20 "$log" >&2
  exit 1
}
json() { python3 -c "import json, sys; d = json.load(open(sys.argv[1])); $2" "$1"; }

echo "demo: installing what is missing and building (scripts/install-deps.sh, scripts/build.sh)"
run scripts/install-deps.sh
run scripts/build.sh

run "$bake" info "$sample"
points=$("$bake" info --json "$sample" | python3 -c 'import json, sys; print(json.load(sys.stdin)["points"])')
echo "demo: baking $sample ($points points) into $out/octahedron/"
run "$bake" "$sample" -o "$out/octahedron" --cache "$out/cache"
manifest=$out/octahedron/manifest.json
echo "demo:   levels: $(json "$manifest" 'print(", ".join("%s %d quads" % (l["file"], l["primitives"]) for l in d["levels"]))')"

run node scripts/validate-gltf/validate.js "$out"/octahedron/*.glb
echo "demo: glTF-Validator: every level has 0 errors and 0 warnings"

# Side by side: the reference (the points as splats), then every level of the LOD set with its
# primitive count, all from the same camera.
echo "demo: rendering the reference and every level (256 px) side by side"
run "$render" "$sample" -o "$out/reference.png" --size 256
run oiiotool "$out/reference.png" --text:x=8:y=20:size=16:font=DejaVuSans "reference: $points points" -o "$out/reference.png"
frames=("$out/reference.png")
while read -r file primitives; do
  png="$out/octahedron/${file%.glb}.png"
  run "$render" "$out/octahedron/$file" -o "$png" --size 256 --frame "$sample"
  run oiiotool "$png" --text:x=8:y=20:size=16:font=DejaVuSans "${file%.glb}: $primitives quads" -o "$png"
  frames+=("$png")
done < <(json "$manifest" '[print(l["file"], l["primitives"]) for l in d["levels"]]')
run oiiotool "${frames[@]}" --mosaic "${#frames[@]}x1" -o "$out/side_by_side.png"

# The fidelity of the coarsest level (fewest primitives) against the reference.
coarsest=$out/octahedron/$(json "$manifest" 'print(min(d["levels"], key=lambda l: l["primitives"])["file"])')
echo "demo: measuring the fidelity of $(basename "$coarsest") against the reference (128 px)"
run "$render" eval "$sample" "$coarsest" --size 128 -o "$out/eval.json"
echo "demo:   $(json "$out/eval.json" 'm = d["mean"]["overlap"]; print("%d views: PSNR %.1f dB, IoU %.3f, holes %.1f%%" % (d["views"], m["psnr"], m["iou"], 100 * m["holes"]))')"

# A textured game asset: the generated tree (alpha-masked leaves), its impostor levels, and
# meshoptimizer's simplify at the coarsest level's budget (two triangles per quad), drawn as an
# engine draws glTF.
echo "demo: generating the sample tree, baking it into $out/tree/, and simplify at the same budget"
run "$bake" generate tree -o "$out/tree.glb"
run "$bake" "$out/tree.glb" -o "$out/tree" --cache "$out/cache" --mesh-lods none
run "$render" "$out/tree.glb" -o "$out/tree/reference.png" --size 256 --method engine
run oiiotool "$out/tree/reference.png" --text:x=8:y=20:size=16:font=DejaVuSans "tree: 3000 leaves" -o "$out/tree/reference.png"
tree_frames=("$out/tree/reference.png")
while read -r file primitives; do
  png="$out/tree/${file%.glb}.png"
  run "$render" "$out/tree/$file" -o "$png" --size 256 --method engine --frame "$out/tree.glb"
  run oiiotool "$png" --text:x=8:y=20:size=16:font=DejaVuSans "${file%.glb}: $primitives quads" -o "$png"
  tree_frames+=("$png")
  last=$primitives
done < <(json "$out/tree/manifest.json" '[print(l["file"], l["primitives"]) for l in d["levels"]]')
run "$bake" simplify "$out/tree.glb" -o "$out/tree/simplify" --triangles $((2 * last))
run "$render" "$out/tree/simplify/tree_S0.glb" -o "$out/tree/simplify.png" --size 256 --method engine --frame "$out/tree.glb"
run oiiotool "$out/tree/simplify.png" --text:x=8:y=20:size=16:font=DejaVuSans "simplify: $((2 * last)) triangles" -o "$out/tree/simplify.png"
tree_frames+=("$out/tree/simplify.png")
run oiiotool "${tree_frames[@]}" --mosaic "${#tree_frames[@]}x1" -o "$out/tree_side_by_side.png"

echo "demo: made"
printf '  %-33s %s\n' \
  "$out/octahedron/" "the levels (.glb), manifest.json, report.json, a picture of each level (.png)" \
  "$out/side_by_side.png" "the reference and every level side by side" \
  "$out/eval.json" "the coarsest level's fidelity" \
  "$out/tree_side_by_side.png" "the generated tree, its levels and simplify at the coarsest budget" \
  "$log" "what the tools printed"
